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
//! scale is in the cloth node's `extras`.

use cloth_collide::TriSurface;
use cloth_core::{math::Vec3, ClothMesh};
use cloth_formats::atomic::write_atomically;
use cloth_render::strain_colours::{strain_colour, vertex_strain, FULL_SCALE_PERCENT};
use gltf_json::accessor::{ComponentType, GenericComponentType, Type};
use gltf_json::buffer::Target;
use gltf_json::material::{PbrBaseColorFactor, PbrMetallicRoughness, StrengthFactor};
use gltf_json::mesh::{Mode, Primitive, Semantic};
use gltf_json::validation::{Checked::Valid, USize64};
use gltf_json::{Accessor, Index};
use serde_json::json;
use std::collections::{BTreeMap, HashMap};
use std::io::{Error, ErrorKind};
use std::path::Path;

/// The draped cloth: its mesh and the positions of its vertices, m.
#[derive(Debug, Clone, Copy)]
pub struct GlbCloth<'a> {
    pub mesh: &'a ClothMesh,
    pub positions: &'a [Vec3],
}

/// Writes `cloth` (named "cloth") and `bodies` (named by their names) as a .glb file.
/// Non-finite positions, or positions that do not match the mesh, are `InvalidData` /
/// `InvalidInput` errors and nothing is written.
pub fn write_glb(path: &Path, cloth: &GlbCloth<'_>, bodies: &[(String, TriSurface)]) -> std::io::Result<()> {
    let glb = glb_bytes(cloth, bodies)?;
    write_atomically(path, |out| out.write_all(&glb))
}

fn glb_bytes(cloth: &GlbCloth<'_>, bodies: &[(String, TriSurface)]) -> std::io::Result<Vec<u8>> {
    let mut doc = Document::default();
    doc.root.asset.generator = Some(format!("cloth {}", env!("CARGO_PKG_VERSION")));

    // The cloth's colour is its vertex colours (times white); seen from both sides, as
    // an open sheet is.
    let cloth_material = doc.add_material("cloth", [1.0; 4], 0.9, true);
    doc.add_cloth(cloth, cloth_material)?;
    if !bodies.is_empty() {
        let grey = doc.add_material("body", [0.6, 0.6, 0.6, 1.0], 0.6, false);
        for (name, surface) in bodies {
            doc.add_body(name, surface, grey)?;
        }
    }
    doc.finish()
}

/// A glTF document being built: the JSON root, the binary buffer, and the names of its
/// nodes (node `i` shows mesh `i`, both named `names[i]`) and materials.
#[derive(Default)]
struct Document {
    root: gltf_json::Root,
    bin: Vec<u8>,
    names: Vec<String>,
    material_names: Vec<&'static str>,
}

impl Document {
    fn add_material(
        &mut self,
        name: &'static str,
        base_colour: [f32; 4],
        roughness: f32,
        double_sided: bool,
    ) -> Index<gltf_json::Material> {
        self.material_names.push(name);
        self.root.push(gltf_json::Material {
            pbr_metallic_roughness: PbrMetallicRoughness {
                base_color_factor: PbrBaseColorFactor(base_colour),
                metallic_factor: StrengthFactor(0.0),
                roughness_factor: StrengthFactor(roughness),
                ..Default::default()
            },
            double_sided,
            ..Default::default()
        })
    }

    fn add_cloth(
        &mut self,
        cloth: &GlbCloth<'_>,
        material: Index<gltf_json::Material>,
    ) -> std::io::Result<()> {
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

        let split = Split::new(mesh)?;
        let per_split =
            |values: &[[f32; 3]]| -> Vec<[f32; 3]> { split.source.iter().map(|&v| values[v]).collect() };
        let attributes = [
            (Semantic::Positions, self.vec3(&per_split(&positions), true)),
            (Semantic::Normals, self.vec3(&per_split(&normals), false)),
            (Semantic::TexCoords(0), self.vec2(&split.uv)),
            (Semantic::Colors(0), self.vec3(&per_split(&strain), false)),
        ];
        let indices = self.indices(&split.indices);
        self.add_mesh_node("cloth", attributes, indices, material);
        Ok(())
    }

