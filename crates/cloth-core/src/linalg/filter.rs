//! The constraint filter of Baraff & Witkin in the projected form of Ascher & Boxerman
//! (2003): with `S` projecting out each constrained particle's constrained directions and
//! `z` the prescribed velocity changes in them, the step solves
//! `(S A S + I - S) y = S (b - A z)` and takes `dv = y + z`: a standard SPD system.

use super::BlockSparse;
use crate::{Mat3, Vec3};

/// Which directions of a particle's velocity a constraint prescribes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ConstraintKind {
    /// All three (a pin).
    Fixed,
    /// The one along `normal` (a contact with a surface; free to slide in its plane).
    Plane { normal: Vec3 },
    /// The two across `direction` (free to slide along a line).
    Line { direction: Vec3 },
}

/// A constraint on one particle: its velocity at the end of the step has the components
/// of `velocity` in the constrained directions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Constraint {
    pub particle: usize,
    pub kind: ConstraintKind,
    pub velocity: Vec3,
}

impl ConstraintKind {
    /// `S`: the projection onto the free directions.
    pub fn free_projection(&self) -> Mat3 {
        match self {
            Self::Fixed => Mat3::zeros(),
            Self::Plane { normal } => {
                let n = normal.normalize();
                Mat3::identity() - n * n.transpose()
            }
            Self::Line { direction } => {
                let d = direction.normalize();
                d * d.transpose()
            }
        }
    }
}

/// The constraints of one step, indexed by particle.
#[derive(Debug, Clone, Default)]
pub struct Filter {
    /// (particle, S, prescribed velocity) in the order given.
    entries: Vec<(usize, Mat3, Vec3)>,
}

impl Filter {
    pub fn clear(&mut self) {
        self.entries.clear();
    }
    pub fn push(&mut self, c: &Constraint) {
        self.entries.push((c.particle, c.kind.free_projection(), c.velocity));
    }
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// `x <- S x`.
    pub fn project(&self, x: &mut [Vec3]) {
        for (p, s, _) in &self.entries {
            x[*p] = s * x[*p];
        }
    }

    /// `z`: the velocity change that brings the constrained components of `v0` to their
    /// prescribed values (zero for free particles).
    pub fn velocity_change(&self, v0: &[Vec3], z: &mut [Vec3]) {
        z.iter_mut().for_each(|zi| *zi = Vec3::zeros());
        for (p, s, target) in &self.entries {
            z[*p] = (Mat3::identity() - s) * (target - v0[*p]);
        }
    }

    /// `A <- S A S + I - S` in place, touching only the constrained rows and columns.
    pub fn filter_matrix(&self, a: &mut BlockSparse) {
        for (r, s, _) in &self.entries {
            for slot in a.row(*r) {
                a.blocks_mut()[slot] = s * a.blocks()[slot];
            }
        }
        for (c, s, _) in &self.entries {
            for slot in a.row(*c) {
                let t = a.transpose_slot(slot);
                a.blocks_mut()[t] = a.blocks()[t] * s;
            }
        }
        for (r, s, _) in &self.entries {
            let d = a.diag_slot(*r);
            a.blocks_mut()[d] += Mat3::identity() - s;
        }
    }

    /// Replaces the constrained components of `v` by their prescribed values.
    pub fn enforce_velocity(&self, v: &mut [Vec3]) {
        for (p, s, target) in &self.entries {
            v[*p] = s * v[*p] + (Mat3::identity() - s) * target;
        }
    }
}
