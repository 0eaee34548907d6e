//! Meshes of flat pieces of fabric: polygons in material (u, v) coordinates triangulated
//! at a target edge length.

mod polygon;

pub use polygon::{
    circle, encloses, mesh_region, triangulate_polygon, MeshingError, RegionMesh, ANGLE_LIMIT_DEGREES,
};
