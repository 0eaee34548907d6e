//! glTF 2.0: meshes read from `.gltf` or `.glb`, and `.glb` written.

mod read;
mod write;

pub use read::read_gltf;
pub use write::{vertex_normals, y_up, GlbDocument, GlbMaterial, GlbMesh, MaterialId};
