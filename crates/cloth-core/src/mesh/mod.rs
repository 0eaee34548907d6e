//! Cloth meshes: triangles with material (warp, weft) coordinates, and their hinges.

mod error;
mod topology;
mod grid_shape;
mod cloth_mesh;
mod grid;
mod rings;

pub use cloth_mesh::ClothMesh;
pub use error::MeshError;
pub use grid::GridBuilder;
pub use grid_shape::{GridDiagonals, GridShape};
pub use rings::{components, within_rings, Neighbours};
pub use topology::Hinge;
