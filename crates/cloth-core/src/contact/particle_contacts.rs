//! Contacts of cloth particles with rigid bodies: the source's boundary condition
//! `r'|S = 0` as a velocity constraint in the filter, Coulomb friction, release when the
//! body would have to pull, and the continuous end-of-step test that keeps particles out.

use super::{Collider, Proximity};
use crate::linalg::{BlockSparse, Constraint, ConstraintKind, Filter};
use crate::{Mat3, Vec3};
use rayon::prelude::*;

/// A particle closer to the surface than `(1 + CONTACT_BAND) * thickness` is in contact.
/// Particles corrected out land at exactly the thickness; the band keeps a resting particle
/// in contact despite the rounding and the curvature of the body under a sliding particle.
const CONTACT_BAND: f64 = 0.1;

/// Fraction of a particle's depth in the contact layer that one step carries it back out.
/// All at once would jerk its neighbours; a fraction relaxes it out over a few steps.
const CORRECTION_RATE: f64 = 0.3;

/// Sliding speed, m/s, under which Coulomb friction is regularised into viscous drag
/// `mu p / SLIP_SPEED`: a particle held by friction creeps at most this fast (times the
/// ratio of the traction to its limit), and the friction never switches discontinuously.
pub const SLIP_SPEED: f64 = 1e-4;

/// How a particle touches a body in this step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ContactMode {
    /// Not constrained.
    #[default]
    Free,
    /// Held by friction: no slip (infinite coefficient) or sliding slower than
    /// [`SLIP_SPEED`].
    Stick,
    /// Held in the normal direction, sliding against kinetic friction.
    Slide,
}

/// One particle's contact state, kept from step to step.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ParticleState {
    pub proximity: Proximity,
    pub mode: ContactMode,
    /// The body pulled on the particle in its last constrained step: it is let go while it
    /// moves away.
    pub released: bool,
    /// Normal force the body exerted in the last step, N (what friction is measured by).
    pub pressure: f64,
}

/// A contact constrained in the current step.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ActiveContact {
    pub constraint: Constraint,
    pub particle: usize,
    pub normal: Vec3,
    pub body_velocity: Vec3,
    /// Normal speed that carries the particle back out towards the thickness. It moves the
    /// particle but is not kept as velocity, so it adds no energy.
    pub correction: f64,
    /// Coulomb coefficient (infinite: no slip).
    pub friction: f64,
    /// Viscous coefficient of the linearised Coulomb friction, N s/m (0 with no slip).
    pub drag: f64,
    /// Force the constraint exerted over the step, N.
    pub reaction: Vec3,
}

/// Counters of one step's contact handling.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct SweepCounts {
    pub corrected: usize,
    pub crossings: usize,
}

/// Per-particle contact state and the scratch of the contact stages.
#[derive(Debug)]
pub(crate) struct ParticleContacts {
    pub state: Vec<ParticleState>,
    pub active: Vec<ActiveContact>,
    /// How far beyond the thickness a query looks, m.
    reach: f64,
}

impl ParticleContacts {
    pub fn new(n: usize, reach: f64) -> Self {
        Self {
            state: vec![
                ParticleState {
                    proximity: Proximity::Far {
                        gap_lower_bound: f64::NEG_INFINITY,
                    },
                    mode: ContactMode::Free,
                    released: false,
                    pressure: 0.0,
                };
                n
            ],
            active: Vec::with_capacity(n),
            reach,
        }
    }

    /// Queries every particle afresh (at the start, or after positions were set).
    pub fn refresh(&mut self, collider: &dyn Collider, t: f64, x: &[Vec3], parallel: bool) {
        let reach = self.reach;
        let query = |(s, xi): (&mut ParticleState, &Vec3)| {
            s.proximity = collider.sweep(t, xi, t, xi, f64::INFINITY, reach);
            s.mode = ContactMode::Free;
            s.released = false;
            s.pressure = 0.0;
        };
        if parallel {
            self.state.par_iter_mut().zip(x).for_each(query);
        } else {
            self.state.iter_mut().zip(x).for_each(query);
        }
    }

