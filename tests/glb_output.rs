//! The glTF binary output, read back with the `gltf` crate (which validates the document
//! on import) and, for the container and extras, byte by byte.

use cloth::collide::TriSurface;
use cloth::formats::panels::PanelLabels;
use cloth::output::{write_glb, GlbCloth};
use cloth::{math::Vec3, ClothMesh, GridBuilder};
use nalgebra::Vector2;
use std::io::ErrorKind;
use std::path::{Path, PathBuf};

fn out_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name)
}

/// A 5 x 4 sheet stretched 10 % along the warp (x), lifted and tilted: every triangle's
/// strain is 10 %, beyond the colour scale's 5 %.
fn stretched_sheet() -> (ClothMesh, Vec<Vec3>) {
    let mesh = GridBuilder::new(5, 4).size(0.4, 0.3).build().expect("valid grid");
    let positions = mesh
        .positions()
        .iter()
        .map(|p| Vec3::new(1.1 * p.x - 0.2, p.y - 0.1, 0.5 + 0.1 * p.y))
        .collect();
    (mesh, positions)
}

/// Two square panels folded at a right angle and sewn along the edge 1-4: the seam
/// vertices 1 and 4 have material coordinates in both panels.
fn seamed_mesh() -> ClothMesh {
    let positions = vec![
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(0.1, 0.0, 0.0),
        Vec3::new(0.1, 0.1, 0.0),
        Vec3::new(0.0, 0.0, 0.1),
        Vec3::new(0.1, 0.0, 0.1),
        Vec3::new(0.1, 0.1, 0.1),
    ];
    let uv = |u, v| Vector2::new(u, v);
    let triangles = vec![[0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4]];
    let corner_uv = vec![
        [uv(0.0, 0.0), uv(0.1, 0.0), uv(0.1, 0.1)],
        [uv(0.0, 0.0), uv(0.1, 0.1), uv(0.0, 0.1)],
        [uv(0.2, 0.0), uv(0.3, 0.0), uv(0.3, 0.1)],
        [uv(0.2, 0.0), uv(0.3, 0.1), uv(0.2, 0.1)],
    ];
    let mesh = ClothMesh::with_corner_uv(positions, triangles, corner_uv).expect("valid seamed mesh");
    assert!(mesh.has_seams());
    mesh
}

fn ball() -> TriSurface {
    TriSurface::icosphere(0.1, 2).expect("valid icosphere")
}

/// glTF's y-up point back in our z-up world.
fn z_up(p: [f32; 3]) -> Vec3 {
    Vec3::new(p[0].into(), (-p[2]).into(), p[1].into())
}

/// `a` equals `b` rounded to f32 (half an ulp is 2^-24 relative; allow 2^-23).
fn assert_f32_close(a: Vec3, b: Vec3, what: &str) {
    for k in 0..3 {
        let tolerance = f64::from(f32::EPSILON) * b[k].abs();
        assert!((a[k] - b[k]).abs() <= tolerance, "{what}: {a:?} vs {b:?}");
    }
}

/// One mesh's attributes as read back, positions and normals in our z-up world.
struct ReadMesh {
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    uv: Vec<[f32; 2]>,
    colours: Vec<[f32; 3]>,
    triangles: Vec<[usize; 3]>,
    double_sided: bool,
    base_colour: [f32; 4],
}

fn read_glb(path: &Path) -> (gltf::Document, Vec<gltf::buffer::Data>) {
    let (doc, buffers, _) = gltf::import(path).expect("a valid glTF file");
    (doc, buffers)
}