    fn add_body(
        &mut self,
        name: &str,
        surface: &TriSurface,
        material: Index<gltf_json::Material>,
    ) -> std::io::Result<()> {
        let positions = y_up(surface.vertices(), &format!("body `{name}`"))?;
        let triangles = surface.triangles().iter().map(|t| t.map(|i| i as usize));
        let normals = vertex_normals(surface.vertices(), triangles);
        let attributes = [
            (Semantic::Positions, self.vec3(&positions, true)),
            (Semantic::Normals, self.vec3(&normals, false)),
        ];
        let indices: Vec<u32> = surface.triangles().iter().flatten().copied().collect();
        let indices = self.indices(&indices);
        self.add_mesh_node(name, attributes, indices, material);
        Ok(())
    }

    fn add_mesh_node<const N: usize>(
        &mut self,
        name: &str,
        attributes: [(Semantic, Index<Accessor>); N],
        indices: Index<Accessor>,
        material: Index<gltf_json::Material>,
    ) {
        let primitive = Primitive {
            attributes: attributes
                .into_iter()
                .map(|(s, a)| (Valid(s), a))
                .collect::<BTreeMap<_, _>>(),
            extensions: None,
            extras: Default::default(),
            indices: Some(indices),
            material: Some(material),
            mode: Valid(Mode::Triangles),
            targets: None,
        };
        let mesh = self.root.push(gltf_json::Mesh {
            primitives: vec![primitive],
            ..blank(json!({ "primitives": [] }))
        });
        self.root.push(gltf_json::Node {
            mesh: Some(mesh),
            ..Default::default()
        });
        self.names.push(name.to_owned());
    }

    /// A VEC3 float attribute; `bounds` adds the min and max that POSITION must have.
    fn vec3(&mut self, values: &[[f32; 3]], bounds: bool) -> Index<Accessor> {
        let (mut min, mut max) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
        let start = self.bin.len();
        for v in values {
            for k in 0..3 {
                min[k] = min[k].min(v[k]);
                max[k] = max[k].max(v[k]);
                self.bin.extend(v[k].to_le_bytes());
            }
        }
        let accessor = self.accessor(
            start,
            values.len(),
            ComponentType::F32,
            Type::Vec3,
            Target::ArrayBuffer,
        );
        let accessor = if bounds {
            Accessor {
                min: Some(json!(min)),
                max: Some(json!(max)),
                ..accessor
            }
        } else {
            accessor
        };
        self.root.push(accessor)
    }

    fn vec2(&mut self, values: &[[f32; 2]]) -> Index<Accessor> {
        let start = self.bin.len();
        self.bin
            .extend(values.iter().flatten().flat_map(|x| x.to_le_bytes()));
        let accessor = self.accessor(
            start,
            values.len(),
            ComponentType::F32,
            Type::Vec2,
            Target::ArrayBuffer,
        );
        self.root.push(accessor)
    }

    fn indices(&mut self, values: &[u32]) -> Index<Accessor> {
        let start = self.bin.len();
        self.bin.extend(values.iter().flat_map(|x| x.to_le_bytes()));
        let accessor = self.accessor(
            start,
            values.len(),
            ComponentType::U32,
            Type::Scalar,
            Target::ElementArrayBuffer,
        );
        self.root.push(accessor)
    }

    /// An accessor over a new buffer view of the bytes from `start` to the end of the
    /// buffer. Every element is 4-byte aligned because all components are 4 bytes.
    fn accessor(
        &mut self,
        start: usize,
        count: usize,
        component: ComponentType,
        ty: Type,
        target: Target,
    ) -> Accessor {
        let view = self.root.push(gltf_json::buffer::View {
            buffer: Index::new(0),
            byte_length: USize64::from(self.bin.len() - start),
            byte_offset: Some(USize64::from(start)),
            target: Some(Valid(target)),
            ..blank(json!({ "buffer": 0, "byteLength": 0 }))
        });
        Accessor {
            buffer_view: Some(view),
            count: USize64::from(count),
            component_type: Valid(GenericComponentType(component)),
            type_: Valid(ty),
            ..blank(json!({ "componentType": 5126, "type": "SCALAR", "count": 0 }))
        }
    }

