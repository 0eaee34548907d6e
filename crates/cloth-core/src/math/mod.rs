//! The basic types every other module is written in: 3-vectors and 3x3 blocks, and the
//! geometric predicates on points, segments and triangles, and disjoint sets.

pub mod predicates;
pub mod union_find;

/// A point, a velocity or a force.
pub type Vec3 = nalgebra::Vector3<f64>;
/// A 3x3 block: one particle pair's coupling in the block-sparse system.
pub type Mat3 = nalgebra::Matrix3<f64>;
