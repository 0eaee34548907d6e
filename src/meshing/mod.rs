//! Meshes of flat pieces of fabric: a polygon in material (u, v) coordinates triangulated
//! at a target edge length.

mod polygon;

pub use polygon::{circle, triangulate_polygon, MeshingError};
