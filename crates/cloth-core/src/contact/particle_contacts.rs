//! Contacts of cloth particles with rigid bodies: the source's boundary condition
//! `r'|S = 0` as a velocity constraint in the filter, Coulomb friction, release when the
//! body would have to pull, and the continuous end-of-step test that keeps particles out.

use super::{Collider, ParticlePath, Proximity, StepEnd, StepStart, SurfacePoint};
use crate::linalg::{BlockSparse, Constraint, ConstraintError, ConstraintKind, Filter};
use crate::math::{Mat3, Vec3};
use crate::parallelism::Parallelism;
use rayon::prelude::*;

/// A particle closer to the surface than `(1 + CONTACT_BAND) * thickness` is in contact.
/// Particles corrected out land at exactly the thickness; the band keeps a resting particle
/// in contact despite the rounding and the curvature of the body under a sliding particle.
const CONTACT_BAND: f64 = 0.1;

/// Fraction of a particle's depth in the contact layer that one step carries it back out.
/// All at once would jerk its neighbours; a fraction relaxes it out over a few steps.
const CORRECTION_RATE: f64 = 0.3;

/// The fastest a particle is carried back out, m/s. A fraction of the depth per step is a
/// speed of `depth / h`, which a step taken again in short substeps would make ever
/// faster: a particle 2 cm deep at a 64th of a sewing step, 20 m/s, dragging its
/// neighbours along.
const CORRECTION_SPEED: f64 = 0.5;

/// Sliding speed, m/s, under which Coulomb friction is regularised into viscous drag
/// `mu p / SLIP_SPEED`: a particle held by friction creeps at most this fast (times the
/// ratio of the traction to its limit).
pub const SLIP_SPEED: f64 = 1e-4;

/// Speed, m/s, below which a velocity or a reaction impulse (per unit mass) is rounding
/// noise. Decisions (release, moving away) wait for a clear sign, so that mirror-image
/// particles of a symmetric scene always decide alike.
const NOISE_SPEED: f64 = 1e-9;

/// Nothing known of where a particle is: the next step asks.
const UNKNOWN: Proximity = Proximity::Far {
    gap_lower_bound: f64::NEG_INFINITY,
};

/// How a particle touches a body in this step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ContactMode {
    /// Not constrained.
    #[default]
    Free,
    /// Held by friction: no slip (infinite coefficient), or friction can stop it within
    /// the step (it creeps slower than [`SLIP_SPEED`]).
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
    /// The force on the particle in its last step other than its contact's (elastic,
    /// gravity, air, sharp features), N, as the implicit solve applied it: `m dv / h` less
    /// the contact's reaction and friction. Friction in the next step is set to hold this force, or to
    /// slide against it.
    pub demand: Vec3,
    /// `demand` is from a step of the present motion (not before the first step, nor
    /// after positions or velocities were set).
    pub demand_known: bool,
    /// The particle is of a piece passing through the bodies' thin parts (see
    /// [`PassThrough`]): they are not there for it.
    pub passing: bool,
    /// `passing` when the step began, for a step taken again.
    passing_at_start: bool,
    /// Of a piece passing until out, whose particles are watched for being inside a body.
    watched: bool,
    /// The particle ended the last step inside a body (kept for the watched particles).
    inside: bool,
}

/// A piece of cloth (a panel) that passes through the bodies' thin parts (hands,
/// forearms, ears, feet: see [`crate::Collider::sweep_past_thin_parts`]) while the thick
/// ones hold it as any cloth. Placed through a hand, a panel held by it would hang on it,
/// pushed out to the nearest side; passed particle by particle, its particles outside the
/// hand would catch on it as the piece moves past, and those the hand's section reaches
/// would be thrown out of it when let go. So the whole piece passes, `until_out` it ends a
/// step with none of its particles inside a body, or for the whole simulation (a skirt
/// sewn round the hips of a body whose hands hang inside its panels).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct PassThrough {
    /// Every particle of the piece.
    pub members: Vec<usize>,
    pub until_out: bool,
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
    /// Friction as a viscous drag against the tangential velocity relative to the body,
    /// N s/m (see [`ParticleContacts::set_friction`]; 0 with no slip, which the
    /// constraint holds).
    pub drag: f64,
    /// The drag already in the system (the matrix and right-hand side take differences).
    applied_drag: f64,
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
    /// The tangential projection of the contact.
    fn tangential(&self, u: &Vec3) -> Vec3 {
        u - u.dot(&self.normal) * self.normal
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
    /// Each particle's fabric's Coulomb coefficient, for bodies that do not set their own.
    pub(super) cloth_friction: Vec<f64>,
    /// What of the friction on the bodies acts (1 all, 0 none; see
    /// [`super::Contacts::scale_friction`]).
    pub(super) friction_scale: f64,
    /// The pieces passing through the bodies (done when their members no longer pass).
    pass_through: Vec<PassThrough>,
}

