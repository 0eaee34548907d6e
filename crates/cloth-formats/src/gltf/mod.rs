//! glTF 2.0: meshes read from `.gltf` or `.glb`; `.glb` written, the cloth's motion too.

mod write;
mod cloth_vertices;
mod animation;
mod read;

pub use animation::{GlbAnimationWriter, MAX_TARGETS};
pub use cloth_vertices::ClothVertices;
pub use read::read_gltf;
pub use write::{
    vertex_normals, y_up, GlbDocument, GlbMaterial, GlbMesh, GlbMorphTarget, MaterialId, NodeId,
};
