//! The repulsion between two layers of cloth closer than their thickness, and the
//! friction between them (Bridson, Fedkiw & Anderson 2002, in the implicit solve).
//!
//! A contact joins four particles by weights `w` (a particle and a triangle's point:
//! `1, -b0, -b1, -b2`; two edges' points: `1 - s, s, -(1 - t), -t`), so that `sum w x`
//! is the gap between the two points and `n . sum w x` its width along the contact's
//! normal `n`. The normal and the weights are those found at the start of the step and
//! are held for it: the energy is then a quadratic one-sided spring in the positions,
//! exact for the step's linearisation and convex.

use super::Local;
use crate::math::{Mat3, Vec3};

/// The four particles' weighting of one contact and its normal, held for a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactFrame {
    pub weights: [f64; 4],
    pub normal: Vec3,
}

impl ContactFrame {
    /// `sum w_k u_k`: the relative position (or velocity) of the two points.
    pub fn relative(&self, u: &[Vec3; 4]) -> Vec3 {
        (0..4).map(|k| self.weights[k] * u[k]).sum()
    }
    /// The width of the gap along the normal at positions `x`.
    pub fn gap(&self, x: &[Vec3; 4]) -> f64 {
        self.normal.dot(&self.relative(x))
    }
}

/// The repulsion's law on the gap `g` of a pair whose contact distance is `d`: a spring of
/// stiffness `k` at the distance that hardens as the pair is pressed together, its force
/// `f(g) = k (d - g) (d - m) / (g - m)` growing towards the least gap `m = d / 2` and its
/// stiffness `f'(g) = k ((d - m) / (g - m))^2`, until at a quarter of the way from `m` to
/// `d` it has reached `16 k`, and goes on linearly at that stiffness. A load that a linear
/// spring of `k` would let press layers through each other meets a stiffer spring the more
/// it presses, and only the contacts so pressed are stiff: stiff contacts cost iterations
/// of the linear solve (and a pair a sewn seam leaves nearly touching, several hundred
/// times `k` pressed as it is, tripled a garment's).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RepulsionLaw {
    /// The stiffness at the distance, N/m.
    pub stiffness: f64,
    /// The contact distance, m.
    pub distance: f64,
}

impl RepulsionLaw {
    /// The least gap the law lets a pair reach, over its contact distance.
    pub const LEAST_GAP: f64 = 0.5;
    /// Where the law turns linear, as a fraction of the way from the least gap to the
    /// distance.
    pub const LINEAR_BELOW: f64 = 0.25;

    fn least(&self) -> f64 {
        Self::LEAST_GAP * self.distance
    }

    /// `(E, f, f')` at gap `g`: the energy (zero at the distance), the force pushing the
    /// pair apart (negative beyond the distance: the law is one spring on either side of
    /// it within a step) and its stiffness `-df/dg`.
    pub fn at(&self, g: f64) -> (f64, f64, f64) {
        let (k, d, m) = (self.stiffness, self.distance, self.least());
        let span = d - m;
        let knee = m + Self::LINEAR_BELOW * span;
        let law = |g: f64| {
            let r = span / (g - m);
            let energy = k * span * (span * r.ln() - (d - g));
            (energy, k * (d - g) * r, k * r * r)
        };
        if g >= knee {
            law(g)
        } else {
            let (e, f, s) = law(knee);
            let below = knee - g;
            (e + f * below + 0.5 * s * below * below, f + s * below, s)
        }
    }
}

/// The repulsion's energy, gradient and Hessian `f'(g) w_a w_b n n^T` (positive
/// semi-definite) at positions `x`, added to `out`; returns the stiffness `f'(g)`. Whether a pair is in contact is
/// decided once a step (closer than the distance, or closing in on it); within the step
/// the contact is this spring.
pub fn add_repulsion(frame: &ContactFrame, law: &RepulsionLaw, x: &[Vec3; 4], out: &mut Local<4>) -> f64 {
    let (energy, force, stiffness) = law.at(frame.gap(x));
    let n = frame.normal;
    out.energy += energy;
    let nn = n * n.transpose();
    for a in 0..4 {
        out.grad[a] -= (force * frame.weights[a]) * n;
        for b in 0..4 {
            out.hess[a][b] += (stiffness * frame.weights[a] * frame.weights[b]) * nn;
        }
    }
    stiffness
}

/// Friction as a viscous drag `c` against the two points' sliding past each other: the
/// dissipation `D = c/2 |P sum w v|^2` (`P` the projection across the normal), whose
/// gradient in the velocities is minus the drag force and whose Hessian
/// `c w_a w_b P` is the force's Jacobian `-dF/dv`, added to `out`.
pub fn add_friction_drag(frame: &ContactFrame, drag: f64, v: &[Vec3; 4], out: &mut Local<4>) {
    let n = frame.normal;
    let p = Mat3::identity() - n * n.transpose();
    let sliding = p * frame.relative(v);
    out.energy += 0.5 * drag * sliding.norm_squared();
    for a in 0..4 {
        out.grad[a] += (drag * frame.weights[a]) * sliding;
        for b in 0..4 {
            out.hess[a][b] += (drag * frame.weights[a] * frame.weights[b]) * p;
        }
    }
}