    /// Serialises the document with its names and extras and frames it as GLB.
    fn finish(mut self) -> std::io::Result<Vec<u8>> {
        self.root.push(gltf_json::Buffer {
            byte_length: USize64::from(self.bin.len()),
            ..blank(json!({ "byteLength": 0 }))
        });
        let nodes = (0..self.names.len()).map(|i| Index::new(i as u32)).collect();
        let scene = self.root.push(gltf_json::Scene {
            nodes,
            ..blank(json!({ "nodes": [] }))
        });
        self.root.scene = Some(scene);

        // Names and extras go into the JSON, not the typed root: see `blank`.
        let mut json = serde_json::to_value(&self.root)?;
        for (i, name) in self.names.iter().enumerate() {
            json["nodes"][i]["name"] = json!(name);
            json["meshes"][i]["name"] = json!(name);
        }
        for (i, name) in self.material_names.iter().enumerate() {
            json["materials"][i]["name"] = json!(name);
        }
        json["nodes"][0]["extras"] = json!({
            "strain_full_scale_percent": FULL_SCALE_PERCENT,
            "COLOR_0": "strain: mean over the vertex's triangles of max(warp, weft, 0) %, \
                        blue at 0 through cyan, green, yellow to red at full scale",
            "TEXCOORD_0": "material coordinates (u along the warp, v along the weft), m",
        });
        glb_container(&serde_json::to_vec(&json)?, &self.bin)
    }
}

/// The cloth's glTF vertices: one per distinct (vertex, material coordinate) of the
/// triangle corners, so a seam vertex is split into one per panel.
struct Split {
    /// The cloth vertex of each glTF vertex.
    source: Vec<usize>,
    uv: Vec<[f32; 2]>,
    /// Three per triangle, in the mesh's order.
    indices: Vec<u32>,
}

impl Split {
    fn new(mesh: &ClothMesh) -> std::io::Result<Self> {
        // Keyed on the exact bits, as ClothMesh::cut_at_seams is: the corners of one panel
        // at a vertex carry the very same coordinates.
        let mut ids: HashMap<(usize, [u64; 2]), u32> = HashMap::new();
        let mut split = Split {
            source: Vec::new(),
            uv: Vec::new(),
            indices: Vec::with_capacity(3 * mesh.triangles().len()),
        };
        for (t, tri) in mesh.triangles().iter().enumerate() {
            for (&v, c) in tri.iter().zip(mesh.corner_uv(t)) {
                let key = (v, [c.x.to_bits(), c.y.to_bits()]);
                let id = match ids.get(&key) {
                    Some(&id) => id,
                    None => {
                        let id = u32::try_from(split.source.len()).map_err(|_| {
                            Error::new(ErrorKind::InvalidInput, "too many cloth vertices for glTF")
                        })?;
                        split.source.push(v);
                        split.uv.push([c.x as f32, c.y as f32]);
                        ids.insert(key, id);
                        id
                    }
                };
                split.indices.push(id);
            }
        }
        Ok(split)
    }
}

/// gltf-json declares the `name` fields of its objects only under its "names" feature,
/// which this crate's tests turn on (through gltf) and its other builds do not. So objects
/// without `Default` are built by struct update from a blank parsed one, which compiles
/// either way, and names (and extras, likewise) are written into the JSON at the end.
fn blank<T: serde::de::DeserializeOwned>(json: serde_json::Value) -> T {
    serde_json::from_value(json).expect("a blank glTF object parses")
}