impl ParticleContacts {
    pub fn new(reach: f64, cloth_friction: Vec<f64>) -> Self {
        let n = cloth_friction.len();
        Self {
            state: vec![
                ParticleState {
                    proximity: UNKNOWN,
                    mode: ContactMode::Free,
                    released: false,
                    demand: Vec3::zeros(),
                    demand_known: false,
                    passing: false,
                    passing_at_start: false,
                    watched: false,
                    inside: false,
                };
                n
            ],
            pass_through: Vec::new(),
            active: Vec::with_capacity(n),
            reach,
            cloth_friction,
            friction_scale: 1.0,
        }
    }

    /// The Coulomb coefficient between particle `i` and a body whose own is `own` (the
    /// particle's fabric's where it has none), times the friction scale.
    pub(super) fn friction(&self, own: Option<f64>, i: usize) -> f64 {
        coefficient(&self.cloth_friction, self.friction_scale, own, i)
    }

    /// Lets the pieces `pieces` pass through the bodies (see [`PassThrough`]).
    pub fn set_pass_through(&mut self, pieces: Vec<PassThrough>) {
        for piece in &pieces {
            for &i in &piece.members {
                let s = &mut self.state[i];
                s.passing = true;
                s.watched = piece.until_out;
                s.proximity = UNKNOWN;
                // Until the first step has looked.
                s.inside = piece.until_out;
            }
        }
        self.pass_through = pieces;
    }

    /// Puts back which particles were passing when the step began (the step is taken
    /// again).
    pub fn rewind_passing(&mut self) {
        self.state.iter_mut().for_each(|s| s.passing = s.passing_at_start);
    }

