//! glTF 2.0 binary (.glb) of the bodies and the draped cloth, for any 3D viewer.
//!
//! glTF is y-up and our world is z-up, so every position and normal is rotated
//! `(x, y, z) -> (x, z, -y)` (a quarter turn about x: lengths and winding are kept, in
//! metres) and the model stands upright in a viewer; read `(X, Y, Z)` back as `(X, -Z, Y)`.
//!
//! The cloth has one glTF vertex per distinct (vertex, material coordinate) of its triangle
//! corners, so the seam vertices of a sewn garment keep each panel's material coordinates
//! in `TEXCOORD_0` (metres). `COLOR_0` is the strain colour of the PLY: per vertex the mean
//! over its triangles of the larger of warp and weft strain, compression as 0; its full
//! scale is in the cloth node's `extras`. A garment's vertices carry their panel in `_PANEL`
//! (a float attribute, the panel's number; each glTF vertex is one panel's), and the
//! panels' names are in the extras.

use cloth_collide::TriSurface;
use cloth_core::{math::Vec3, ClothMesh};
use cloth_formats::atomic::write_atomically;
use cloth_formats::gltf::{vertex_normals, y_up, ClothVertices, GlbDocument, GlbMaterial, GlbMesh};
use cloth_formats::panels::PanelLabels;
use cloth_render::strain_colours::{strain_colour, vertex_strain, FULL_SCALE_PERCENT};
use serde_json::json;
use std::io::{Error, ErrorKind};
use std::path::Path;

/// The draped cloth: its mesh and the positions of its vertices, m, and a garment's
/// panels.
#[derive(Debug, Clone, Copy)]
pub struct GlbCloth<'a> {
    pub mesh: &'a ClothMesh,
    pub positions: &'a [Vec3],
    pub panels: Option<&'a PanelLabels>,
}

/// Writes `cloth` (named "cloth") and `bodies` (named by their names) as a .glb file.
/// Non-finite positions, or positions that do not match the mesh, are `InvalidData` /
/// `InvalidInput` errors and nothing is written.
pub fn write_glb(path: &Path, cloth: &GlbCloth<'_>, bodies: &[(String, TriSurface)]) -> std::io::Result<()> {
    let glb = glb_bytes(cloth, bodies)?;
    write_atomically(path, |out| out.write_all(&glb))
}

fn glb_bytes(cloth: &GlbCloth<'_>, bodies: &[(String, TriSurface)]) -> std::io::Result<Vec<u8>> {
    let mut doc = GlbDocument::new(format!("cloth {}", env!("CARGO_PKG_VERSION")));
    // The cloth's colour is its vertex colours (times white); seen from both sides, as
    // an open sheet is.
    let cloth_material = doc.add_material(GlbMaterial {
        name: "cloth".into(),
        base_colour: [1.0; 4],
        roughness: 0.9,
        double_sided: true,
    });
    let mesh = cloth.mesh;
    if cloth.positions.len() != mesh.vertex_count() {
        return Err(Error::new(
            ErrorKind::InvalidInput,
            format!(
                "the cloth has {} positions for {} vertices",
                cloth.positions.len(),
                mesh.vertex_count()
            ),
        ));
    }
    let positions = y_up(cloth.positions, "cloth")?;
    let normals = vertex_normals(cloth.positions, mesh.triangles().iter().copied());
    let strain = vertex_colours(mesh, cloth.positions);
    let split = ClothVertices::new(mesh)?;
    let mut extras = json!({
        "strain_full_scale_percent": FULL_SCALE_PERCENT,
        "COLOR_0": "strain: mean over the vertex's triangles of max(warp, weft, 0) %, \
                    blue at 0 through cyan, green, yellow to red at full scale",
        "TEXCOORD_0": "material coordinates (u along the warp, v along the weft), m",
    });
    let panel_of: Vec<f32>;
    let mut scalars: Vec<(&str, &[f32])> = Vec::new();
    if let Some(panels) = cloth.panels {
        panel_of = split.panel_attribute(panels);
        scalars.push(("_PANEL", &panel_of));
        extras["_PANEL"] = json!("the vertex's panel: an index into `panels`");
        extras["panels"] = json!(panels.names());
    }
    doc.add_mesh(GlbMesh {
        name: "cloth",
        positions: &split.gather(&positions),
        normals: &split.gather(&normals),
        texcoords: Some(split.uv()),
        colours: Some(&split.gather(&strain)),
        scalars: &scalars,
        targets: &[],
        indices: split.indices(),
        material: cloth_material,
        extras: Some(extras),
    })?;
    if !bodies.is_empty() {
        let grey = doc.add_material(GlbMaterial {
            name: "body".into(),
            base_colour: [0.6, 0.6, 0.6, 1.0],
            roughness: 0.6,
            double_sided: false,
        });
        for (name, surface) in bodies {
            let positions = y_up(surface.vertices(), &format!("body `{name}`"))?;
            let triangles = surface.triangles().iter().map(|t| t.map(|i| i as usize));
            let indices: Vec<u32> = surface.triangles().iter().flatten().copied().collect();
            doc.add_mesh(GlbMesh {
                name,
                positions: &positions,
                normals: &vertex_normals(surface.vertices(), triangles),
                texcoords: None,
                colours: None,
                scalars: &[],
                targets: &[],
                indices: &indices,
                material: grey,
                extras: None,
            })?;
        }
    }
    doc.into_bytes()
}

/// Each vertex's strain colour as the PLY has it, in linear RGB: glTF vertex colours are
/// linear, and the viewer's sRGB output then shows the PLY's sRGB colours.
fn vertex_colours(mesh: &ClothMesh, positions: &[Vec3]) -> Vec<[f32; 3]> {
    let linear = |c: u8| {
        let c = f32::from(c) / 255.0;
        if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    };
    vertex_strain(mesh, positions)
        .iter()
        .map(|&s| strain_colour(s).map(linear))
        .collect()
}
