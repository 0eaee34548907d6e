//! Attachments: a particle held on one side of a plane, free on the other.
//!
//! GarmentCode's simulator keeps a skirt's waist from sinking below the waist, and a
//! bodice's neckline from sliding out over the shoulders, with one-sided plane constraints
//! on the edges its patterns label (its fork of Warp, `integrator_xpbd.py`
//! `attachment_constraint`: only a particle on the wrong side is pushed back). Here they
//! are a penalty in the energy, so the implicit step sees them coming like any spring.

use super::Local;
use crate::math::Vec3;

/// A particle kept on the side of the plane through `point` that `direction` points to:
/// it moves along `direction` freely, and against it no further than `point`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Attachment {
    pub particle: usize,
    pub point: Vec3,
    /// Unit normal of the plane, pointing to the allowed side.
    pub direction: Vec3,
}

/// Whether an attachment holds its particle through a step of `h` from `x` at velocity `v`:
/// the particle is on the wrong side, or would be at the end of the step at its velocity.
/// Held only once on the wrong side, a particle resting on the plane came off it each step
/// the penalty pushed it out and fell back in the next, never at rest; held from the step
/// it would cross in, it lands on the plane instead (see [`add_attachment`]). With `h = 0`
/// (an explicit step), the wrong side alone.
pub fn holds(attachment: &Attachment, x: &Vec3, v: &Vec3, h: f64) -> bool {
    let n = attachment.direction;
    let d = (x - attachment.point).dot(&n);
    d < 0.0 || d + h * v.dot(&n) < 0.0
}

/// A held attachment's penalty (see [`holds`]): `k d^2 / 2` for a particle at `x` a signed
/// distance `d` from the plane, its force `-k d n` along the normal and its Hessian
/// `k n n^T`. On either side while held, so that the implicit step, whose force is this one
/// plus the Hessian times the step's displacement, ends the particle on the plane, not
/// short of it or through it.
pub fn add_attachment(
    attachment: &Attachment,
    stiffness: f64,
    x: &Vec3,
    with_hessian: bool,
    out: &mut Local<1>,
) {
    let n = attachment.direction;
    let d = (x - attachment.point).dot(&n);
    out.energy += 0.5 * stiffness * d * d;
    out.grad[0] += stiffness * d * n;
    if with_hessian {
        out.hess[0][0] += stiffness * n * n.transpose();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn energy(a: &Attachment, k: f64, x: &Vec3) -> f64 {
        let mut l = Local::<1>::default();
        add_attachment(a, k, x, false, &mut l);
        l.energy
    }

    #[test]
    fn attachment_force_and_hessian_match_finite_differences() {
        let a = Attachment {
            particle: 0,
            point: Vec3::new(0.1, -0.2, 1.0),
            direction: Vec3::new(0.3, -0.4, 1.2).normalize(),
        };
        let k = 250.0;
        let eps = 1e-6;
        // On the wrong side and on the right one (held as it would cross).
        for x in [Vec3::new(0.05, -0.1, 0.97), Vec3::new(0.2, -0.3, 1.05)] {
            let mut l = Local::<1>::default();
            add_attachment(&a, k, &x, true, &mut l);
            for c in 0..3 {
                let mut e = Vec3::zeros();
                e[c] = eps;
                let fd = (energy(&a, k, &(x + e)) - energy(&a, k, &(x - e))) / (2.0 * eps);
                assert!(
                    (fd - l.grad[0][c]).abs() < 1e-6,
                    "gradient {c}: {fd} vs {}",
                    l.grad[0][c]
                );
                let mut lp = Local::<1>::default();
                let mut lm = Local::<1>::default();
                add_attachment(&a, k, &(x + e), true, &mut lp);
                add_attachment(&a, k, &(x - e), true, &mut lm);
                let column = (lp.grad[0] - lm.grad[0]) / (2.0 * eps);
                for r in 0..3 {
                    assert!(
                        (column[r] - l.hess[0][0][(r, c)]).abs() < 1e-4,
                        "hessian ({r}, {c}): {} vs {}",
                        column[r],
                        l.hess[0][0][(r, c)]
                    );
                }
            }
        }
    }

    #[test]
    fn an_attachment_holds_from_the_wrong_side_or_a_step_that_would_cross() {
        let a = Attachment {
            particle: 0,
            point: Vec3::zeros(),
            direction: Vec3::z(),
        };
        let (below, above) = (Vec3::new(0.3, 0.1, -0.01), Vec3::new(0.3, 0.1, 0.01));
        let still = Vec3::zeros();
        assert!(holds(&a, &below, &still, 0.1));
        assert!(
            holds(&a, &below, &Vec3::new(0.0, 0.0, 1.0), 0.1),
            "moving out, still below"
        );
        assert!(!holds(&a, &above, &still, 0.1));
        // 1 cm above, at 0.2 m/s down: through the plane within a step of 0.1 s, not of 0.01 s.
        let falling = Vec3::new(0.0, 0.0, -0.2);
        assert!(holds(&a, &above, &falling, 0.1));
        assert!(!holds(&a, &above, &falling, 0.01));
        assert!(
            !holds(&a, &above, &falling, 0.0),
            "an explicit step: the side alone"
        );
        // Held below, the force (minus the gradient) is k d along the normal: 1 N up.
        let mut l = Local::<1>::default();
        add_attachment(&a, 100.0, &below, true, &mut l);
        assert!((-l.grad[0] - Vec3::new(0.0, 0.0, 1.0)).norm() < 1e-12);
        assert_eq!(l.hess[0][0], 100.0 * Vec3::z() * Vec3::z().transpose());
    }
}