fn read_mesh(doc: &gltf::Document, buffers: &[gltf::buffer::Data], name: &str) -> ReadMesh {
    let mesh = doc
        .meshes()
        .find(|m| m.name() == Some(name))
        .unwrap_or_else(|| panic!("no mesh named {name}"));
    let mut primitives = mesh.primitives();
    let primitive = primitives.next().expect("a primitive");
    assert!(primitives.next().is_none());
    assert_eq!(primitive.mode(), gltf::mesh::Mode::Triangles);
    let reader = primitive.reader(|b| buffers.get(b.index()).map(|d| &d[..]));
    let positions: Vec<Vec3> = reader.read_positions().expect("POSITION").map(z_up).collect();

    // POSITION's min and max, which the spec requires, bound the data exactly.
    let bounds = primitive.bounding_box();
    for k in 0..3 {
        let gl: Vec<f32> = reader.read_positions().expect("POSITION").map(|p| p[k]).collect();
        assert_eq!(bounds.min[k], gl.iter().copied().fold(f32::INFINITY, f32::min));
        assert_eq!(
            bounds.max[k],
            gl.iter().copied().fold(f32::NEG_INFINITY, f32::max)
        );
    }

    let indices: Vec<usize> = reader
        .read_indices()
        .expect("indices")
        .into_u32()
        .map(|i| i as usize)
        .collect();
    assert_eq!(indices.len() % 3, 0);
    let pbr = primitive.material().pbr_metallic_roughness();
    ReadMesh {
        normals: reader.read_normals().expect("NORMAL").map(z_up).collect(),
        uv: reader
            .read_tex_coords(0)
            .map(|t| t.into_f32().collect())
            .unwrap_or_default(),
        colours: reader
            .read_colors(0)
            .map(|c| c.into_rgb_f32().collect())
            .unwrap_or_default(),
        triangles: indices.chunks(3).map(|t| [t[0], t[1], t[2]]).collect(),
        double_sided: primitive.material().double_sided(),
        base_colour: pbr.base_color_factor(),
        positions,
    }
}

/// Every corner of every triangle is at its cloth vertex's position, with the corner's
/// material coordinates; normals are unit.
fn assert_cloth_matches(read: &ReadMesh, mesh: &ClothMesh, positions: &[Vec3]) {
    assert_eq!(read.triangles.len(), mesh.triangles().len());
    assert_eq!(read.uv.len(), read.positions.len());
    assert_eq!(read.colours.len(), read.positions.len());
    assert_eq!(read.normals.len(), read.positions.len());
    for (t, (gl, tri)) in read.triangles.iter().zip(mesh.triangles()).enumerate() {
        let corners = mesh.corner_uv(t);
        for k in 0..3 {
            let what = format!("triangle {t} corner {k}");
            assert_f32_close(read.positions[gl[k]], positions[tri[k]], &what);
            let uv = read.uv[gl[k]];
            assert_eq!(
                [uv[0], uv[1]],
                [corners[k].x as f32, corners[k].y as f32],
                "{what}"
            );
        }
    }
    for n in &read.normals {
        assert!((n.norm() - 1.0).abs() < 1e-5, "normal {n:?}");
    }
    assert!(read.double_sided);
    assert_eq!(read.base_colour, [1.0; 4]);
}

#[test]
fn cloth_and_bodies_read_back() {
    let (mesh, positions) = stretched_sheet();
    let bodies = vec![("ball".to_owned(), ball()), ("head".to_owned(), ball())];
    let path = out_path("cloth_and_bodies.glb");
    write_glb(
        &path,
        &GlbCloth {
            mesh: &mesh,
            positions: &positions,
            panels: None,
        },
        &bodies,
    )
    .expect("written");
    let (doc, buffers) = read_glb(&path);

    let names: Vec<_> = doc
        .nodes()
        .map(|n| (n.name(), n.mesh().and_then(|m| m.name())))
        .collect();
    assert_eq!(
        names,
        [
            (Some("cloth"), Some("cloth")),
            (Some("ball"), Some("ball")),
            (Some("head"), Some("head"))
        ]
    );
    let scene = doc.default_scene().expect("a default scene");
    assert_eq!(scene.nodes().count(), 3);

    let cloth = read_mesh(&doc, &buffers, "cloth");
    // A grid has no seams: one glTF vertex per cloth vertex.
    assert_eq!(cloth.positions.len(), mesh.vertex_count());
    assert_cloth_matches(&cloth, &mesh, &positions);
    // 10 % strain is beyond full scale: red everywhere.
    for c in &cloth.colours {
        assert_eq!(*c, [1.0, 0.0, 0.0]);
    }
    // The sheet faces up (+z) in our world: its normals point up or down, not sideways.
    for n in &cloth.normals {
        assert!(n.z.abs() > 0.99, "normal {n:?}");
    }

    let surface = ball();
    for name in ["ball", "head"] {
        let body = read_mesh(&doc, &buffers, name);
        assert_eq!(body.positions.len(), surface.vertices().len());
        for ((p, n), q) in body.positions.iter().zip(&body.normals).zip(surface.vertices()) {
            assert_f32_close(*p, *q, name);
            // On a sphere about the origin the smooth normal is close to the radius.
            assert!(n.dot(&q.normalize()) > 0.99, "{name} normal {n:?} at {q:?}");
        }
        let triangles: Vec<[usize; 3]> = surface
            .triangles()
            .iter()
            .map(|t| t.map(|i| i as usize))
            .collect();
        assert_eq!(body.triangles, triangles);
        assert!(body.uv.is_empty() && body.colours.is_empty());
        assert!(!body.double_sided);
        assert!(body.base_colour[0] < 1.0, "bodies are grey");
    }
}

