//! How a body moves: a pose that is a prescribed function of time.

use cloth_core::math::Vec3;
use nalgebra::{Isometry3, Point3, Translation3, Unit, UnitQuaternion};
use std::sync::Arc;

/// A body's pose as a function of simulation time.
#[derive(Clone)]
pub enum Motion {
    /// Fixed at a pose.
    Static(Isometry3<f64>),
    /// Starting at `pose`, turning at `rate` rad/s about the axis through `center` (world
    /// frame): a turntable, a turning sphere.
    Spin {
        pose: Isometry3<f64>,
        center: Vec3,
        axis: Unit<Vec3>,
        rate: f64,
    },
    /// Starting at `pose`, moving at a constant velocity.
    Linear { pose: Isometry3<f64>, velocity: Vec3 },
    /// Any prescribed pose path (a moving mannequin). Surface velocities come from central
    /// differences, and the motion bound from the poses at the ends of a step, so the path
    /// should be smooth on the scale of a time step.
    Path(Arc<dyn Fn(f64) -> Isometry3<f64> + Send + Sync>),
}

impl std::fmt::Debug for Motion {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Static(p) => write!(f, "Static({p})"),
            Self::Spin {
                center, axis, rate, ..
            } => {
                write!(f, "Spin {{ center: {center:?}, axis: {axis:?}, rate: {rate} }}")
            }
            Self::Linear { velocity, .. } => write!(f, "Linear {{ velocity: {velocity:?} }}"),
            Self::Path(_) => write!(f, "Path(..)"),
        }
    }
}

impl Default for Motion {
    fn default() -> Self {
        Self::Static(Isometry3::identity())
    }
}

/// Time step of the central differences for [`Motion::Path`] velocities, s.
const PATH_DT: f64 = 1e-5;

impl Motion {
    pub fn pose(&self, t: f64) -> Isometry3<f64> {
        match self {
            Self::Static(pose) => *pose,
            Self::Spin {
                pose,
                center,
                axis,
                rate,
            } => {
                let turn = UnitQuaternion::from_axis_angle(axis, rate * t);
                let about = Translation3::from(*center);
                about * Isometry3::from_parts(Translation3::identity(), turn) * about.inverse() * pose
            }
            Self::Linear { pose, velocity } => Translation3::from(velocity * t) * pose,
            Self::Path(f) => f(t),
        }
    }

    /// Velocity at time `t` of the body's material point that is at `point` (world).
    pub fn velocity_at(&self, t: f64, point: &Vec3) -> Vec3 {
        match self {
            Self::Static(_) => Vec3::zeros(),
            Self::Spin {
                center, axis, rate, ..
            } => (axis.into_inner() * *rate).cross(&(point - center)),
            Self::Linear { velocity, .. } => *velocity,
            Self::Path(f) => {
                let local = f(t).inverse_transform_point(&Point3::from(*point));
                let ahead = f(t + PATH_DT) * local;
                let behind = f(t - PATH_DT) * local;
                (ahead - behind) / (2.0 * PATH_DT)
            }
        }
    }

    /// An upper bound on how far a body point within `radius` of the body's local origin
    /// moves between `t0` and `t1`.
    pub fn displacement_bound(&self, t0: f64, t1: f64, radius: f64) -> f64 {
        let dt = (t1 - t0).abs();
        match self {
            Self::Static(_) => 0.0,
            Self::Spin {
                pose, center, rate, ..
            } => rate.abs() * dt * (radius + (pose.translation.vector - center).norm()),
            Self::Linear { velocity, .. } => velocity.norm() * dt,
            Self::Path(f) => {
                let (a, b) = (f(t0), f(t1));
                let turn = a.rotation.angle_to(&b.rotation);
                (b.translation.vector - a.translation.vector).norm() + turn * radius
            }
        }
    }
}
