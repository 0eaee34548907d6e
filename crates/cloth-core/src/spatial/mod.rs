//! Spatial search shared by the body and the self contacts: axis-aligned boxes and a
//! bounding volume hierarchy over them.

mod bvh;

pub(crate) use bvh::{Aabb, Bvh};
