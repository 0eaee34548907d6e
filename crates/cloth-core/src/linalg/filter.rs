//! The constraint filter of Baraff & Witkin in the projected form of Ascher & Boxerman
//! (2003): with `S` projecting out each constrained particle's constrained directions and
//! `z` the prescribed velocity changes in them, the step solves
//! `(S A S + I - S) y = S (b - A z)` and takes `dv = y + z`: a standard SPD system.
//! The matrix is never filtered in place: PCG applies the filter inside its operator, so
//! the same assembled matrix serves a re-solve with fewer constraints and the reaction
//! forces of the constrained rows.

use crate::math::{Mat3, Vec3};

/// A constraint the filter cannot hold.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum ConstraintError {
    #[error("constraint on particle {particle} has a zero or non-finite direction or velocity")]
    NotFinite { particle: usize },
    #[error("constraint on particle {particle}, but there are {count}")]
    NoSuchParticle { particle: usize, count: usize },
}

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

/// The constraints of one step. A particle constrained twice (a pin that also touches
/// a body) gets the union of the constrained directions.
#[derive(Debug, Clone, Default)]
pub struct Filter {
    /// (particle, S, prescribed velocity projected on the constrained directions).
    entries: Vec<(usize, Mat3, Vec3)>,
    /// Entry of each particle, or `u32::MAX`.
    slot: Vec<u32>,
}

impl Filter {
    /// A filter for `n` particles with room for `capacity` constraints before it grows.
    pub fn new(n: usize, capacity: usize) -> Self {
        Self {
            entries: Vec::with_capacity(capacity),
            slot: vec![u32::MAX; n],
        }
    }
    pub fn clear(&mut self) {
        for (p, ..) in &self.entries {
            self.slot[*p] = u32::MAX;
        }
        self.entries.clear();
    }

    /// Adds a constraint; a zero or non-finite direction or velocity is an error naming
    /// the particle.
    pub fn push(&mut self, c: &Constraint) -> Result<(), ConstraintError> {
        let direction = match c.kind {
            ConstraintKind::Fixed => None,
            ConstraintKind::Plane { normal } => Some(normal),
            ConstraintKind::Line { direction } => Some(direction),
        };
        let finite = |v: &Vec3| v.iter().all(|x| x.is_finite());
        if direction.is_some_and(|d| !finite(&d) || d.norm() < 1e-12) || !finite(&c.velocity) {
            return Err(ConstraintError::NotFinite { particle: c.particle });
        }
        if c.particle >= self.slot.len() {
            return Err(ConstraintError::NoSuchParticle {
                particle: c.particle,
                count: self.slot.len(),
            });
        }
        let s = c.kind.free_projection();
        let held = (Mat3::identity() - s) * c.velocity;
        match self.slot[c.particle] {
            u32::MAX => {
                self.slot[c.particle] = self.entries.len() as u32;
                self.entries.push((c.particle, s, held));
            }
            k => {
                let (_, s0, held0) = self.entries[k as usize];
                let (s1, held1) = merge(s0, held0, s, held);
                self.entries[k as usize] = (c.particle, s1, held1);
            }
        }
        Ok(())
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
        for (p, s, held) in &self.entries {
            z[*p] = held - (Mat3::identity() - s) * v0[*p];
        }
    }

    /// `S_r y`: one row of a vector projected (unchanged for a free particle).
    pub fn project_row(&self, r: usize, y: Vec3) -> Vec3 {
        match self.slot[r] {
            u32::MAX => y,
            k => self.entries[k as usize].1 * y,
        }
    }

    /// `S_r`: particle `r`'s projection onto its free directions.
    pub fn free_projection(&self, r: usize) -> Mat3 {
        match self.slot[r] {
            u32::MAX => Mat3::identity(),
            k => self.entries[k as usize].1,
        }
    }

    /// Diagonal block `r` of the filtered matrix `S A S + I - S`, given `A`'s block `d`.
    pub fn filtered_diagonal(&self, r: usize, d: &Mat3) -> Mat3 {
        match self.slot[r] {
            u32::MAX => *d,
            k => {
                let s = &self.entries[k as usize].1;
                s * d * s + (Mat3::identity() - s)
            }
        }
    }

    /// Replaces the constrained components of `v` by their prescribed values.
    pub fn enforce_velocity(&self, v: &mut [Vec3]) {
        for (p, s, held) in &self.entries {
            v[*p] = s * v[*p] + held;
        }
    }
}

/// Two constraints on one particle. A pin (nothing free) wins outright. Otherwise the
/// constrained directions are united, directions closer than about 6 degrees counting
/// as one, and the prescribed velocities are met in the least-squares sense.
fn merge(s0: Mat3, held0: Vec3, s1: Mat3, held1: Vec3) -> (Mat3, Vec3) {
    if s0 == Mat3::zeros() {
        return (s0, held0);
    }
    if s1 == Mat3::zeros() {
        return (s1, held1);
    }
    let m = (Mat3::identity() - s0) + (Mat3::identity() - s1);
    let eig = m.symmetric_eigen();
    let largest = eig.eigenvalues.max();
    let (mut constrained, mut pinv) = (Mat3::zeros(), Mat3::zeros());
    for k in 0..3 {
        // Eigenvalue 1 - cos(angle) for two planes at that angle: 1e-2 is about 6 degrees.
        if eig.eigenvalues[k] > 1e-2 * largest {
            let e = eig.eigenvectors.column(k);
            constrained += e * e.transpose();
            pinv += e * e.transpose() / eig.eigenvalues[k];
        }
    }
    (
        Mat3::identity() - constrained,
        constrained * pinv * (held0 + held1),
    )
}
