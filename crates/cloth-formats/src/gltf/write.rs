//! Writing binary glTF 2.0 (.glb): named triangle meshes with their materials, in glTF's
//! y-up frame, for any 3D viewer.

use cloth_core::math::Vec3;
use gltf_json::accessor::{ComponentType, GenericComponentType, Type};
use gltf_json::animation::{Channel, Interpolation, Property, Sampler};
use gltf_json::buffer::Target;
use gltf_json::material::{PbrBaseColorFactor, PbrMetallicRoughness, StrengthFactor};
use gltf_json::mesh::{Mode, Primitive, Semantic};
use gltf_json::validation::{Checked::Valid, USize64};
use gltf_json::{Accessor, Index};
use serde_json::json;
use std::collections::BTreeMap;
use std::io::{Error, ErrorKind};

/// A material: a base colour (times the vertex colours, if any), no metal.
#[derive(Debug, Clone, PartialEq)]
pub struct GlbMaterial {
    pub name: String,
    pub base_colour: [f32; 4],
    pub roughness: f32,
    /// Seen from both sides, as an open sheet is.
    pub double_sided: bool,
}

/// A mesh to write, in glTF's frame (see [`y_up`]); every attribute has one entry per
/// vertex.
#[derive(Debug, Clone)]
pub struct GlbMesh<'a> {
    pub name: &'a str,
    pub positions: &'a [[f32; 3]],
    pub normals: &'a [[f32; 3]],
    pub texcoords: Option<&'a [[f32; 2]]>,
    /// Linear RGB.
    pub colours: Option<&'a [[f32; 3]]>,
    /// Application-specific scalar attributes, one value per vertex: each name must start
    /// with an underscore, as glTF asks of attributes it does not define.
    pub scalars: &'a [(&'a str, &'a [f32])],
    /// Shapes the mesh can be blended towards, named in the mesh's `extras.targetNames`
    /// (which Blender reads as its shape keys' names).
    pub targets: &'a [GlbMorphTarget],
    /// Three per triangle.
    pub indices: &'a [u32],
    pub material: MaterialId,
    /// Written as the node's `extras`, to say what the attributes mean.
    pub extras: Option<serde_json::Value>,
}

/// A morph target: every vertex's displacement from the mesh's own position and normal.
#[derive(Debug, Clone, PartialEq)]
pub struct GlbMorphTarget {
    pub name: String,
    pub positions: Vec<[f32; 3]>,
    pub normals: Vec<[f32; 3]>,
}

/// A mesh added to a [`GlbDocument`], as the index of the node that shows it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NodeId(u32);

/// A material added to a [`GlbDocument`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MaterialId(u32);

/// A glTF document being built: the JSON root, the binary buffer, and the names of its
/// nodes (node `i` shows mesh `i`, both named `names[i]`), their extras and morph target
/// names, and the materials' and animations' names.
#[derive(Default)]
pub struct GlbDocument {
    root: gltf_json::Root,
    bin: Vec<u8>,
    names: Vec<String>,
    extras: Vec<Option<serde_json::Value>>,
    target_names: Vec<Vec<String>>,
    material_names: Vec<String>,
    animation_names: Vec<String>,
}

impl GlbDocument {
    /// An empty document; `generator` names the program in its asset record.
    pub fn new(generator: String) -> Self {
        let mut doc = Self::default();
        doc.root.asset.generator = Some(generator);
        doc
    }

    pub fn add_material(&mut self, material: GlbMaterial) -> MaterialId {
        let id = MaterialId(self.material_names.len() as u32);
        self.material_names.push(material.name);
        self.root.push(gltf_json::Material {
            pbr_metallic_roughness: PbrMetallicRoughness {
                base_color_factor: PbrBaseColorFactor(material.base_colour),
                metallic_factor: StrengthFactor(0.0),
                roughness_factor: StrengthFactor(material.roughness),
                ..Default::default()
            },
            double_sided: material.double_sided,
            ..Default::default()
        });
        id
    }

