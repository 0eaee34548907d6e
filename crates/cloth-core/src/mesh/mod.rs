//! Cloth meshes: triangles with material (warp, weft) coordinates, and their hinges.

mod cloth_mesh;
mod grid;
mod rings;
mod topology;

pub use cloth_mesh::{ClothMesh, GridShape};
pub use grid::{GridBuilder, GridDiagonals};
pub use rings::{components, within_rings, Neighbours};
pub use topology::Hinge;
