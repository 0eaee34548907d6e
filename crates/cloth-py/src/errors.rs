//! The engine's errors as Python exceptions: bad input is a `ValueError` carrying the
//! same message the `cloth` command prints; a run that fails on valid input is a
//! `SimulationError` that says at which step.

use cloth::garment::GarmentError;
use cloth::SimError;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

pyo3::create_exception!(
    cloth,
    SimulationError,
    PyRuntimeError,
    "A run that diverged or otherwise could not go on, on valid input. The simulation \
     keeps the last good state; `step` is the step that failed (0 if unknown) and `report` \
     the run's report (a dict) when a scene was running, else None."
);

/// Bad input: the message is the command's.
pub fn input(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// A failed run, with the step that failed and the report if there is one.
pub fn simulation(py: Python<'_>, message: &str, step: u64, report: Option<Bound<'_, PyAny>>) -> PyErr {
    let err = SimulationError::new_err(message.to_string());
    let value = err.value(py);
    // Setting attributes on a fresh exception instance cannot fail.
    let _ = value.setattr("step", step);
    let _ = value.setattr("report", report);
    err
}

/// A stepping error: parameters are input, the rest a failed run.
pub fn sim(py: Python<'_>, e: &SimError) -> PyErr {
    match e.step() {
        Some(step) => simulation(py, &e.to_string(), step, None),
        None => input(e),
    }
}

/// A garment error: what the pattern or settings got wrong is input; seams that will not
/// close and divergences are failed runs.
pub fn garment(py: Python<'_>, e: &GarmentError) -> PyErr {
    let step = match e {
        GarmentError::NotSewn { steps, .. }
        | GarmentError::Stalled { steps, .. }
        | GarmentError::Stopped { steps, .. } => Some(*steps),
        GarmentError::Sim { source, .. } => source.step(),
        _ => None,
    };
    match step {
        Some(step) => simulation(py, &e.to_string(), step, None),
        None => input(e),
    }
}