    /// Adds `mesh` as a node of the scene. Attributes whose length is not the vertex count
    /// are an `InvalidInput` error.
    pub fn add_mesh(&mut self, mesh: GlbMesh<'_>) -> std::io::Result<NodeId> {
        let n = mesh.positions.len();
        let target_lengths = mesh
            .targets
            .iter()
            .flat_map(|t| [Some(t.positions.len()), Some(t.normals.len())]);
        let lengths: Vec<Option<usize>> = [
            Some(mesh.normals.len()),
            mesh.texcoords.map(<[_]>::len),
            mesh.colours.map(<[_]>::len),
        ]
        .into_iter()
        .chain(target_lengths)
        .collect();
        let scalar_lengths = mesh.scalars.iter().map(|(_, values)| values.len());
        if lengths
            .iter()
            .flatten()
            .copied()
            .chain(scalar_lengths)
            .any(|l| l != n)
            || mesh.indices.len() % 3 != 0
        {
            return Err(Error::new(
                ErrorKind::InvalidInput,
                format!("mesh `{}`: attributes of different lengths", mesh.name),
            ));
        }
        if let Some(&bad) = mesh.indices.iter().find(|&&i| i as usize >= n) {
            return Err(Error::new(
                ErrorKind::InvalidInput,
                format!("mesh `{}`: index {bad} of {n} vertices", mesh.name),
            ));
        }
        if let Some((name, _)) = mesh.scalars.iter().find(|(name, _)| !name.starts_with('_')) {
            return Err(Error::new(
                ErrorKind::InvalidInput,
                format!(
                    "mesh `{}`: attribute `{name}` does not start with an underscore",
                    mesh.name
                ),
            ));
        }
        let mut attributes = vec![
            (Semantic::Positions, self.vec3(mesh.positions, true)),
            (Semantic::Normals, self.vec3(mesh.normals, false)),
        ];
        if let Some(uv) = mesh.texcoords {
            attributes.push((Semantic::TexCoords(0), self.vec2(uv)));
        }
        if let Some(colours) = mesh.colours {
            attributes.push((Semantic::Colors(0), self.vec3(colours, false)));
        }
        for (name, values) in mesh.scalars {
            attributes.push((Semantic::Extras(name[1..].to_string()), self.scalar(values)));
        }
        let targets = (!mesh.targets.is_empty()).then(|| {
            mesh.targets
                .iter()
                .map(|t| gltf_json::mesh::MorphTarget {
                    positions: Some(self.vec3(&t.positions, true)),
                    normals: Some(self.vec3(&t.normals, false)),
                    tangents: None,
                })
                .collect()
        });
        let indices = self.indices(mesh.indices);
        let primitive = Primitive {
            attributes: attributes
                .into_iter()
                .map(|(s, a)| (Valid(s), a))
                .collect::<BTreeMap<_, _>>(),
            extensions: None,
            extras: Default::default(),
            indices: Some(indices),
            material: Some(Index::new(mesh.material.0)),
            mode: Valid(Mode::Triangles),
            targets,
        };
        let gltf_mesh = self.root.push(gltf_json::Mesh {
            primitives: vec![primitive],
            weights: (!mesh.targets.is_empty()).then(|| vec![0.0; mesh.targets.len()]),
            ..blank(json!({ "primitives": [] }))
        });
        let node = self.root.push(gltf_json::Node {
            mesh: Some(gltf_mesh),
            ..Default::default()
        });
        self.names.push(mesh.name.to_owned());
        self.extras.push(mesh.extras);
        self.target_names
            .push(mesh.targets.iter().map(|t| t.name.clone()).collect());
        Ok(NodeId(node.value() as u32))
    }

