//! Pictures of meshes without a GPU: a z-buffered, supersampled triangle rasteriser with
//! smooth two-sided shading, a perspective camera that frames whatever it is given, bitmap
//! text, and figures of titled panels side by side with a strain colour legend.
//!
//! [`render_run`] is the picture of a finished run; [`figure`] draws anything else, and
//! [`read_render_mesh`] reads OBJ and PLY files to feed it.

mod camera;
mod error;
mod figure;
mod image;
mod legend;
mod mesh_read;
mod raster;
mod run;
mod shading;
mod text;

pub use camera::View;
pub use error::RenderError;
pub use figure::{figure, Panel};
pub use image::Image;
pub use legend::Legend;
pub use mesh_read::{read_render_mesh, Colouring, LoadedMesh};
pub use run::render_run;

use crate::collide::TriSurface;
use crate::math::Vec3;

/// The picture sizes drawn, pixels a side: smaller has no room for the titles, larger is
/// surely a typo.
pub const IMAGE_SIDES: std::ops::RangeInclusive<u32> = 32..=16384;

/// Whether a picture of `width` x `height` pixels can be drawn; if not, why.
pub fn check_image_size(width: u32, height: u32) -> Result<(), String> {
    if IMAGE_SIDES.contains(&width) && IMAGE_SIDES.contains(&height) {
        Ok(())
    } else {
        Err(format!(
            "{width} x {height} pixels: each side must be {} to {}",
            IMAGE_SIDES.start(),
            IMAGE_SIDES.end()
        ))
    }
}

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

    fn colour(&self, vertex: usize) -> [u8; 3] {
        match &self.colours {
            MeshColours::Uniform(c) => *c,
            MeshColours::PerVertex(c) => c.get(vertex).copied().unwrap_or(NEUTRAL_GREY),
        }
    }
}
