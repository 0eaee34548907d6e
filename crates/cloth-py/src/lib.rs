//! `cloth._cloth`: the engine's Python module. Thin: it converts arguments (numpy arrays,
//! dicts shaped as the scene file's tables), releases the GIL while the engine works, and
//! turns errors into Python exceptions. The `cloth` package around it (python/cloth)
//! re-exports it and adds batch runs.

mod arrays;
mod errors;
mod convert;
mod self_collision;
mod mesh;
mod body;
mod fabric;
mod results;
mod observe;
mod simulation;
mod garment;
mod scene;
mod drape;

use pyo3::prelude::*;

/// Cloth simulation: fabric as a particle system draped on rigid bodies (the native part
/// of the `cloth` package).
#[pymodule]
fn _cloth(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("SimulationError", m.py().get_type::<errors::SimulationError>())?;
    m.add_class::<fabric::Fabric>()?;
    m.add_class::<mesh::ClothMesh>()?;
    m.add_class::<body::Body>()?;
    m.add_class::<garment::Pattern>()?;
    m.add_class::<garment::Garment>()?;
    m.add_class::<garment::SewnGarment>()?;
    m.add_class::<garment::Draped>()?;
    m.add_class::<simulation::Simulation>()?;
    m.add_class::<results::StepStats>()?;
    m.add_class::<results::RestOutcome>()?;
    m.add_class::<results::Snapshot>()?;
    m.add_class::<results::Strain>()?;
    m.add_function(wrap_pyfunction!(results::strain, m)?)?;
    m.add_function(wrap_pyfunction!(results::grid_stretch, m)?)?;
    m.add_function(wrap_pyfunction!(drape::drape_scenes, m)?)?;
    m.add_function(wrap_pyfunction!(drape::write_drape_summary, m)?)?;
    m.add_class::<scene::Scene>()?;
    m.add_class::<scene::RunResult>()?;
    Ok(())
}
