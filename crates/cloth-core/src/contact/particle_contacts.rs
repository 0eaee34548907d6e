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

/// Speed, m/s, below which a velocity or a reaction impulse (per unit mass) is rounding
/// noise. Decisions (release, moving away) wait for a clear sign, so that mirror-image
/// particles of a symmetric scene always decide alike.
const NOISE_SPEED: f64 = 1e-9;

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
    pub normal: Vec3,
    pub body_velocity: Vec3,
    /// Normal speed relative to the body that corrects the position (back out towards the
    /// thickness, or down onto it). It moves the particle but is not kept as velocity, so
    /// it adds no energy.
    pub correction: f64,
    /// Coulomb coefficient (infinite: no slip).
    pub friction: f64,
    /// Held by friction: a viscous drag `mu p / SLIP_SPEED` (N s/m) against tangential
    /// motion (0 with no slip, which the constraint holds).
    pub drag: f64,
    /// Sliding: the kinetic friction force, `mu p` against the sliding direction, N.
    pub kinetic: Vec3,
    /// The drag and force already in the system (the matrix and right-hand side take
    /// differences).
    applied_drag: f64,
    applied_kinetic: Vec3,
    /// Normal force friction is measured by, N.
    pressure: f64,
    /// The pressure friction uses is not known yet (a new contact): the first solve finds it.
    fresh: bool,
    /// Still holding the particle (false once released within the step).
    pub live: bool,
    /// A normal reaction below minus this, N, is the body pulling.
    pull_limit: f64,
    /// Force the constraint exerted over the step, N.
    pub reaction: Vec3,
}

impl ActiveContact {
    pub fn particle(&self) -> usize {
        self.constraint.particle
    }
    /// Coulomb friction for sticking (drag regularised at [`SLIP_SPEED`]) or for sliding
    /// along `tangential` (the relative tangential velocity).
    fn set_friction(&mut self, mode: ContactMode, tangential: &Vec3) {
        if !self.friction.is_finite() {
            return;
        }
        let limit = self.friction * self.pressure;
        match tangential.try_normalize(1e-12) {
            Some(t) if mode == ContactMode::Slide => {
                self.drag = 0.0;
                self.kinetic = -limit * t;
            }
            _ => {
                self.drag = limit / SLIP_SPEED;
                self.kinetic = Vec3::zeros();
            }
        }
    }

