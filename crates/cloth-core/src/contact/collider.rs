//! The interface through which the solver sees rigid bodies. cloth-core knows nothing of
//! how a body is stored or queried; cloth-collide implements this on parry.

use crate::math::Vec3;

/// The body surface nearest a particle at the end of a motion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    /// Which body (the collider's own numbering).
    pub body: usize,
    /// The surface point, world frame, at the end of the motion.
    pub point: Vec3,
    /// Outward unit normal there.
    pub normal: Vec3,
    /// Signed distance of the particle from the surface, m (negative inside). After a
    /// crossing it is the depth behind the entry point's tangent plane.
    pub distance: f64,
    /// Velocity of the surface at `point`, m/s.
    pub velocity: Vec3,
    /// The body's contact thickness, m: particles are kept this far out.
    pub thickness: f64,
    /// Coulomb coefficient between the cloth and this body (`f64::INFINITY`: no slip);
    /// `None` when the body leaves it to the fabric's own coefficient.
    pub friction: Option<f64>,
    /// The particle's path entered the body during the motion; `point` is the entry.
    pub crossed: bool,
}

impl SurfacePoint {
    /// Distance beyond the contact thickness (negative: inside the contact layer).
    pub fn gap(&self) -> f64 {
        self.distance - self.thickness
    }
}

/// A particle's straight way over a step: from `x0` at time `t0` to `x1` at `t1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParticlePath {
    pub t0: f64,
    pub x0: Vec3,
    pub t1: f64,
    pub x1: Vec3,
}

impl ParticlePath {
    pub fn new(t0: f64, x0: Vec3, t1: f64, x1: Vec3) -> Self {
        Self { t0, x0, t1, x1 }
    }

    /// A particle standing at `x` at time `t`: a sweep of it asks for the nearest surface
    /// point only.
    pub fn still(t: f64, x: Vec3) -> Self {
        Self::new(t, x, t, x)
    }
}

/// What a collider knows of one particle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Proximity {
    /// Within the query reach of a body.
    Near(SurfacePoint),
    /// Farther than `gap_lower_bound` beyond every body's contact thickness.
    Far { gap_lower_bound: f64 },
}

impl Proximity {
    /// A lower bound on the distance beyond the contact thickness (exact when near).
    pub fn gap_lower_bound(&self) -> f64 {
        match self {
            Self::Near(p) => p.gap(),
            Self::Far { gap_lower_bound } => *gap_lower_bound,
        }
    }
}

/// A sharp edge (`a != b`) or corner (`a == b`) of a body, world frame, where the body's
/// surface is not smooth and can poke between cloth particles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SharpFeature {
    pub a: Vec3,
    pub b: Vec3,
    /// Outward pseudo-normal (unit).
    pub normal: Vec3,
    /// Velocity of the feature (at its midpoint), m/s.
    pub velocity: Vec3,
    pub thickness: f64,
    /// The body's Coulomb coefficient (infinite: no slip); `None`: the fabric's.
    pub friction: Option<f64>,
}

/// Rigid bodies as the solver needs them. Implementations answer queries only; the solver
/// decides what is in contact and owns all per-particle state and parallelism.
pub trait Collider: Send + Sync + std::fmt::Debug {
    /// Where a particle moving in a straight line (relative to each body) along `path`
    /// ends up relative to the bodies.
    ///
    /// If the path enters a body, the answer is the entry point with `crossed` set: the
    /// continuous test that keeps fast particles from tunnelling. Otherwise it is the
    /// nearest surface point to the path's end if that lies within the body's thickness plus `reach`,
    /// or `Far`. `start_gap_lower_bound` is what the solver knows of the path's start (a lower
    /// bound on its distance beyond every thickness); an implementation may skip the path test when
    /// the relative path is shorter than that.
    fn sweep(&self, path: &ParticlePath, start_gap_lower_bound: f64, reach: f64) -> Proximity;

    /// As [`Collider::sweep`], for a particle passing through the bodies' thin parts
    /// (hands, forearms: where a body is thinner under its surface than a hand is wide),
    /// which are not there for it; a collider without thin parts answers as `sweep` does.
    fn sweep_past_thin_parts(
        &self,
        path: &ParticlePath,
        start_gap_lower_bound: f64,
        reach: f64,
    ) -> Proximity {
        self.sweep(path, start_gap_lower_bound, reach)
    }

    /// An upper bound on how far any surface point moves between `t0` and `t1` (0 when
    /// every body is static).
    fn motion_bound(&self, t0: f64, t1: f64) -> f64;

    /// The largest contact thickness of any body.
    fn max_thickness(&self) -> f64;

    /// The sharp features of every body at time `t`, appended to `out`.
    fn sharp_features(&self, t: f64, out: &mut Vec<SharpFeature>);

    /// How many body triangles the segment from `a` to `b` passes through at time `t`,
    /// each decided by [`crate::math::predicates::segment_crosses_triangle`], as the
    /// cloth's own intersections are.
    fn segment_crossings(&self, t: f64, a: &Vec3, b: &Vec3) -> usize;

    /// As [`Collider::segment_crossings`], of the bodies' thick parts only (see
    /// [`Collider::sweep_past_thin_parts`]).
    fn thick_segment_crossings(&self, t: f64, a: &Vec3, b: &Vec3) -> usize {
        self.segment_crossings(t, a, b)
    }
}
