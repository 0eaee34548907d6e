//! The physical validation tests of fabrics: the cantilever against the elastica, the
//! Cusick drape against measured ranges, and a hanging strip against its tensile law.
//! The integration tests assert on them; `examples/fabric_validation.rs` prints them as a
//! table.

pub mod cusick;
pub mod elastica;
pub mod cantilever;
pub mod hanging_strip;

pub use cantilever::{fixed_angle, Cantilever, CantileverRest, FixedAngle};
pub use cusick::{CusickResult, CusickTest};
pub use elastica::{elastica_tip, ElasticaTip};
pub use hanging_strip::{HangingRest, HangingStrip};

use cloth_core::{MeshError, ParamError, RestCriteria, SimError, Simulation, StopReason};

/// Runs `sim` to rest; reaching the step limit is an error naming the test. Returns the
/// steps taken.
fn settle(sim: &mut Simulation, criteria: &RestCriteria, test: &'static str) -> Result<u64, ValidationError> {
    let out = sim.run_to_rest(criteria)?;
    match out.reason {
        StopReason::AtRest => Ok(out.steps),
        _ => Err(ValidationError::NotAtRest {
            test,
            steps: out.steps,
        }),
    }
}

/// Why a validation run gave no result.
#[derive(Debug, thiserror::Error)]
pub enum ValidationError {
    #[error(transparent)]
    Mesh(#[from] MeshError),
    #[error(transparent)]
    Param(#[from] ParamError),
    #[error(transparent)]
    Sim(#[from] SimError),
    #[error("meshing the specimen: {0}")]
    Meshing(#[from] cloth_garment::meshing::MeshingError),
    #[error("{test}: not at rest after {steps} steps")]
    NotAtRest { test: &'static str, steps: u64 },
    #[error("fixed-angle cantilever: the chord does not cross 41.5 degrees by an overhang of {cells} cells")]
    NoCrossing { cells: usize },
}