/// The GLB container: a 12-byte header, then a JSON chunk padded with spaces and a BIN
/// chunk padded with zeros, both to 4 bytes as the format requires.
fn glb_container(json: &[u8], bin: &[u8]) -> std::io::Result<Vec<u8>> {
    let padded = |n: usize| n.div_ceil(4) * 4;
    let total = 12 + 8 + padded(json.len()) + 8 + padded(bin.len());
    let length = |n: usize| {
        u32::try_from(n)
            .map(u32::to_le_bytes)
            .map_err(|_| Error::new(ErrorKind::InvalidData, "the glTF file would be 4 GiB or more"))
    };
    let mut out = Vec::with_capacity(total);
    out.extend(b"glTF");
    out.extend(2u32.to_le_bytes());
    out.extend(length(total)?);
    for (data, kind, pad) in [(json, b"JSON", b' '), (bin, b"BIN\0", 0)] {
        out.extend(length(padded(data.len()))?);
        out.extend(kind);
        out.extend(data);
        out.resize(out.len() + padded(data.len()) - data.len(), pad);
    }
    Ok(out)
}

/// `points` in glTF's y-up frame as f32; a point that is not finite there is an error
/// naming `what` and the vertex.
fn y_up(points: &[Vec3], what: &str) -> std::io::Result<Vec<[f32; 3]>> {
    points
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let q = [p.x as f32, p.z as f32, -p.y as f32];
            if q.iter().all(|c| c.is_finite()) {
                Ok(q)
            } else {
                Err(Error::new(
                    ErrorKind::InvalidData,
                    format!(
                        "{what} vertex {i} is at ({}, {}, {}), not finite in f32",
                        p.x, p.y, p.z
                    ),
                ))
            }
        })
        .collect()
}

/// Smooth unit normals in the y-up frame: the area-weighted mean of the triangle normals
/// around each vertex (world up where they cancel or the triangles have collapsed).
fn vertex_normals(points: &[Vec3], triangles: impl Iterator<Item = [usize; 3]>) -> Vec<[f32; 3]> {
    let mut sum = vec![Vec3::zeros(); points.len()];
    for [a, b, c] in triangles {
        // Twice the area times the unit normal.
        let n = (points[b] - points[a]).cross(&(points[c] - points[a]));
        for i in [a, b, c] {
            sum[i] += n;
        }
    }
    sum.iter()
        .map(|n| {
            let n = n.try_normalize(1e-300).unwrap_or_else(Vec3::z);
            [n.x as f32, n.z as f32, -n.y as f32]
        })
        .collect()
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

#[cfg(test)]
mod tests {
    use super::*;

    fn u32_at(bytes: &[u8], at: usize) -> usize {
        u32::from_le_bytes(bytes[at..at + 4].try_into().expect("4 bytes")) as usize
    }

    #[test]
    fn container_pads_chunks_to_four_bytes() {
        let glb = glb_container(b"{\"a\":1}", &[1, 2, 3, 4, 5]).expect("small");
        assert_eq!(&glb[0..4], b"glTF");
        assert_eq!(u32_at(&glb, 4), 2);
        assert_eq!(u32_at(&glb, 8), glb.len());
        assert_eq!(u32_at(&glb, 12), 8);
        assert_eq!(&glb[16..28], b"JSON{\"a\":1} ");
        assert_eq!(u32_at(&glb, 28), 8);
        assert_eq!(&glb[32..36], b"BIN\0");
        assert_eq!(&glb[36..], &[1, 2, 3, 4, 5, 0, 0, 0]);
    }

    #[test]
    fn blank_objects_parse() {
        // Every `blank` template the writer uses, so a gltf-json update that breaks one
        // fails here rather than in a run.
        let _: gltf_json::Mesh = blank(json!({ "primitives": [] }));
        let _: gltf_json::buffer::View = blank(json!({ "buffer": 0, "byteLength": 0 }));
        let _: Accessor = blank(json!({ "componentType": 5126, "type": "SCALAR", "count": 0 }));
        let _: gltf_json::Buffer = blank(json!({ "byteLength": 0 }));
        let _: gltf_json::Scene = blank(json!({ "nodes": [] }));
    }
}
