//! Warp and weft stretch and compression.
//!
//! Per triangle `E = A (W_u(e_u) + W_v(e_v))`, with `e = |w| - 1` the thread strain
//! and `W` the tensile law's energy density (its own stiffness in compression).
//! With `w = sum c_i x_i` the Hessian is `(c c^T) (x) H_w`, where
//! `H_w = A [T' w^ w^T + (T/|w|)(I - w^ w^T)]`: its eigenvalues are `T'` and `T/|w|`,
//! so clamping a compressive `T` to zero is the exact PSD projection.

use super::{HessianMode, Local, TriangleRest};
use crate::fabric::{Fabric, TensileLaw, TensileResponse};
use crate::math::{Mat3, Vec3};

/// Tension response of one thread direction, with its compression stiffness.
#[derive(Debug, Clone, Copy)]
pub struct ThreadLaw<'a> {
    pub tension: &'a TensileLaw,
    pub compression: f64,
}

impl<'a> ThreadLaw<'a> {
    /// The warp and the weft laws of a fabric.
    pub fn of(fabric: &'a Fabric) -> [Self; 2] {
        [
            Self {
                tension: &fabric.warp,
                compression: fabric.compression_warp,
            },
            Self {
                tension: &fabric.weft,
                compression: fabric.compression_weft,
            },
        ]
    }

    /// The tension law from a strain of minus [`STRAIN_NOISE`] up: a sheet at rest has
    /// strains of rounding size and either sign, and the stiffness must not depend on which
    /// (mirror-image threads would get tension and compression stiffness at random).
    #[inline]
    pub fn response(&self, strain: f64) -> TensileResponse {
        if strain >= -STRAIN_NOISE {
            self.tension.extension(strain.max(0.0))
        } else {
            TensileResponse {
                energy: 0.5 * self.compression * strain * strain,
                tension: self.compression * strain,
                slope: self.compression,
            }
        }
    }
}

/// Strains closer to zero than this are rounding noise, m/m.
pub const STRAIN_NOISE: f64 = 1e-12;

/// Adds the stretch energy of one triangle along warp and weft.
pub fn add_stretch(
    rest: &TriangleRest,
    warp: ThreadLaw,
    weft: ThreadLaw,
    x: &[Vec3; 3],
    mode: HessianMode,
    out: &mut Local<3>,
) {
    let (wu, wv) = rest.deformation(x);
    add_direction(rest.area, &rest.a, wu, warp, mode, out);
    add_direction(rest.area, &rest.b, wv, weft, mode, out);
}

#[inline]
fn add_direction(area: f64, c: &[f64; 3], w: Vec3, law: ThreadLaw, mode: HessianMode, out: &mut Local<3>) {
    let len = w.norm();
    if len < 1e-12 {
        return; // a thread collapsed to a point has no direction to pull along
    }
    let dir = w / len;
    let r = law.response(len - 1.0);
    out.energy += area * r.energy;
    for i in 0..3 {
        out.grad[i] += (area * r.tension * c[i]) * dir;
    }
    if mode == HessianMode::None {
        return;
    }
    let transverse = match mode {
        HessianMode::Projected => r.tension.max(0.0),
        _ => r.tension,
    } / len;
    let ddt = dir * dir.transpose();
    let hw = area * (r.slope * ddt + transverse * (Mat3::identity() - ddt));
    for i in 0..3 {
        for j in 0..3 {
            out.hess[i][j] += (c[i] * c[j]) * hw;
        }
    }
}
