//! Integrator choice and solver settings.

use crate::error::ParamError;
use crate::linalg::PcgSettings;
use crate::math::Vec3;
use crate::parallelism::Parallelism;
use crate::self_contact::SelfCollision;
use serde::{Deserialize, Serialize};

/// Time integration scheme.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Integrator {
    /// The source's explicit (forward) Euler: `x += h v0`, `v += h M^-1 F(x0, v0)`.
    ExplicitEuler,
    /// Symplectic Euler: `v += h M^-1 F(x0, v0)`, then `x += h v`.
    SymplecticEuler,
    /// Backward Euler linearised to one Newton step, solved by filtered PCG.
    ImplicitEuler,
}

/// Everything about how the simulation steps.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SolverSettings {
    pub integrator: Integrator,
    /// Time step h, s.
    pub time_step: f64,
    /// Gravitational acceleration, m/s^2 (z is up by default).
    pub gravity: Vec3,
    /// Air velocity the drag acts against, m/s.
    pub wind: Vec3,
    pub pcg: PcgSettings,
    /// Divergence guard: a particle faster than this (m/s) stops the run.
    pub max_speed: f64,
    /// Divergence guard: total kinetic energy above this (J) stops the run.
    pub max_kinetic_energy: f64,
    /// Use rayon for assembly and the matrix-vector product.
    pub parallel: bool,
    /// A step that diverges, whose solve fails or does not converge, or whose impact
    /// passes go over their budget is taken again in halves, and those in halves, up to
    /// this many times (down to `time_step / 2^max_halvings`); only then does it fail.
    pub max_halvings: u32,
    /// The cloth's collision with itself (on by default). Not part of a scene's
    /// `[solver]` table: a scene sets it once for all its stages, in `[self_collision]`.
    #[serde(skip)]
    pub self_collision: SelfCollision,
}

impl Default for SolverSettings {
    fn default() -> Self {
        Self {
            integrator: Integrator::ImplicitEuler,
            time_step: 1.0 / 60.0,
            gravity: Vec3::new(0.0, 0.0, -9.81),
            wind: Vec3::zeros(),
            pcg: PcgSettings::default(),
            max_speed: 100.0,
            max_kinetic_energy: f64::INFINITY,
            parallel: true,
            max_halvings: 6,
            self_collision: SelfCollision::default(),
        }
    }
}

impl SolverSettings {
    /// Where the step's loops run, from [`parallel`](Self::parallel).
    pub fn parallelism(&self) -> Parallelism {
        Parallelism::from_setting(self.parallel)
    }

    pub fn validate(&self) -> Result<(), ParamError> {
        let h = self.time_step;
        ParamError::check(
            h > 0.0 && h.is_finite(),
            "time_step",
            h,
            "a positive finite time step in seconds",
        )?;
        let tol = self.pcg.rel_tolerance;
        ParamError::check(
            tol > 0.0 && tol < 1.0,
            "pcg.rel_tolerance",
            tol,
            "a relative tolerance in (0, 1)",
        )?;
        ParamError::check(
            self.pcg.max_iterations > 0,
            "pcg.max_iterations",
            0.0,
            "at least one iteration",
        )?;
        let v = self.max_speed;
        ParamError::check(v > 0.0, "max_speed", v, "a positive speed limit in m/s")?;
        ParamError::check(
            self.max_halvings <= 20,
            "max_halvings",
            self.max_halvings as f64,
            "at most 20 halvings of the time step",
        )?;
        let e = self.max_kinetic_energy;
        ParamError::check(e > 0.0, "max_kinetic_energy", e, "a positive energy limit in J")?;
        for (name, vector) in [("gravity", &self.gravity), ("wind", &self.wind)] {
            for c in vector.iter() {
                ParamError::check(c.is_finite(), name, *c, "finite components")?;
            }
        }
        self.self_collision.validate()
    }
}
