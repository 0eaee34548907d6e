//! The simulation: state, integrators, pins and the stopping mechanism.

mod error;
mod settings;
mod interrupt;
mod pins;
mod stats;
mod assembly;
mod rest;
mod simulation;
mod explicit;
mod implicit;

pub use crate::linalg::{Constraint, ConstraintKind, PcgSettings};
pub use assembly::SeamPull;
pub use error::{DivergenceReason, SimError, SolveFailure};
pub use interrupt::Interrupt;
pub use pins::{Pin, PinMotion};
pub use rest::{RestCriteria, RestOutcome, StopReason};
pub use settings::{Integrator, SolverSettings};
pub use simulation::{Simulation, SimulationBuilder};
pub use stats::StepStats;
