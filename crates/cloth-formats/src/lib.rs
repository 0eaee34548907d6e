//! cloth-formats: the files the engine reads and writes. OBJ, PLY, STL and glTF meshes are
//! read in the file's own numbering, so a vertex is one number for every user; outputs are
//! written atomically.

// Bottom-up: each module uses only those above it.
pub mod error;
pub mod atomic;
pub mod mesh;
pub mod panels;
pub mod obj;
pub mod ply;
pub mod stl;
pub mod pc2;
pub mod gltf;
pub mod by_extension;

pub use by_extension::{read_mesh, MeshFormat};
pub use error::FormatError;
pub use mesh::FileMesh;
