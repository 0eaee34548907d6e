//! Rigid-body surfaces: triangle meshes read from OBJ, STL, PLY or glTF files or built
//! from primitives, repaired where that is sound and described where it is not. Pure
//! geometry; collision queries live elsewhere.

mod error;
mod options;
mod defects;
mod edges;
mod features;
mod measure;
mod orientation;
mod weld;
mod winding;
mod overlap;
mod repair;
mod primitives;
mod read;

use cloth_core::math::Vec3;

pub use defects::SurfaceDefect;
pub use error::SurfaceError;
pub use features::SharpFeature;
pub use options::SurfaceOptions;
pub use winding::WindingTree;

/// A body's triangle mesh, its triangles turned to face outward wherever their part can be
/// oriented. Every constructor checks it, so holding one means it encloses something.
///
/// A watertight surface (closed, every edge in two triangles, consistently oriented, its
/// parts apart) tells inside from outside by its nearest triangle. Any other keeps the
/// [`SurfaceDefect`]s found, and inside/outside comes from its winding number.
#[derive(Debug, Clone, PartialEq)]
pub struct TriSurface {
    vertices: Vec<Vec3>,
    triangles: Vec<[u32; 3]>,
    /// Per triangle, whether it lies inside another part (empty when none does).
    buried: Vec<bool>,
    defects: Vec<SurfaceDefect>,
}

impl TriSurface {
    fn assemble(
        vertices: Vec<Vec3>,
        triangles: Vec<[u32; 3]>,
        buried: Vec<bool>,
        defects: Vec<SurfaceDefect>,
    ) -> Self {
        let buried = if buried.contains(&true) {
            buried
        } else {
            Vec::new()
        };
        Self {
            vertices,
            triangles,
            buried,
            defects,
        }
    }

    pub fn vertices(&self) -> &[Vec3] {
        &self.vertices
    }
    /// Vertex indices of each triangle, counter-clockwise seen from outside.
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }
    /// What loading found and did; empty for a mesh that was watertight as given.
    pub fn defects(&self) -> &[SurfaceDefect] {
        &self.defects
    }
    /// Whether the nearest triangle alone tells inside from outside: closed, manifold,
    /// consistently oriented, its parts apart (after the repairs that keep it so).
    pub fn is_watertight(&self) -> bool {
        self.defects.iter().all(SurfaceDefect::keeps_watertight)
    }
    /// Whether triangle `t` lies inside another part, out of the cloth's reach.
    pub fn is_buried(&self, t: usize) -> bool {
        self.buried.get(t).copied().unwrap_or(false)
    }
}
