//! In-plane shear: the source's `T = mu_s (l1 l2 / 2) phi^2`.
//!
//! `phi` is the shear angle, the departure of the angle between the warp and weft
//! directions `w_u`, `w_v` from 90 degrees: `sin phi = cos(angle) = c`. Per triangle
//! `E = (G/2) A phi^2` with A the rest area (the source's `l1 l2 / 2` for a grid cell's
//! triangle) and G the shear rigidity per radian (`mu_s = G/2` for phi in radians; the
//! source's phi is in degrees, see [`crate::fabric::SourceCoefficients`]). The exact Hessian is
//! `E_cc g g^T + E_c d^2c/dx^2`; the projected one keeps the first, PSD term
//! (`E_cc > 0`), which is all of it at zero shear.

use super::{HessianMode, Local, TriangleRest};
use crate::math::{Mat3, Vec3};

/// Adds the shear energy of one triangle with shear rigidity `modulus` (N/m per radian).
pub fn add_shear(rest: &TriangleRest, modulus: f64, x: &[Vec3; 3], mode: HessianMode, out: &mut Local<3>) {
    if modulus == 0.0 {
        return;
    }
    let (p, q) = rest.deformation(x);
    let (lp, lq) = (p.norm(), q.norm());
    if lp < 1e-12 || lq < 1e-12 {
        return;
    }
    let (ph, qh) = (p / lp, q / lq);
    let c = ph.dot(&qh).clamp(-1.0 + 1e-9, 1.0 - 1e-9);
    let phi = c.asin();
    let s2 = 1.0 - c * c;
    let ga = modulus * rest.area;
    let e_c = ga * phi / s2.sqrt();
    let e_cc = ga * (1.0 / s2 + phi * c / (s2 * s2.sqrt()));
    out.energy += 0.5 * ga * phi * phi;

    let gp = (qh - c * ph) / lp;
    let gq = (ph - c * qh) / lq;
    let (a, b) = (&rest.a, &rest.b);
    let g: [Vec3; 3] = std::array::from_fn(|i| a[i] * gp + b[i] * gq);
    for i in 0..3 {
        out.grad[i] += e_c * g[i];
    }
    match mode {
        HessianMode::None => {}
        HessianMode::Projected => out.add_outer(e_cc, &g),
        HessianMode::Exact => {
            out.add_outer(e_cc, &g);
            let id = Mat3::identity();
            let (pp, qq, pq) = (ph * ph.transpose(), qh * qh.transpose(), ph * qh.transpose());
            let hpp = -(pq + pq.transpose() + c * id - 3.0 * c * pp) / (lp * lp);
            let hqq = -(pq + pq.transpose() + c * id - 3.0 * c * qq) / (lq * lq);
            let hpq = (id - qq - pp + c * pq) / (lp * lq);
            for i in 0..3 {
                for j in 0..3 {
                    let h = a[i] * a[j] * hpp
                        + a[i] * b[j] * hpq
                        + b[i] * a[j] * hpq.transpose()
                        + b[i] * b[j] * hqq;
                    out.hess[i][j] += e_c * h;
                }
            }
        }
    }
}
