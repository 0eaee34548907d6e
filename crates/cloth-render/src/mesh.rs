//! What is drawn: a triangle mesh and its colours.

use cloth_collide::TriSurface;
use cloth_core::math::Vec3;

/// The grey of bodies, and of meshes that bring no colours of their own.
pub const NEUTRAL_GREY: [u8; 3] = [190, 190, 194];

/// A triangle mesh to draw. Triangles with an index out of range, or a corner that is not
/// finite, are skipped rather than drawn wrong.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderMesh {
    pub positions: Vec<Vec3>,
    pub triangles: Vec<[usize; 3]>,
    pub colours: MeshColours,
}

/// The base colour of a mesh, before shading.
#[derive(Debug, Clone, PartialEq)]
pub enum MeshColours {
    Uniform([u8; 3]),
    /// One per position, interpolated across triangles; positions without one are grey.
    PerVertex(Vec<[u8; 3]>),
}

impl RenderMesh {
    /// A body surface in one colour.
    pub fn from_surface(surface: &TriSurface, colour: [u8; 3]) -> Self {
        Self {
            positions: surface.vertices().to_vec(),
            triangles: surface
                .triangles()
                .iter()
                .map(|t| t.map(|i| i as usize))
                .collect(),
            colours: MeshColours::Uniform(colour),
        }
    }

    pub(crate) fn colour(&self, vertex: usize) -> [u8; 3] {
        match &self.colours {
            MeshColours::Uniform(c) => *c,
            MeshColours::PerVertex(c) => c.get(vertex).copied().unwrap_or(NEUTRAL_GREY),
        }
    }
}