    fn pressure(&self) -> f64 {
        self.reaction.dot(&self.normal)
    }
    /// The body had to pull the particle to hold it.
    pub fn pulls(&self) -> bool {
        self.pressure() < -self.pull_limit
    }
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
    pub fn constrain(&mut self, h: f64, v: &[Vec3], masses: &[f64], pinned: &[bool]) {
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
            if s.released && relative.dot(&n) > NOISE_SPEED {
                s.mode = ContactMode::Free;
                continue;
            }
            s.released = false;
            let fresh = s.mode == ContactMode::Free;
            // The normal speed prescribed relative to the body, not kept after the step. A
            // particle inside the layer is carried back out over a few steps. One above it
            // keeps its speed towards the body, but lands on the layer rather than crossing
            // into it, and then stops: stopping it at once would leave it hanging above the
            // body, to fall again and bounce in and out of contact.
            let correction = if p.gap() <= 0.0 {
                -CORRECTION_RATE * p.gap() / h
            } else {
                relative.dot(&n).max(-p.gap() / h).min(0.0)
            };
            let tangential = relative - relative.dot(&n) * n;
            let sliding = tangential.norm();
            let (kind, velocity) = if p.friction == f64::INFINITY {
                s.mode = ContactMode::Stick;
                (ConstraintKind::Fixed, p.velocity + correction * n)
            } else {
                s.mode = if sliding > SLIP_SPEED {
                    ContactMode::Slide
                } else {
                    ContactMode::Stick
                };
                (
                    ConstraintKind::Plane { normal: n },
                    (n.dot(&p.velocity) + correction) * n,
                )
            };
            self.active.push(ActiveContact {
                constraint: Constraint {
                    particle: i,
                    kind,
                    velocity,
                },
                normal: n,
                body_velocity: p.velocity,
                correction,
                friction: p.friction,
                drag: 0.0,
                kinetic: Vec3::zeros(),
                applied_drag: 0.0,
                applied_kinetic: Vec3::zeros(),
                pressure: s.pressure,
                fresh,
                live: true,
                pull_limit: masses[i] * NOISE_SPEED / h,
                reaction: Vec3::zeros(),
            });
            if let Some(c) = self.active.last_mut() {
                c.set_friction(s.mode, &tangential);
            }
        }
    }

    /// Adds the active contacts to the filter.
    pub fn push_constraints(&self, filter: &mut Filter) -> Result<(), String> {
        self.active
            .iter()
            .filter(|c| c.live)
            .try_for_each(|c| filter.push(&c.constraint))
    }

    /// Lets go of the contacts whose body had to pull (negative normal reaction): they are
    /// free for the rest of the step and while they move away. Returns how many.
    pub fn release_pulling(&mut self) -> usize {
        let mut released = 0;
        for c in self.active.iter_mut().filter(|c| c.live && c.pulls()) {
            let s = &mut self.state[c.particle()];
            s.released = true;
            s.mode = ContactMode::Free;
            s.pressure = 0.0;
            c.live = false;
            released += 1;
        }
        released
    }

    /// Friction from the step just solved: a new contact takes its pressure from the
    /// reaction; a held contact that had to slip faster than [`SLIP_SPEED`] (its drag
    /// exceeding `mu p`) slides; a sliding one whose sliding turned back sticks. Returns
    /// how many changed (the step is then solved again). `v_new` is the solved velocity.
    pub fn settle_friction(&mut self, v_new: impl Fn(usize) -> Vec3) -> usize {
        let mut changed = 0;
        for c in self
            .active
            .iter_mut()
            .filter(|c| c.live && c.friction.is_finite())
        {
            let rel = v_new(c.particle()) - c.body_velocity;
            let tangential = rel - rel.dot(&c.normal) * c.normal;
            let mut mode = if c.kinetic == Vec3::zeros() {
                ContactMode::Stick
            } else {
                ContactMode::Slide
            };
            let mut update = false;
            if c.fresh {
                c.fresh = false;
                let pressure = c.pressure();
                if pressure > c.pull_limit {
                    c.pressure = pressure;
                    update = true;
                }
            }
            if mode == ContactMode::Stick && tangential.norm() > SLIP_SPEED * (1.0 + 1e-6) && c.pressure > 0.0
            {
                mode = ContactMode::Slide;
                update = true;
            } else if mode == ContactMode::Slide && tangential.dot(&c.kinetic) > 0.0 {
                mode = ContactMode::Stick;
                update = true;
            }
            if update {
                c.set_friction(mode, &tangential);
                changed += 1;
            }
        }
        changed
    }

    /// Brings the friction in the system up to date: the drag `-c P (v - v_body)` (P the
    /// tangential projection) as `b += h F(v0)`, `A += h c P`, and the kinetic force as
    /// `b += h F`, for the change in each (a released contact's go to zero).
    pub fn apply_friction(&mut self, v0: &[Vec3], b: &mut [Vec3], a: &mut BlockSparse, h: f64) {
        for c in &mut self.active {
            let (drag, kinetic) = if c.live {
                (c.drag, c.kinetic)
            } else {
                (0.0, Vec3::zeros())
            };
            let i = c.particle();
            b[i] += h * (kinetic - c.applied_kinetic);
            c.applied_kinetic = kinetic;
            let change = drag - c.applied_drag;
            if change == 0.0 {
                continue;
            }
            c.applied_drag = drag;
            let p = Mat3::identity() - c.normal * c.normal.transpose();
            b[i] -= (h * change) * (p * (v0[i] - c.body_velocity));
            let d = a.diag_slot(i);
            a.blocks_mut()[d] += (h * change) * p;
        }
    }

    /// Reaction forces after an implicit solve of `A dv = b`: the constrained rows'
    /// residual `(A dv - b) / h`, what the body had to add for the prescribed velocities.
    /// The solve is exact only to its relative tolerance `accuracy`: a pull smaller than
    /// ten times that of the row's own force is solver noise, not the body pulling.
    pub fn implicit_reactions(
        &mut self,
        a: &BlockSparse,
        b: &[Vec3],
        dv: impl Fn(usize) -> Vec3,
        h: f64,
        accuracy: f64,
    ) {
        for c in self.active.iter_mut().filter(|c| c.live) {
            let i = c.particle();
            c.pull_limit = c.pull_limit.max(10.0 * accuracy * b[i].norm() / h);
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
            let i = c.particle();
            c.reaction = masses[i] * (v_new[i] - v0[i]) / h - force[i];
        }
    }

    /// Coulomb friction for the explicit integrators, as an impulse from this step's
    /// pressure that can stop the sliding but never turn it back (Bridson et al. 2002); a
    /// drag of `mu p / SLIP_SPEED` would be far beyond an explicit step's stability.
    pub fn explicit_friction(&self, masses: &[f64], v_new: &mut [Vec3], h: f64) {
        for c in self.active.iter().filter(|c| c.live && c.friction.is_finite()) {
            let i = c.particle();
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
        for c in self.active.iter().filter(|c| c.live) {
            let state = &mut self.state[c.particle()];
            state.pressure = c.reaction.dot(&c.normal).max(0.0);
            if c.friction.is_finite() {
                state.mode = if c.kinetic == Vec3::zeros() {
                    ContactMode::Stick
                } else {
                    ContactMode::Slide
                };
            }
            v_new[c.particle()] -= c.correction * c.normal;
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
