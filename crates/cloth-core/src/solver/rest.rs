//! The source's stopping mechanism: run until the cloth is at rest or a step limit.

use super::StepStats;
use crate::error::ParamError;
use serde::{Deserialize, Serialize};

/// At rest when, over a window of `consecutive_steps` steps (and half a second at least),
/// every particle (all but `moving_fraction` of them) has moved less than `tolerance`
/// metres per step of the window from where it was at the window's start; otherwise stop
/// after `max_steps` steps. The motion is judged from end to end of the window, not step
/// by step, so that cloth that only trembles in place, its contacts catching and letting
/// go, is at rest: a GarmentCode dress (rand_1_037), the fastest of its particles at 1-5
/// cm/s in every step to the end, went 500 steps of 0.1 s without resting, while over its
/// last 2.5 s no particle moved 2 mm and 99 % of them less than 0.7 mm. Steady creep is
/// judged as step by step. A swing at the top of its arc is judged by the half second: a
/// sheet swinging under explicit Euler, judged over its 20 steps of 0.25 ms, passed for
/// at rest 8.4 mm from its rest.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RestCriteria {
    pub tolerance: f64,
    pub consecutive_steps: u32,
    pub max_steps: u64,
    /// The fraction of the particles that may still move faster (0: none, the source's
    /// rule). A garment whose hem corner swings or whose loose front creeps down at a few
    /// millimetres a second is at rest as a whole, which is how GarmentCode judges its
    /// drapes (1.5 % of the vertices).
    #[serde(default)]
    pub moving_fraction: f64,
    /// The time step may grow, while the steps go well, up to this (s; none: it stays the
    /// solver's). The rest is where the forces balance whatever the step, and implicit
    /// Euler's longer steps damp the motion that is left faster: a GarmentCode skirt
    /// (rand_1_067) swayed on at 1/30 s past 376 steps and ten minutes, and came to rest
    /// in 167 steps of 0.1 s. The rest tolerance, a distance per step, grows with it.
    #[serde(default)]
    pub max_time_step: Option<f64>,
}

impl Default for RestCriteria {
    fn default() -> Self {
        Self {
            tolerance: 1e-5,
            consecutive_steps: 10,
            max_steps: 10_000,
            moving_fraction: 0.0,
            max_time_step: None,
        }
    }
}

impl RestCriteria {
    pub fn validate(&self) -> Result<(), ParamError> {
        let t = self.tolerance;
        ParamError::check(
            t > 0.0 && t.is_finite(),
            "rest.tolerance",
            t,
            "a positive finite distance per step in metres",
        )?;
        ParamError::check(
            self.consecutive_steps > 0,
            "rest.consecutive_steps",
            0.0,
            "at least one step",
        )?;
        ParamError::check(
            (0.0..1.0).contains(&self.moving_fraction),
            "rest.moving_fraction",
            self.moving_fraction,
            "a fraction in [0, 1)",
        )?;
        if let Some(h) = self.max_time_step {
            ParamError::check(
                h.is_finite() && h > 0.0,
                "rest.max_time_step",
                h,
                "a positive time step in s",
            )?;
        }
        ParamError::check(self.max_steps > 0, "rest.max_steps", 0.0, "at least one step")
    }
}

/// The shortest time a window of a run to rest spans, s (see [`RestCriteria`]).
pub(super) const MIN_WINDOW: f64 = 0.5;

/// Why a run to rest ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StopReason {
    AtRest,
    StepLimit,
    /// The observer asked to stop (a user's interrupt, say).
    Stopped,
}

/// The end of a run to rest.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RestOutcome {
    pub reason: StopReason,
    /// Steps taken by this run.
    pub steps: u64,
    /// Statistics of the last step.
    pub last: StepStats,
}
