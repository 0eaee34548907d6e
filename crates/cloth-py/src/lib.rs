//! `cloth._cloth`: the engine's Python module. Thin: it converts arguments (numpy arrays,
//! dicts shaped as the scene file's tables), releases the GIL while the engine works, and
//! turns errors into Python exceptions. The `cloth` package around it (python/cloth)
//! re-exports it and adds batch runs.

mod arrays;
mod body;
mod convert;
mod drape;
mod errors;
mod fabric;
mod garment;
mod mesh;
mod observe;
mod scene;
mod simulation;

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
    m.add_class::<simulation::StepStats>()?;
    m.add_class::<simulation::RestOutcome>()?;
    m.add_class::<simulation::Snapshot>()?;
    m.add_class::<simulation::Strain>()?;
    m.add_function(wrap_pyfunction!(simulation::strain, m)?)?;
    m.add_function(wrap_pyfunction!(simulation::grid_stretch, m)?)?;
    m.add_function(wrap_pyfunction!(drape::drape_scenes, m)?)?;
    m.add_function(wrap_pyfunction!(drape::write_drape_summary, m)?)?;
    m.add_class::<scene::Scene>()?;
    m.add_class::<scene::RunResult>()?;
    Ok(())
}
