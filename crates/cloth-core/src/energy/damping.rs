//! Stiffness-proportional (Rayleigh) damping: `F = -beta K v`, `dF/dv = -beta K`, with K
//! the element's PSD stiffness, so damping acts only on deforming motion, never on
//! rigid motion (which K maps to zero).

use super::Local;
use crate::math::Vec3;

/// Adds `-beta H v` to `force` and `H v` to `hv` for one element.
#[inline]
pub fn add_damping<const N: usize>(
    beta: f64,
    local: &Local<N>,
    v: &[Vec3; N],
    force: &mut [Vec3; N],
    hv: &mut [Vec3; N],
) {
    for i in 0..N {
        let mut s = Vec3::zeros();
        for j in 0..N {
            s += local.hess[i][j] * v[j];
        }
        force[i] -= beta * s;
        hv[i] += s;
    }
}
