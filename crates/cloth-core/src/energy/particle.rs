//! Per-particle forces: gravity and viscous air drag.

use crate::math::Vec3;

/// Gravity: `E = -m g.x`, `F = m g`, no Jacobian.
#[inline]
pub fn gravity_energy(mass: f64, g: &Vec3, x: &Vec3) -> f64 {
    -mass * g.dot(x)
}

/// Viscous drag on a particle carrying area `area`: `F = -c area (v - wind)`;
/// `dF/dv = -c area I`, returned as the scalar `c area`.
#[inline]
pub fn drag(coefficient: f64, area: f64, v: &Vec3, wind: &Vec3) -> (Vec3, f64) {
    let c = coefficient * area;
    (-c * (v - wind), c)
}