    /// Chooses the particles in contact for a step of length `h` from `v`, and their
    /// constraints: no velocity into the body; with no slip, none along it either.
    pub fn constrain(&mut self, h: f64, v: &[Vec3], pinned: &[bool]) {
        self.active.clear();
        for (i, s) in self.state.iter_mut().enumerate() {
            let Proximity::Near(p) = s.proximity else {
                s.mode = ContactMode::Free;
                continue;
            };
            let n = p.normal;
            let relative = v[i] - p.velocity;
            // In contact when inside the band, or about to cross into the layer within the
            // step at its present speed: stopping it at the layer beats pushing it back out.
            let approach = p.gap() + h * relative.dot(&n).min(0.0);
            if pinned[i] || approach > CONTACT_BAND * p.thickness {
                s.mode = ContactMode::Free;
                s.released = false;
                s.pressure = 0.0;
                continue;
            }
            if s.released && relative.dot(&n) > 0.0 {
                s.mode = ContactMode::Free;
                continue;
            }
            s.released = false;
            let correction = CORRECTION_RATE * (-p.gap()).max(0.0) / h;
            let (kind, velocity, drag) = if p.friction == f64::INFINITY {
                s.mode = ContactMode::Stick;
                (ConstraintKind::Fixed, p.velocity + correction * n, 0.0)
            } else {
                // Coulomb friction mu p against the sliding, linearised as drag about the
                // sliding speed at the start of the step (regularised near zero).
                let sliding = (relative - relative.dot(&n) * n).norm();
                s.mode = if sliding > SLIP_SPEED {
                    ContactMode::Slide
                } else {
                    ContactMode::Stick
                };
                let drag = p.friction * s.pressure / sliding.max(SLIP_SPEED);
                let held = (n.dot(&p.velocity) + correction) * n;
                (ConstraintKind::Plane { normal: n }, held, drag)
            };
            self.active.push(ActiveContact {
                constraint: Constraint {
                    particle: i,
                    kind,
                    velocity,
                },
                particle: i,
                normal: n,
                body_velocity: p.velocity,
                correction,
                friction: p.friction,
                drag,
                reaction: Vec3::zeros(),
            });
        }
    }

    /// Adds the active contacts to the filter.
    pub fn push_constraints(&self, filter: &mut Filter) -> Result<(), String> {
        self.active.iter().try_for_each(|c| filter.push(&c.constraint))
    }

    /// Lets go of the contacts whose body had to pull (negative normal reaction): they are
    /// free for the rest of the step and while they move away. Returns how many.
    pub fn release_pulling(&mut self) -> usize {
        let before = self.active.len();
        let state = &mut self.state;
        self.active.retain(|c| {
            let pulling = c.reaction.dot(&c.normal) < 0.0;
            if pulling {
                let s = &mut state[c.particle];
                s.released = true;
                s.mode = ContactMode::Free;
                s.pressure = 0.0;
            }
            !pulling
        });
        before - self.active.len()
    }

    /// The friction drag `-c P (v - v_body)` (P the tangential projection) at `v0`, times
    /// `scale`, added to `force`.
    pub fn add_friction_force(&self, v0: &[Vec3], force: &mut [Vec3], scale: f64) {
        for c in self.active.iter().filter(|c| c.drag > 0.0) {
            let rel = v0[c.particle] - c.body_velocity;
            let tangential = rel - rel.dot(&c.normal) * c.normal;
            force[c.particle] -= (scale * c.drag) * tangential;
        }
    }

    /// Its velocity Jacobian into the system matrix: `A_ii += scale c P`.
    pub fn add_friction_jacobian(&self, a: &mut BlockSparse, scale: f64) {
        for c in self.active.iter().filter(|c| c.drag > 0.0) {
            let p = Mat3::identity() - c.normal * c.normal.transpose();
            let d = a.diag_slot(c.particle);
            a.blocks_mut()[d] += (scale * c.drag) * p;
        }
    }

    /// Reaction forces after an implicit solve of `A dv = b`: the constrained rows'
    /// residual `(A dv - b) / h`, what the body had to add for the prescribed velocities.
    pub fn implicit_reactions(&mut self, a: &BlockSparse, b: &[Vec3], dv: impl Fn(usize) -> Vec3, h: f64) {
        for c in &mut self.active {
            let i = c.particle;
            let mut r = -b[i];
            for slot in a.row(i) {
                r += a.blocks()[slot] * dv(a.col_of(slot));
            }
            c.reaction = r / h;
        }
    }

