//! cloth-collide: rigid polyhedral bodies for the cloth to drape on, on parry.
//!
//! A [`Body`] is a [`TriSurface`] (read from OBJ, STL, PLY, glTF or GLB, repaired where
//! that is sound and its defects named, or generated) with a pose that may move in time,
//! a contact thickness and a friction coefficient. [`Bodies`] implements cloth-core's [`cloth_core::Collider`]: bounded BVH
//! point queries for contact, ray casts along each particle's path against tunnelling, and
//! the sharp edges and corners that must not poke through cloth triangles.

mod convert;
mod motion;
pub mod surface;
mod contact_mesh;
mod layer;
mod thin_parts;
mod body;
mod bodies;

pub use bodies::Bodies;
pub use body::{Body, BodyError, DEFAULT_SHARP_ANGLE, DEFAULT_THICKNESS};
pub use motion::Motion;
pub use surface::{SurfaceDefect, SurfaceError, SurfaceOptions, TriSurface};
pub use thin_parts::THIN_PART;
