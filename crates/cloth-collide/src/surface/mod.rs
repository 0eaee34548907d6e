//! Rigid-body surfaces: closed, manifold, outward triangle meshes, read from OBJ or STL
//! files or built from primitives. Pure geometry; collision queries live elsewhere.

mod edges;
mod error;
mod features;
mod io;
mod measure;
mod obj;
mod options;
mod primitives;
mod stl;
mod validate;
mod weld;

use cloth_core::Vec3;

pub use error::SurfaceError;
pub use features::SharpFeature;
pub use options::SurfaceOptions;

/// A closed, manifold, consistently and outwardly oriented triangle mesh: what a rigid body
/// is made of. Every constructor validates, so holding one means the invariants hold.
#[derive(Debug, Clone, PartialEq)]
pub struct TriSurface {
    vertices: Vec<Vec3>,
    triangles: Vec<[u32; 3]>,
}

impl TriSurface {
    pub fn vertices(&self) -> &[Vec3] {
        &self.vertices
    }
    /// Vertex indices of each triangle, counter-clockwise seen from outside.
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }
}
