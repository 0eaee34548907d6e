//! A step as the contact stages see it, the bodies' and the cloth's own alike: its start,
//! where contacts are found and constrained, and its end, where the passes put right what
//! the solve left. One view of the step's state instead of its pieces passed one by one.

use crate::math::Vec3;
use crate::parallelism::Parallelism;

/// The state at a step's start, as the contacts are found and the constraints chosen.
pub struct StepStart<'a> {
    /// The step's start time, s.
    pub t0: f64,
    /// The step's length, s.
    pub h: f64,
    pub x: &'a [Vec3],
    pub v: &'a [Vec3],
    pub masses: &'a [f64],
    pub pinned: &'a [bool],
    /// Whether the step is implicit (long enough that contacts are looked for ahead along
    /// the motion).
    pub implicit: bool,
    pub par: Parallelism,
}

/// The positions at a step's start and end and the velocities at its end, with the
/// particles' masses, which are pinned, and the outward normal of the body holding each
/// (zero for free particles: the bodies' passes write it, the cloth's own read it).
pub struct StepEnd<'a> {
    /// The step's start time, s.
    pub t0: f64,
    /// The step's length, s.
    pub h: f64,
    pub x0: &'a [Vec3],
    pub x1: &'a mut [Vec3],
    pub v1: &'a mut [Vec3],
    pub masses: &'a [f64],
    pub pinned: &'a [bool],
    pub support: &'a mut [Vec3],
    pub par: Parallelism,
}
