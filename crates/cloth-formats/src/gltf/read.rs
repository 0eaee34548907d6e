//! Reading glTF 2.0 (`.gltf` with its buffers, or binary `.glb`): every triangle primitive
//! of every mesh the default scene's nodes place, with the nodes' transforms applied, in the
//! file's own (y-up) frame. Buffers come from the GLB's binary chunk, from files beside it,
//! or from base64 data URIs.

use crate::error::{read_bytes, FormatError};
use crate::mesh::FileMesh;
use ::gltf::mesh::Mode;
use cloth_core::math::Vec3;
use nalgebra::{Matrix4, Point3};
use std::path::Path;

/// Reads `path`: the primitives' vertices one after another, in the order the scene's
/// nodes are visited (depth first).
pub fn read_gltf(path: &Path) -> Result<FileMesh, FormatError> {
    let bytes = read_bytes(path)?;
    let parse = |message: String| FormatError::Parse {
        path: path.to_path_buf(),
        line: None,
        message,
    };
    // gltf-json's validation indexes a primitive's POSITION accessor before checking it
    // exists (and panics): check that first on the unvalidated document.
    let unchecked = ::gltf::Gltf::from_slice_without_validation(&bytes).map_err(|e| parse(e.to_string()))?;
    let accessors = unchecked.accessors().count();
    for mesh in &unchecked.as_json().meshes {
        for primitive in &mesh.primitives {
            if let Some(a) = primitive.attributes.values().find(|a| a.value() >= accessors) {
                return Err(parse(format!(
                    "a primitive's attribute names accessor {}, but the file has {accessors}",
                    a.value()
                )));
            }
        }
    }
    let gltf = ::gltf::Gltf::from_slice(&bytes).map_err(|e| parse(e.to_string()))?;
    let mut buffers: Vec<Vec<u8>> = Vec::new();
    for buffer in gltf.buffers() {
        let data = match buffer.source() {
            ::gltf::buffer::Source::Bin => gltf.blob.clone().ok_or_else(|| {
                parse(format!(
                    "buffer {} is the binary chunk, which the file lacks",
                    buffer.index()
                ))
            })?,
            ::gltf::buffer::Source::Uri(uri) => {
                buffer_data(path, uri).map_err(|m| parse(format!("buffer {}: {m}", buffer.index())))?
            }
        };
        if data.len() < buffer.length() {
            return Err(parse(format!(
                "buffer {} holds {} bytes, fewer than the {} it declares",
                buffer.index(),
                data.len(),
                buffer.length()
            )));
        }
        buffers.push(data);
    }
    let scene = gltf
        .default_scene()
        .or_else(|| gltf.scenes().next())
        .ok_or_else(|| parse("the file has no scene".into()))?;
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    // Depth-first through the node tree with each node's world transform; the
    // validated document has no cycles.
    let mut stack: Vec<(::gltf::Node, Matrix4<f64>)> =
        scene.nodes().map(|n| (n, Matrix4::identity())).collect();
    while let Some((node, parent)) = stack.pop() {
        let local = Matrix4::from(node.transform().matrix()).cast::<f64>();
        let world = parent * local;
        stack.extend(node.children().map(|c| (c, world)));
        let Some(mesh) = node.mesh() else { continue };
        for primitive in mesh.primitives() {
            if primitive.mode() != Mode::Triangles {
                continue;
            }
            let reader = primitive.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
            let Some(positions) = reader.read_positions() else {
                continue;
            };
            let first = vertices.len() as u32;
            vertices.extend(positions.map(|p| {
                let q = world.transform_point(&Point3::from(p.map(f64::from)));
                Vec3::new(q.x, q.y, q.z)
            }));
            let count = vertices.len() as u32 - first;
            let indices: Vec<u32> = match reader.read_indices() {
                Some(indices) => indices.into_u32().collect(),
                None => (0..count).collect(),
            };
            if let Some(&bad) = indices.iter().find(|&&i| i >= count) {
                return Err(parse(format!(
                    "mesh {} refers to vertex {bad} of a primitive with {count}",
                    mesh.index()
                )));
            }
            // A mirroring transform turns the faces inside out; the surface's repair
            // turns them back and says so.
            triangles.extend(
                indices
                    .chunks_exact(3)
                    .map(|c| [c[0] + first, c[1] + first, c[2] + first]),
            );
        }
    }
    Ok(FileMesh {
        positions: vertices,
        triangles,
    })
}

/// A buffer's bytes from a data URI or a file beside the glTF.
fn buffer_data(path: &Path, uri: &str) -> Result<Vec<u8>, String> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let (_, data) = rest
            .split_once(";base64,")
            .ok_or("a data URI that is not base64")?;
        return base64::decode(data).map_err(|e| format!("bad base64: {e}"));
    }
    let file = path.parent().unwrap_or(Path::new(".")).join(uri);
    std::fs::read(&file).map_err(|e| format!("cannot read '{}': {e}", file.display()))
}
