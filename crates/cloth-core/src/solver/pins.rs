//! Pinned particles: held in place, or moved along a prescribed path.

use crate::math::Vec3;
use std::sync::Arc;

/// How a pinned particle moves.
#[derive(Clone)]
pub enum PinMotion {
    /// Held where it is when the simulation is built.
    Fixed,
    /// Held at a given point.
    At(Vec3),
    /// Follows a path: position as a function of simulation time (s).
    Path(Arc<dyn Fn(f64) -> Vec3 + Send + Sync>),
}

impl std::fmt::Debug for PinMotion {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Fixed => write!(f, "Fixed"),
            Self::At(p) => write!(f, "At({}, {}, {})", p.x, p.y, p.z),
            Self::Path(_) => write!(f, "Path(..)"),
        }
    }
}

/// A pinned particle.
#[derive(Debug, Clone)]
pub struct Pin {
    pub particle: usize,
    pub motion: PinMotion,
}

impl Pin {
    pub fn fixed(particle: usize) -> Self {
        Self {
            particle,
            motion: PinMotion::Fixed,
        }
    }
    pub fn at(particle: usize, position: Vec3) -> Self {
        Self {
            particle,
            motion: PinMotion::At(position),
        }
    }
    pub fn path(particle: usize, path: impl Fn(f64) -> Vec3 + Send + Sync + 'static) -> Self {
        Self {
            particle,
            motion: PinMotion::Path(Arc::new(path)),
        }
    }

    /// Where the pin wants its particle at time `t`.
    pub(crate) fn target(&self, t: f64) -> Vec3 {
        match &self.motion {
            PinMotion::At(p) => *p,
            PinMotion::Path(f) => f(t),
            PinMotion::Fixed => unreachable!("Fixed pins are resolved to At when the simulation is built"),
        }
    }
}