    /// An animation of the morph target weights of `node`'s mesh: at `times[k]` (seconds,
    /// increasing) the weights are `weights[k * targets..(k + 1) * targets]`, blended
    /// linearly between. Lengths that do not match, or times that do not increase, are an
    /// `InvalidInput` error.
    pub fn add_weights_animation(
        &mut self,
        name: &str,
        node: NodeId,
        times: &[f32],
        weights: &[f32],
    ) -> std::io::Result<()> {
        let targets = self.target_names.get(node.0 as usize).map_or(0, Vec::len);
        let invalid = |message: String| Err(Error::new(ErrorKind::InvalidInput, message));
        if targets == 0 {
            return invalid(format!("animation `{name}`: its mesh has no morph targets"));
        }
        if times.is_empty() || weights.len() != times.len() * targets {
            return invalid(format!(
                "animation `{name}`: {} weights for {} times of {targets} targets",
                weights.len(),
                times.len()
            ));
        }
        if times.iter().any(|t| !t.is_finite()) || times.windows(2).any(|w| w[0] >= w[1]) {
            return invalid(format!("animation `{name}`: its times do not increase"));
        }
        let input = {
            let words = times.iter().map(|x| x.to_le_bytes());
            let start = self.bin.len();
            self.bin.extend(words.flatten());
            let accessor = self.accessor(start, times.len(), ComponentType::F32, Type::Scalar, None);
            // An animation's input must state its range.
            self.root.push(Accessor {
                min: Some(json!([times[0]])),
                max: Some(json!([times[times.len() - 1]])),
                ..accessor
            })
        };
        let output = {
            let start = self.bin.len();
            self.bin.extend(weights.iter().flat_map(|x| x.to_le_bytes()));
            let accessor = self.accessor(start, weights.len(), ComponentType::F32, Type::Scalar, None);
            self.root.push(accessor)
        };
        let sampler = Sampler {
            extensions: None,
            extras: Default::default(),
            input,
            interpolation: Valid(Interpolation::Linear),
            output,
        };
        let channel = Channel {
            sampler: Index::new(0),
            target: gltf_json::animation::Target {
                extensions: None,
                extras: Default::default(),
                node: Index::new(node.0),
                path: Valid(Property::MorphTargetWeights),
            },
            extensions: None,
            extras: Default::default(),
        };
        self.root.push(gltf_json::Animation {
            channels: vec![channel],
            samplers: vec![sampler],
            ..blank(json!({ "channels": [], "samplers": [] }))
        });
        self.animation_names.push(name.to_owned());
        Ok(())
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
            Some(Target::ArrayBuffer),
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
        let words = values.iter().flatten().map(|x| x.to_le_bytes());
        self.packed(
            words,
            values.len(),
            ComponentType::F32,
            Type::Vec2,
            Target::ArrayBuffer,
        )
    }

    fn scalar(&mut self, values: &[f32]) -> Index<Accessor> {
        let words = values.iter().map(|x| x.to_le_bytes());
        self.packed(
            words,
            values.len(),
            ComponentType::F32,
            Type::Scalar,
            Target::ArrayBuffer,
        )
    }

    fn indices(&mut self, values: &[u32]) -> Index<Accessor> {
        let words = values.iter().map(|x| x.to_le_bytes());
        let target = Target::ElementArrayBuffer;
        self.packed(words, values.len(), ComponentType::U32, Type::Scalar, target)
    }

    /// `count` elements of type `ty`, their 4-byte components given in order, appended to
    /// the buffer behind a new accessor.
    fn packed(
        &mut self,
        words: impl Iterator<Item = [u8; 4]>,
        count: usize,
        component: ComponentType,
        ty: Type,
        target: Target,
    ) -> Index<Accessor> {
        let start = self.bin.len();
        self.bin.extend(words.flatten());
        let accessor = self.accessor(start, count, component, ty, Some(target));
        self.root.push(accessor)
    }

    /// An accessor over a new buffer view of the bytes from `start` to the end of the
    /// buffer. Every element is 4-byte aligned because all components are 4 bytes. Views
    /// that are not vertex attributes or indices (animation data) have no `target`.
    fn accessor(
        &mut self,
        start: usize,
        count: usize,
        component: ComponentType,
        ty: Type,
        target: Option<Target>,
    ) -> Accessor {
        let view = self.root.push(gltf_json::buffer::View {
            buffer: Index::new(0),
            byte_length: USize64::from(self.bin.len() - start),
            byte_offset: Some(USize64::from(start)),
            target: target.map(Valid),
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
    pub fn into_bytes(mut self) -> std::io::Result<Vec<u8>> {
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
        for (i, name) in self.animation_names.iter().enumerate() {
            json["animations"][i]["name"] = json!(name);
        }
        for (i, names) in self.target_names.iter().enumerate() {
            if !names.is_empty() {
                json["meshes"][i]["extras"] = json!({ "targetNames": names });
            }
        }
        for (i, extras) in self.extras.into_iter().enumerate() {
            if let Some(extras) = extras {
                json["nodes"][i]["extras"] = extras;
            }
        }

        glb_container(&serde_json::to_vec(&json)?, &self.bin)
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
pub fn y_up(points: &[Vec3], what: &str) -> std::io::Result<Vec<[f32; 3]>> {
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
pub fn vertex_normals(points: &[Vec3], triangles: impl Iterator<Item = [usize; 3]>) -> Vec<[f32; 3]> {
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
        let _: gltf_json::Animation = blank(json!({ "channels": [], "samplers": [] }));
    }
}
