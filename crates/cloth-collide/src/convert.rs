//! parry 0.31 speaks glam; the engine speaks nalgebra. Conversions happen here only.

use cloth_core::math::Vec3;
use parry3d_f64::math::Vector;

pub(crate) fn to_parry(v: &Vec3) -> Vector {
    Vector::new(v.x, v.y, v.z)
}

pub(crate) fn from_parry(v: Vector) -> Vec3 {
    Vec3::new(v.x, v.y, v.z)
}
