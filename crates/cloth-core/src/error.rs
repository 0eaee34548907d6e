//! Error types. Each names the element, field or step at fault so a user can act on it.

use thiserror::Error;

/// A cloth mesh that cannot be simulated.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum MeshError {
    #[error("mesh has no triangles")]
    Empty,
    #[error("mesh has {positions} positions but {uvs} material (u, v) coordinates")]
    LengthMismatch { positions: usize, uvs: usize },
    #[error("triangle {triangle} refers to vertex {index}, but the mesh has {vertex_count} vertices")]
    IndexOutOfRange {
        triangle: usize,
        index: usize,
        vertex_count: usize,
    },
    #[error("triangle {triangle} repeats vertex {index}")]
    RepeatedVertex { triangle: usize, index: usize },
    #[error("triangle {triangle} is degenerate in {space} (area {area:e})")]
    DegenerateTriangle {
        triangle: usize,
        space: &'static str,
        area: f64,
    },
    #[error("edge ({a}, {b}) is shared by {count} triangles (at most 2 allowed): non-manifold")]
    NonManifoldEdge { a: usize, b: usize, count: usize },
    #[error("vertex {vertex} belongs to no triangle (it would have no mass)")]
    UnusedVertex { vertex: usize },
    #[error("vertex {vertex} has a non-finite {field} coordinate")]
    NonFinite { vertex: usize, field: &'static str },
    #[error("grid needs at least 2 x 2 particles and positive spacing, got {nx} x {ny} at ({du}, {dv}) m")]
    BadGrid { nx: usize, ny: usize, du: f64, dv: f64 },
}

/// A physical or numerical parameter that is out of its valid range.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ParamError {
    #[error("parameter `{name}` = {value} is invalid: {expected}")]
    OutOfRange {
        name: &'static str,
        value: f64,
        expected: &'static str,
    },
    #[error("parameter `{name}` = {value} is inconsistent: {reason}")]
    Inconsistent {
        name: &'static str,
        value: f64,
        reason: String,
    },
    #[error("tensile curve `{name}` is invalid: {reason}")]
    BadCurve { name: &'static str, reason: String },
    #[error("pin on particle {particle}, but the mesh has {count} particles")]
    PinOutOfRange { particle: usize, count: usize },
}

impl ParamError {
    /// `Ok` when `ok`, otherwise the out-of-range error for `name`.
    pub fn check(ok: bool, name: &'static str, value: f64, expected: &'static str) -> Result<(), Self> {
        if ok {
            Ok(())
        } else {
            Err(Self::OutOfRange {
                name,
                value,
                expected,
            })
        }
    }
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
        reason: String,
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
