//! Why a run stopped with an error: each names the step, and the state kept.

use crate::error::ParamError;
use crate::linalg::{ConstraintError, PcgError};
use thiserror::Error;

/// Why a step's linear solve failed.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum SolveFailure {
    #[error(transparent)]
    Constraint(#[from] ConstraintError),
    #[error(transparent)]
    Pcg(#[from] PcgError),
    #[error("the solve did not converge in {iterations} iterations (relative residual {residual:.1e})")]
    NotConverged { iterations: usize, residual: f64 },
}

/// Why a run stopped with an error. The simulation keeps the last good state.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum SimError {
    #[error("diverged at step {step}: {reason}; the state of step {last_good} is kept")]
    Diverged {
        step: u64,
        last_good: u64,
        reason: DivergenceReason,
    },
    #[error(transparent)]
    Param(#[from] ParamError),
    #[error("pin on particle {particle} has a non-finite target at step {step}; the state of step {} is kept", step - 1)]
    InvalidPin { step: u64, particle: usize },
    #[error("linear solve failed at step {step}: {reason}; the state of step {last_good} is kept")]
    Solver {
        step: u64,
        last_good: u64,
        reason: SolveFailure,
    },
    /// The simulation's [`Interrupt`](crate::Interrupt) was raised during a step.
    #[error("interrupted during step {step}; the state of step {last_good} is kept")]
    Interrupted { step: u64, last_good: u64 },
}

impl SimError {
    /// The step that failed; `None` for a parameter refused before any step.
    pub fn step(&self) -> Option<u64> {
        match self {
            Self::Diverged { step, .. }
            | Self::InvalidPin { step, .. }
            | Self::Solver { step, .. }
            | Self::Interrupted { step, .. } => Some(*step),
            Self::Param(_) => None,
        }
    }
}

/// What the divergence guard saw.
#[derive(Debug, Clone, PartialEq)]
pub enum DivergenceReason {
    NonFinite {
        particle: usize,
    },
    SpeedLimit {
        particle: usize,
        speed: f64,
        limit: f64,
    },
    EnergyLimit {
        energy: f64,
        limit: f64,
    },
    /// The impact passes found more impacts than a step may resolve.
    ImpactBudget {
        found: usize,
        budget: usize,
    },
}

impl std::fmt::Display for DivergenceReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::NonFinite { particle } => {
                write!(f, "particle {particle} has a non-finite position or velocity")
            }
            Self::SpeedLimit {
                particle,
                speed,
                limit,
            } => write!(
                f,
                "particle {particle} moves at {speed:.3e} m/s, over the limit of {limit} m/s"
            ),
            Self::EnergyLimit { energy, limit } => write!(
                f,
                "kinetic energy {energy:.3e} J is over the limit of {limit:.3e} J"
            ),
            Self::ImpactBudget { found, budget } => write!(
                f,
                "the cloth's layers met in {found} impacts, over the step's budget of {budget}"
            ),
        }
    }
}