    /// The pieces still passing through the bodies.
    pub fn passing(&self) -> impl Iterator<Item = &PassThrough> + '_ {
        self.pass_through
            .iter()
            .filter(|p| p.members.first().is_some_and(|&i| self.state[i].passing))
    }

    /// Ends the passing of each piece passing until out with none of its particles inside
    /// a body.
    fn finish_passing(&mut self) {
        for piece in self.pass_through.iter().filter(|p| p.until_out) {
            let passing = piece.members.first().is_some_and(|&i| self.state[i].passing);
            if passing && !piece.members.iter().any(|&i| self.state[i].inside) {
                for &i in &piece.members {
                    let s = &mut self.state[i];
                    s.passing = false;
                    // What it knew was of the thick parts: the next step asks afresh.
                    s.proximity = UNKNOWN;
                }
            }
        }
    }

    /// Queries every particle afresh (at the start, or after positions were set).
    pub fn refresh(&mut self, collider: &dyn Collider, t: f64, x: &[Vec3], par: Parallelism) {
        let reach = self.reach;
        let query = |(s, xi): (&mut ParticleState, &Vec3)| {
            s.proximity = sweep_for(
                collider,
                s.passing,
                &ParticlePath::still(t, *xi),
                f64::INFINITY,
                reach,
            );
            s.mode = ContactMode::Free;
            s.released = false;
            s.demand_known = false;
        };
        if par.is_rayon() {
            self.state.par_iter_mut().zip(x).for_each(query);
        } else {
            self.state.iter_mut().zip(x).for_each(query);
        }
    }

    /// Chooses the particles in contact for the step from `start`, and their
    /// constraints: no velocity into the body; with no slip, none along it either.
    /// A particle outside the contact layer that `on_cloth(i, normal)` finds lying on
    /// other cloth between it and the body (`normal` the body's) is left to that cloth.
    pub fn constrain(&mut self, start: &StepStart<'_>, on_cloth: impl Fn(usize, &Vec3) -> bool) {
        let StepStart {
            h, v, masses, pinned, ..
        } = *start;
        self.active.clear();
        for (i, s) in self.state.iter_mut().enumerate() {
            s.passing_at_start = s.passing;
            let Proximity::Near(p) = s.proximity else {
                s.mode = ContactMode::Free;
                continue;
            };
            let n = p.normal;
            let relative = v[i] - p.velocity;
            // In contact when inside the band, or about to cross into the layer within the
            // step at its present speed: stopping it at the layer beats pushing it back out.
            let approach = p.gap() + h * relative.dot(&n).min(0.0);
            if pinned[i] || approach > CONTACT_BAND * p.thickness || (p.gap() > 0.0 && on_cloth(i, &n)) {
                s.mode = ContactMode::Free;
                s.released = false;
                continue;
            }
            if s.released && relative.dot(&n) > NOISE_SPEED {
                s.mode = ContactMode::Free;
                continue;
            }
            s.released = false;
            // The normal speed prescribed relative to the body, not kept after the step. A
            // particle inside the layer is carried back out over a few steps. One above it
            // keeps its speed towards the body, but lands on the layer rather than crossing
            // into it, and then stops: stopping it at once would leave it hanging above the
            // body, to fall again and bounce in and out of contact.
            let correction = if p.gap() <= 0.0 {
                (-CORRECTION_RATE * p.gap() / h).min(CORRECTION_SPEED)
            } else {
                relative.dot(&n).max(-p.gap() / h).min(0.0)
            };
            let friction = coefficient(&self.cloth_friction, self.friction_scale, p.friction, i);
            let (kind, velocity) = if friction == f64::INFINITY {
                s.mode = ContactMode::Stick;
                (ConstraintKind::Fixed, p.velocity + correction * n)
            } else {
                // Until friction is set for the step (implicit) or applied (explicit).
                s.mode = ContactMode::Slide;
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
                friction,
                drag: 0.0,
                applied_drag: 0.0,
                live: true,
                pull_limit: masses[i] * NOISE_SPEED / h,
                reaction: Vec3::zeros(),
            });
        }
    }

    /// Coulomb friction for an implicit step from `v0`, as a drag `c` against the sliding
    /// velocity `u` relative to the body. Each contact predicts the step as Coulomb's law
    /// would end it for the particle alone: it meets the force `d` it met in the last step
    /// (see [`ParticleState::demand`]; `force` before the first step) and the pressure
    /// `p = m (u_n' - u_n) / h - d.n` that brings its normal speed `u_n` to the
    /// constraint's `u_n'`. Friction can take `h mu p / m` off the tangential speed
    /// `u* = |u + h d_t / m|` it would have without friction: when the slip left,
    /// `s = u* - h mu p / m`, exceeds [`SLIP_SPEED`], `c = mu p / s` ends it sliding at `s`
    /// against exactly `mu p`; otherwise `c = mu p / SLIP_SPEED` holds it. One solve
    /// settles the step: the drag is continuous in the state (no stick or slide to decide
    /// and re-solve), it cannot turn the sliding back, and within the solve it carries
    /// each contact's friction to its neighbours. The prediction lags the coupling by a
    /// step, as `demand` is the last step's.
    pub fn set_friction(&mut self, h: f64, v0: &[Vec3], masses: &[f64], force: &[Vec3]) {
        for c in self.active.iter_mut().filter(|c| c.friction.is_finite()) {
            let i = c.particle();
            let s = &mut self.state[i];
            let m = masses[i];
            let demand = if s.demand_known { s.demand } else { force[i] };
            let relative = v0[i] - c.body_velocity;
            let pressure =
                (m * (c.correction - relative.dot(&c.normal)) / h - demand.dot(&c.normal)).max(0.0);
            let limit = c.friction * pressure;
            let slip = c.tangential(&(relative + (h / m) * demand)).norm() - h * limit / m;
            (c.drag, s.mode) = if slip > SLIP_SPEED {
                (limit / slip, ContactMode::Slide)
            } else {
                (limit / SLIP_SPEED, ContactMode::Stick)
            };
        }
    }

    /// Adds the active contacts to the filter.
    pub fn push_constraints(&self, filter: &mut Filter) -> Result<(), ConstraintError> {
        self.active
            .iter()
            .filter(|c| c.live)
            .try_for_each(|c| filter.push(&c.constraint))
    }

    /// Lets go of the contacts whose body had to pull (negative normal reaction): they are
    /// free while they move away, and with `now` for the rest of the step too (which is
    /// then solved again). Without it they stay held to the step's end, as its last solve
    /// had them. Returns how many.
    pub fn release_pulling(&mut self, now: bool) -> usize {
        let mut released = 0;
        for c in self.active.iter_mut().filter(|c| c.live && c.pulls()) {
            let s = &mut self.state[c.particle()];
            s.released = true;
            if now {
                s.mode = ContactMode::Free;
                c.live = false;
            }
            released += 1;
        }
        released
    }

    /// Brings the friction in the system up to date: the drag `-c P (v - v_body)` (P the
    /// tangential projection) as `b += h F(v0)`, `A += h c P`, for its change (a released
    /// contact's goes to zero).
    pub fn apply_friction(&mut self, v0: &[Vec3], b: &mut [Vec3], a: &mut BlockSparse, h: f64) {
        for c in &mut self.active {
            let drag = if c.live { c.drag } else { 0.0 };
            let i = c.particle();
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
    pub fn implicit_reactions(&mut self, a: &BlockSparse, b: &[Vec3], dv: &[Vec3], h: f64, accuracy: f64) {
        for c in self.active.iter_mut().filter(|c| c.live) {
            let i = c.particle();
            c.pull_limit = c.pull_limit.max(10.0 * accuracy * b[i].norm() / h);
            c.reaction = (a.row_product(i, dv) - b[i]) / h;
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
    pub fn explicit_friction(&mut self, masses: &[f64], v_new: &mut [Vec3], h: f64) {
        for c in self.active.iter().filter(|c| c.live && c.friction.is_finite()) {
            let i = c.particle();
            let n = c.normal;
            let rel = v_new[i] - c.body_velocity;
            let tangential = rel - rel.dot(&n) * n;
            let speed = tangential.norm();
            let brake = c.friction * c.reaction.dot(&n).max(0.0) * h / masses[i];
            let kept = if speed <= brake { 0.0 } else { 1.0 - brake / speed };
            v_new[i] -= (1.0 - kept) * tangential;
            if kept == 0.0 {
                self.state[i].mode = ContactMode::Stick;
            }
        }
    }

    /// Takes the push-out speed back out of the kept velocity. Contacts released within
    /// the step are no longer active and keep their free motion.
    pub fn finish(&mut self, v_new: &mut [Vec3]) {
        for c in self.active.iter().filter(|c| c.live) {
            v_new[c.particle()] -= c.correction * c.normal;
        }
    }

    /// Keeps, after an implicit step from `v0` to `v_new`, the force each particle met
    /// other than its contact's (see [`ParticleState::demand`]) for the next step's friction.
    pub fn record_demand(&mut self, v0: &[Vec3], v_new: impl Fn(usize) -> Vec3, masses: &[f64], h: f64) {
        for (i, s) in self.state.iter_mut().enumerate() {
            s.demand = (masses[i] / h) * (v_new(i) - v0[i]);
            s.demand_known = true;
        }
        for c in self.active.iter().filter(|c| c.live) {
            let i = c.particle();
            let friction = -c.applied_drag * c.tangential(&(v_new(i) - c.body_velocity));
            self.state[i].demand -= c.reaction + friction;
        }
    }

    /// Drops the recorded demands: the next implicit step predicts friction from the forces
    /// at its start.
    pub fn forget_demand(&mut self) {
        self.state.iter_mut().for_each(|s| s.demand_known = false);
    }

    /// The end-of-step test along every particle's path from `end.x0` (at its start) to
    /// `end.x1` (at its end): a particle that entered a body or ended inside its contact layer is put back
    /// at the thickness along the surface normal and loses its velocity into the body.
    pub fn sweep(&mut self, collider: &dyn Collider, end: &mut StepEnd<'_>) -> SweepCounts {
        let (t0, t1) = (end.t0, end.t0 + end.h);
        let reach = self.reach;
        let body_motion = collider.motion_bound(t0, t1);
        let visit = |(((s, x0), x1), v1): (((&mut ParticleState, &Vec3), &mut Vec3), &mut Vec3),
                     pinned: bool|
         -> SweepCounts {
            if s.passing && s.watched {
                // Out once it ends the step clear of every body, thin parts and all (in the
                // contact layer at most, from where a later step's contact carries it out).
                let whole = collider.sweep(&ParticlePath::new(t0, *x0, t1, *x1), f64::NEG_INFINITY, reach);
                s.inside = matches!(whole, Proximity::Near(p) if p.distance < 0.0 || p.crossed);
            }
            let start_bound = s.proximity.gap_lower_bound();
            let moved = (*x1 - x0).norm() + body_motion;
            if pinned || start_bound - moved > reach {
                // Provably still far: no query.
                s.proximity = Proximity::Far {
                    gap_lower_bound: start_bound - moved,
                };
                return SweepCounts::default();
            }
            let mut proximity = sweep_for(
                collider,
                s.passing,
                &ParticlePath::new(t0, *x0, t1, *x1),
                start_bound,
                reach,
            );
            let mut counts = SweepCounts::default();
            if let Proximity::Near(p) = &mut proximity {
                if p.crossed || p.distance < 0.0 {
                    counts.corrected = 1;
                    counts.crossings = p.crossed as usize;
                    let passing = s.passing;
                    let query = |a: &Vec3, b: &Vec3| {
                        sweep_for(
                            collider,
                            passing,
                            &ParticlePath::new(t1, *a, t1, *b),
                            f64::NEG_INFINITY,
                            reach,
                        )
                    };
                    let (out, other) = out_of_pinch(p, query);
                    *x1 = out;
                    for wall in std::iter::once(&*p).chain(other.as_ref()) {
                        let into = (*v1 - wall.velocity).dot(&wall.normal);
                        if into < 0.0 {
                            *v1 -= into * wall.normal;
                        }
                    }
                    // Exactly the thickness where nothing was in the way.
                    p.distance = match other {
                        Some(_) => (out - p.point).dot(&p.normal),
                        None => p.thickness,
                    };
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
        let counts = if end.par.is_rayon() {
            self.state
                .par_iter_mut()
                .zip(&*end.x0)
                .zip(end.x1.par_iter_mut())
                .zip(end.v1.par_iter_mut())
                .zip(end.pinned)
                .map(|(item, &p)| visit(item, p))
                .reduce(SweepCounts::default, add)
        } else {
            self.state
                .iter_mut()
                .zip(end.x0)
                .zip(end.x1.iter_mut())
                .zip(end.v1.iter_mut())
                .zip(end.pinned)
                .map(|(item, &p)| visit(item, p))
                .fold(SweepCounts::default(), add)
        };
        self.finish_passing();
        counts
    }

    /// Particle `i` was moved by up to `d` after its last query: what is known of its gap
    /// shrinks by as much, so no query is skipped that should not be.
    pub fn displaced(&mut self, i: usize, d: f64) {
        match &mut self.state[i].proximity {
            Proximity::Near(p) => p.distance -= d,
            Proximity::Far { gap_lower_bound } => *gap_lower_bound -= d,
        }
    }

    /// A lower bound on each particle's distance beyond the nearest body's thickness.
    pub fn gap_lower_bound(&self, i: usize) -> f64 {
        self.state[i].proximity.gap_lower_bound()
    }

    /// As [`ParticleContacts::gap_lower_bound`] for sharp features, which leave the
    /// triangles of particles passing through the thin parts alone (most features are
    /// there: fingers, ears): infinite for those.
    pub fn feature_gap_bound(&self, i: usize) -> f64 {
        if self.state[i].passing {
            f64::INFINITY
        } else {
            self.gap_lower_bound(i)
        }
    }
}

/// The collider's sweep along `path` for a particle that is `passing` the bodies' thin
/// parts or not.
fn sweep_for(
    collider: &dyn Collider,
    passing: bool,
    path: &ParticlePath,
    start_bound: f64,
    reach: f64,
) -> Proximity {
    match passing {
        true => collider.sweep_past_thin_parts(path, start_bound, reach),
        false => collider.sweep(path, start_bound, reach),
    }
}

/// Where a particle found inside a body or past its surface, at `wall`, is put back out:
/// at the thickness along the wall's normal, unless the way there enters the body again,
/// as it does in a pinch (an arm lying against the trunk leaves a crease between them
/// narrower than their two contact layers: put out of one at its thickness, the particle
/// lands inside the other, and so to and fro until it rests inside one). There it goes
/// where it lies the thickness off both walls (their tangent planes), if that is near and
/// clear of the body, else halfway between them. `query(a, b)` is the collider's sweep
/// along the straight way from `a` to `b`. Returns where, and the other wall if any.
fn out_of_pinch(
    wall: &SurfacePoint,
    query: impl Fn(&Vec3, &Vec3) -> Proximity,
) -> (Vec3, Option<SurfacePoint>) {
    let (a, n) = (wall.point, wall.normal);
    let target = a + wall.thickness * n;
    // Just off the wall: the way out does not meet the wall itself.
    let start = a + PINCH_START * n;
    let Proximity::Near(other) = query(&start, &target) else {
        return (target, None);
    };
    if !other.crossed {
        return (target, None);
    }
    let halfway = 0.5 * (start + other.point);
    let (m, c) = (other.normal, n.dot(&other.normal));
    // The thickness off both tangent planes, nearest the target (which is on the first's):
    // `target + alpha n + beta m` with both planes met (`alpha + beta c = 0`,
    // `beta (1 - c^2) = short`); off the second alone when that clears the first.
    let short = other.thickness - (target - other.point).dot(&m);
    let off_both = if c >= 0.0 {
        target + short * m
    } else if 1.0 - c * c > 1e-12 {
        let beta = short / (1.0 - c * c);
        target - beta * c * n + beta * m
    } else {
        return (halfway, Some(other));
    };
    let near = (off_both - target).norm() <= PINCH_REACH * (wall.thickness + other.thickness);
    let clear =
        near && !matches!(query(&start, &off_both), Proximity::Near(q) if q.crossed || q.distance < 0.0);
    (if clear { off_both } else { halfway }, Some(other))
}

/// How far off a wall, m, the way out of a pinch starts (see [`out_of_pinch`]).
const PINCH_START: f64 = 1e-7;

/// How far from where one wall would put it a particle is moved out of a pinch, in the two
/// walls' thicknesses: the walls' tangent planes stand for them only so far.
const PINCH_REACH: f64 = 2.0;

/// The Coulomb coefficient between particle `i` and a body whose own is `own` (else the
/// particle's fabric's, `cloth_friction[i]`), times `scale`: none at a scale of zero, even
/// where the coefficient is infinite (a contact that sticks).
fn coefficient(cloth_friction: &[f64], scale: f64, own: Option<f64>, i: usize) -> f64 {
    if scale == 0.0 {
        0.0
    } else {
        scale * own.unwrap_or(cloth_friction[i])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A wall: a half-space of a body, `(x - point) . normal < 0` inside, with its contact
    /// thickness.
    struct Wall {
        point: Vec3,
        normal: Vec3,
        thickness: f64,
    }

    fn wall(point: [f64; 3], normal: [f64; 3], thickness: f64) -> Wall {
        Wall {
            point: Vec3::from(point),
            normal: Vec3::from(normal).normalize(),
            thickness,
        }
    }

    fn surface_point(w: &Wall, point: Vec3, distance: f64, crossed: bool) -> SurfacePoint {
        SurfacePoint {
            body: 0,
            point,
            normal: w.normal,
            distance,
            velocity: Vec3::zeros(),
            thickness: w.thickness,
            friction: None,
            crossed,
        }
    }

    /// The collider's sweep over a body made of `walls`: the first entry into one of them
    /// along the way, else inside one at its end, else far.
    fn sweep_of(walls: &[Wall]) -> impl Fn(&Vec3, &Vec3) -> Proximity + '_ {
        move |a, b| {
            let side = |w: &Wall, x: &Vec3| (x - w.point).dot(&w.normal);
            let entry = walls
                .iter()
                .filter(|w| side(w, a) >= 0.0 && side(w, b) < 0.0)
                .map(|w| (side(w, a) / (side(w, a) - side(w, b)), w))
                .min_by(|p, q| p.0.total_cmp(&q.0));
            if let Some((s, w)) = entry {
                let point = a + s * (b - a);
                return Proximity::Near(surface_point(w, point, side(w, b), true));
            }
            match walls.iter().find(|w| side(w, b) < 0.0) {
                Some(w) => Proximity::Near(surface_point(w, b - side(w, b) * w.normal, side(w, b), false)),
                None => Proximity::Far { gap_lower_bound: 0.0 },
            }
        }
    }

    /// Wall `walls[0]` found the particle crossed at the origin.
    fn put_out(walls: &[Wall]) -> (Vec3, Option<SurfacePoint>) {
        out_of_pinch(
            &surface_point(&walls[0], Vec3::zeros(), -1e-3, true),
            sweep_of(walls),
        )
    }

    fn assert_near(a: Vec3, b: Vec3) {
        assert!((a - b).norm() < 1e-9, "{a:?} against {b:?}");
    }

    #[test]
    fn a_particle_is_put_out_at_the_thickness_where_the_way_is_clear() {
        let floor = wall([0.0; 3], [0.0, 1.0, 0.0], 3e-3);
        let (out, other) = put_out(&[floor]);
        assert_near(out, Vec3::new(0.0, 3e-3, 0.0));
        assert!(other.is_none());
    }

    #[test]
    fn in_a_slot_narrower_than_its_two_layers_a_particle_is_put_halfway() {
        // Two walls 2 mm apart, each with a layer of 3 mm: put out of the floor at 3 mm, it
        // would be 1 mm inside the ceiling.
        let walls = [
            wall([0.0; 3], [0.0, 1.0, 0.0], 3e-3),
            wall([0.0, 2e-3, 0.0], [0.0, -1.0, 0.0], 3e-3),
        ];
        let (out, other) = put_out(&walls);
        assert_near(out, Vec3::new(0.0, 1e-3 + 0.5 * PINCH_START, 0.0));
        assert_near(other.unwrap().point, Vec3::new(0.0, 2e-3, 0.0));
    }

    #[test]
    fn in_a_wedge_a_particle_goes_where_it_is_a_thickness_off_both_walls() {
        // The floor and a wall 2 mm above the origin that rises at 30 degrees from it
        // along x: the two layers of 3 mm leave room 7.73 mm along x.
        let (sin, cos) = 30f64.to_radians().sin_cos();
        let walls = [
            wall([0.0; 3], [0.0, 1.0, 0.0], 3e-3),
            wall([0.0, 2e-3, 0.0], [sin, -cos, 0.0], 3e-3),
        ];
        let (out, other) = put_out(&walls);
        let x = (3e-3 + 1e-3 * cos) / sin;
        assert_near(out, Vec3::new(x, 3e-3, 0.0));
        let other = other.unwrap();
        assert!(((out - other.point).dot(&other.normal) - 3e-3).abs() < 1e-9);
        // A body in the way there (a third wall at x = 5 mm): halfway instead.
        let blocked = [
            wall([0.0; 3], [0.0, 1.0, 0.0], 3e-3),
            wall([0.0, 2e-3, 0.0], [sin, -cos, 0.0], 3e-3),
            wall([5e-3, 0.0, 0.0], [-1.0, 0.0, 0.0], 3e-3),
        ];
        let (out, _) = put_out(&blocked);
        assert!(out.x.abs() < 1e-12 && out.y > 0.0 && out.y < 2e-3, "{out:?}");
        // A wedge too narrow for the tangent planes to stand for the walls that far (5
        // degrees: 46 mm along x): halfway.
        let (sin, cos) = 5f64.to_radians().sin_cos();
        let narrow = [
            wall([0.0; 3], [0.0, 1.0, 0.0], 3e-3),
            wall([0.0, 2e-3, 0.0], [sin, -cos, 0.0], 3e-3),
        ];
        let (out, _) = put_out(&narrow);
        assert!(out.x.abs() < 1e-12 && (out.y - 1e-3).abs() < 1e-6, "{out:?}");
    }
}