#[test]
fn unstrained_sheet_alone_is_blue() {
    let mesh = GridBuilder::new(5, 4).size(0.4, 0.3).build().expect("valid grid");
    let path = out_path("sheet.glb");
    write_glb(
        &path,
        &GlbCloth {
            mesh: &mesh,
            positions: mesh.positions(),
            panels: None,
        },
        &[],
    )
    .expect("written");
    let (doc, buffers) = read_glb(&path);
    assert_eq!(doc.meshes().count(), 1);
    assert_eq!(doc.nodes().count(), 1);
    let cloth = read_mesh(&doc, &buffers, "cloth");
    assert_cloth_matches(&cloth, &mesh, mesh.positions());
    for c in &cloth.colours {
        assert_eq!(*c, [0.0, 0.0, 1.0]);
    }
}

#[test]
fn seam_vertices_keep_both_material_coordinates() {
    let mesh = seamed_mesh();
    let path = out_path("seamed.glb");
    write_glb(
        &path,
        &GlbCloth {
            mesh: &mesh,
            positions: mesh.positions(),
            panels: None,
        },
        &[("ball".into(), ball())],
    )
    .expect("written");
    let (doc, buffers) = read_glb(&path);
    let cloth = read_mesh(&doc, &buffers, "cloth");
    // Vertices 1 and 4 are split in two: 6 + 2.
    assert_eq!(cloth.positions.len(), 8);
    assert!(cloth.positions.len() > mesh.vertex_count());
    assert_cloth_matches(&cloth, &mesh, mesh.positions());
    // The halves of a seam vertex share one smooth normal, across the fold.
    let seam: Vec<usize> = (0..8)
        .filter(|&i| cloth.positions[i] == cloth.positions[1])
        .collect();
    assert_eq!(seam.len(), 2);
    assert_eq!(cloth.normals[seam[0]], cloth.normals[seam[1]]);
}

/// A garment's panels ride along: `_PANEL` on every glTF vertex (each one panel's, the seam
/// vertices split), their names in the extras.
#[test]
fn panels_are_a_vertex_attribute_with_their_names() {
    let mesh = seamed_mesh();
    let panels = PanelLabels::new(vec!["left".into(), "right".into()], vec![0, 0, 1, 1]).expect("labels");
    let path = out_path("panels.glb");
    write_glb(
        &path,
        &GlbCloth {
            mesh: &mesh,
            positions: mesh.positions(),
            panels: Some(&panels),
        },
        &[],
    )
    .expect("written");
    let (doc, buffers) = read_glb(&path);
    let node = doc
        .nodes()
        .find(|n| n.name() == Some("cloth"))
        .expect("the cloth");
    let extras: serde_json::Value =
        serde_json::from_str(node.extras().as_ref().expect("extras").get()).expect("json");
    assert_eq!(extras["panels"], serde_json::json!(["left", "right"]));
    let primitive = node
        .mesh()
        .expect("a mesh")
        .primitives()
        .next()
        .expect("a primitive");
    let (_, accessor) = primitive
        .attributes()
        .find(|(s, _)| *s == gltf::Semantic::Extras("PANEL".into()))
        .expect("a _PANEL attribute");
    let view = accessor.view().expect("a buffer view");
    let bytes = &buffers[0][view.offset()..view.offset() + view.length()];
    let labels: Vec<f32> = bytes
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes(b.try_into().expect("4 bytes")))
        .collect();
    let positions: Vec<Vec3> = primitive
        .reader(|b| buffers.get(b.index()).map(|d| &d[..]))
        .read_positions()
        .expect("POSITION")
        .map(z_up)
        .collect();
    assert_eq!(labels.len(), positions.len());
    // The left panel is the square at y = 0 (x from 0 to 0.1, z from 0 to 0.1) and the
    // right one the square at x = 0.1; the seam (x = 0.1, y = 0) is in both, once each.
    for (p, &label) in positions.iter().zip(&labels) {
        let on_seam = (p.x - 0.1).abs() < 1e-6 && p.y.abs() < 1e-6;
        let expected = if p.y.abs() < 1e-6 && !on_seam { 0.0 } else { 1.0 };
        if !on_seam {
            assert_eq!(label, expected, "vertex at {p:?}");
        }
    }
    let seam: Vec<f32> = positions
        .iter()
        .zip(&labels)
        .filter(|(p, _)| (p.x - 0.1).abs() < 1e-6 && p.y.abs() < 1e-6)
        .map(|(_, &l)| l)
        .collect();
    assert_eq!(seam.len(), 4, "two seam vertices, split in two");
    assert_eq!(seam.iter().filter(|&&l| l == 0.0).count(), 2);
}