    /// Reaction forces after an explicit step: `m (v_constrained - v_free) / h` with
    /// `v_free = v0 + h F / m`.
    pub fn explicit_reactions(
        &mut self,
        masses: &[f64],
        v0: &[Vec3],
        force: &[Vec3],
        v_new: &[Vec3],
        h: f64,
    ) {
        for c in &mut self.active {
            let i = c.particle;
            c.reaction = masses[i] * (v_new[i] - v0[i]) / h - force[i];
        }
    }

    /// Coulomb friction for the explicit integrators, as an impulse from this step's
    /// pressure that can stop the sliding but never turn it back (Bridson et al. 2002); a
    /// drag of `mu p / SLIP_SPEED` would be far beyond an explicit step's stability.
    pub fn explicit_friction(&self, masses: &[f64], v_new: &mut [Vec3], h: f64) {
        for c in self.active.iter().filter(|c| c.friction.is_finite()) {
            let i = c.particle;
            let n = c.normal;
            let rel = v_new[i] - c.body_velocity;
            let tangential = rel - rel.dot(&n) * n;
            let speed = tangential.norm();
            let brake = c.friction * c.reaction.dot(&n).max(0.0) * h / masses[i];
            let kept = if speed <= brake { 0.0 } else { 1.0 - brake / speed };
            v_new[i] -= (1.0 - kept) * tangential;
        }
    }

    /// Keeps each contact's pressure for the next step's friction, and takes the push-out
    /// speed back out of the kept velocity. Contacts released within the step are no
    /// longer active and keep their free motion.
    pub fn finish(&mut self, v_new: &mut [Vec3]) {
        for c in &self.active {
            let state = &mut self.state[c.particle];
            state.pressure = c.reaction.dot(&c.normal).max(0.0);
            v_new[c.particle] -= c.correction * c.normal;
        }
    }

    /// The end-of-step test along every particle's path from `x` (time `t0`) to `x_new`
    /// (`t1`): a particle that entered a body or ended inside its contact layer is put back
    /// at the thickness along the surface normal and loses its velocity into the body.
    #[allow(clippy::too_many_arguments)]
    pub fn sweep(
        &mut self,
        collider: &dyn Collider,
        t0: f64,
        t1: f64,
        x: &[Vec3],
        x_new: &mut [Vec3],
        v_new: &mut [Vec3],
        pinned: &[bool],
        parallel: bool,
    ) -> SweepCounts {
        let reach = self.reach;
        let body_motion = collider.motion_bound(t0, t1);
        let visit = |(((s, x0), x1), v1): (((&mut ParticleState, &Vec3), &mut Vec3), &mut Vec3),
                     pinned: bool|
         -> SweepCounts {
            let start_bound = s.proximity.gap_lower_bound();
            let moved = (*x1 - x0).norm() + body_motion;
            if pinned || start_bound - moved > reach {
                // Provably still far: no query.
                s.proximity = Proximity::Far {
                    gap_lower_bound: start_bound - moved,
                };
                return SweepCounts::default();
            }
            let mut proximity = collider.sweep(t0, x0, t1, x1, start_bound, reach);
            let mut counts = SweepCounts::default();
            if let Proximity::Near(p) = &mut proximity {
                if p.crossed || p.distance < 0.0 {
                    counts.corrected = 1;
                    counts.crossings = p.crossed as usize;
                    *x1 = p.point + p.thickness * p.normal;
                    let into = (*v1 - p.velocity).dot(&p.normal);
                    if into < 0.0 {
                        *v1 -= into * p.normal;
                    }
                    p.distance = p.thickness;
                    p.crossed = false;
                }
            }
            s.proximity = proximity;
            counts
        };
        let add = |a: SweepCounts, b: SweepCounts| SweepCounts {
            corrected: a.corrected + b.corrected,
            crossings: a.crossings + b.crossings,
        };
        if parallel {
            self.state
                .par_iter_mut()
                .zip(x)
                .zip(x_new.par_iter_mut())
                .zip(v_new.par_iter_mut())
                .zip(pinned)
                .map(|(item, &p)| visit(item, p))
                .reduce(SweepCounts::default, add)
        } else {
            self.state
                .iter_mut()
                .zip(x)
                .zip(x_new.iter_mut())
                .zip(v_new.iter_mut())
                .zip(pinned)
                .map(|(item, &p)| visit(item, p))
                .fold(SweepCounts::default(), add)
        }
    }

    /// A lower bound on each particle's distance beyond the nearest body's thickness.
    pub fn gap_lower_bound(&self, i: usize) -> f64 {
        self.state[i].proximity.gap_lower_bound()
    }
}
