//! What can go wrong making, sewing and draping a garment.

use crate::meshing::MeshingError;
use crate::pattern::PatternError;
use cloth_core::{MeshError, ParamError, SimError};

#[derive(Debug, thiserror::Error)]
pub enum GarmentError {
    #[error(transparent)]
    Pattern(#[from] PatternError),
    #[error("{file}: panel '{panel}' cannot be meshed: {source}")]
    Meshing {
        file: String,
        panel: String,
        #[source]
        source: MeshingError,
    },
    #[error("{what} are not a valid cloth mesh: {source}")]
    Mesh {
        what: &'static str,
        #[source]
        source: MeshError,
    },
    #[error("{name} = {value} is invalid: expected {expected}")]
    Parameter {
        name: &'static str,
        value: f64,
        expected: &'static str,
    },
    #[error(transparent)]
    Param(#[from] ParamError),
    /// Welding would fold a triangle onto itself: two of its corners are sewn together.
    #[error("welding the seams collapses triangle {triangle} of panel '{panel}': two of its corners are sewn together")]
    Collapse { triangle: usize, panel: String },
    /// The seams did not close within the sewing stage's step limit.
    #[error("the seams did not close in {steps} steps: {seam} is still {gap_mm:.1} mm apart (tolerance {tolerance_mm:.1} mm)")]
    NotSewn {
        steps: u64,
        seam: String,
        gap_mm: f64,
        tolerance_mm: f64,
    },
    /// The observer asked to stop (a user's interrupt, say).
    #[error("{stage} stopped at step {steps}")]
    Stopped { stage: &'static str, steps: u64 },
    #[error("{stage}: {source}")]
    Sim {
        stage: &'static str,
        #[source]
        source: SimError,
    },
}