fn u32_at(bytes: &[u8], at: usize) -> usize {
    u32::from_le_bytes(bytes[at..at + 4].try_into().expect("4 bytes")) as usize
}

#[test]
fn glb_framing_and_extras() {
    let (mesh, positions) = stretched_sheet();
    let path = out_path("framing.glb");
    write_glb(
        &path,
        &GlbCloth {
            mesh: &mesh,
            positions: &positions,
            panels: None,
        },
        &[("ball".into(), ball())],
    )
    .expect("written");
    let bytes = std::fs::read(&path).expect("readable");

    assert_eq!(&bytes[0..4], b"glTF");
    assert_eq!(u32_at(&bytes, 4), 2);
    assert_eq!(u32_at(&bytes, 8), bytes.len());
    let mut chunks = Vec::new();
    let mut at = 12;
    while at < bytes.len() {
        let length = u32_at(&bytes, at);
        assert_eq!(length % 4, 0, "chunk at {at}");
        chunks.push((&bytes[at + 4..at + 8], &bytes[at + 8..at + 8 + length]));
        at += 8 + length;
    }
    assert_eq!(at, bytes.len());
    let [(b"JSON", json), (b"BIN\0", bin)] = chunks[..] else {
        panic!("expected a JSON and a BIN chunk");
    };

    let json: serde_json::Value = serde_json::from_slice(json).expect("JSON chunk parses");
    assert_eq!(json["asset"]["version"], "2.0");
    let generator = json["asset"]["generator"].as_str().expect("a generator");
    assert!(generator.starts_with("cloth "), "{generator}");
    let cloth = json["nodes"]
        .as_array()
        .expect("nodes")
        .iter()
        .find(|n| n["name"] == "cloth")
        .expect("a cloth node");
    assert_eq!(cloth["extras"]["strain_full_scale_percent"], 5.0);

    // The one buffer is the BIN chunk; every view lies in it, 4-byte aligned.
    assert_eq!(json["buffers"].as_array().map(Vec::len), Some(1));
    let buffer_length = json["buffers"][0]["byteLength"].as_u64().expect("byteLength") as usize;
    assert!(buffer_length <= bin.len() && bin.len() < buffer_length + 4);
    for view in json["bufferViews"].as_array().expect("views") {
        let offset = view["byteOffset"].as_u64().unwrap_or(0) as usize;
        let length = view["byteLength"].as_u64().expect("byteLength") as usize;
        assert_eq!(offset % 4, 0);
        assert!(offset + length <= buffer_length);
    }
}

#[test]
fn non_finite_or_mismatched_positions_are_errors() {
    let (mesh, positions) = stretched_sheet();
    let path = out_path("broken.glb");
    let _ = std::fs::remove_file(&path);
    // 1e300 is finite in f64 but not in the file's f32.
    for bad in [f64::NAN, f64::INFINITY, 1e300] {
        let mut broken = positions.clone();
        broken[7].y = bad;
        let error = write_glb(
            &path,
            &GlbCloth {
                mesh: &mesh,
                positions: &broken,
                panels: None,
            },
            &[],
        )
        .expect_err("non-finite position");
        assert_eq!(error.kind(), ErrorKind::InvalidData);
        assert!(error.to_string().contains("cloth vertex 7 "), "{error}");
        assert!(!path.exists(), "nothing is written");
    }
    let error = write_glb(
        &path,
        &GlbCloth {
            mesh: &mesh,
            positions: &positions[1..],
            panels: None,
        },
        &[],
    )
    .expect_err("too few positions");
    assert_eq!(error.kind(), ErrorKind::InvalidInput);
    assert!(!path.exists());
}
