//! What a run reports to Python: step statistics, rest outcomes, the snapshots callbacks
//! see, strain.

use crate::arrays::points;
use crate::convert::to_python;
use crate::mesh::ClothMesh;
use cloth::scene_file::HistoryRow;
use cloth::StopReason;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Statistics of one step.
#[pyclass(frozen, module = "cloth")]
#[derive(Clone)]
pub struct StepStats {
    /// Number of this step (1 for the first).
    #[pyo3(get)]
    pub step: u64,
    /// Simulation time at its end, s.
    #[pyo3(get)]
    pub time: f64,
    /// PCG iterations (0 for explicit integrators).
    #[pyo3(get)]
    pub cg_iterations: usize,
    /// Final relative PCG residual |r|/|b|.
    #[pyo3(get)]
    pub cg_residual: f64,
    /// Whether PCG met its tolerance (True for explicit integrators).
    #[pyo3(get)]
    pub cg_converged: bool,
    /// Wall time assembling forces and Jacobians, s.
    #[pyo3(get)]
    pub assembly_seconds: f64,
    /// Wall time in the linear solve, s.
    #[pyo3(get)]
    pub solve_seconds: f64,
    /// Largest particle speed at the end of the step, m/s.
    #[pyo3(get)]
    pub max_speed: f64,
    /// Largest particle displacement during the step, m.
    #[pyo3(get)]
    pub max_displacement: f64,
    /// Kinetic energy at the end of the step, J.
    #[pyo3(get)]
    pub kinetic_energy: f64,
    /// Elastic plus gravitational energy at the start of the step, J.
    #[pyo3(get)]
    pub potential_energy: f64,
    /// Particles constrained by a body contact during the step.
    #[pyo3(get)]
    pub contacts: usize,
    /// Particles put back out to the contact thickness at the end of the step.
    #[pyo3(get)]
    pub contact_corrections: usize,
    /// Of those, particles whose path entered a body within the step.
    #[pyo3(get)]
    pub crossings: usize,
    /// Sharp body features under cloth triangles, held off by the feature penalty.
    #[pyo3(get)]
    pub feature_contacts: usize,
    /// Cloth triangles found pierced by a sharp feature and pushed back out.
    #[pyo3(get)]
    pub feature_corrections: usize,
    /// Wall time in the end-of-step contact passes, s.
    #[pyo3(get)]
    pub contact_seconds: f64,
    /// Pairs of the cloth closer than their contact distance, repelled in the step.
    #[pyo3(get)]
    pub self_contacts: usize,
    /// Pairs of the cloth found passing through each other and turned back by impulses.
    #[pyo3(get)]
    pub self_impacts: usize,
    /// Particles moved as impact zones.
    #[pyo3(get)]
    pub self_zone_particles: usize,
    /// Particles stopped where they started the step (the last resort).
    #[pyo3(get)]
    pub self_frozen: usize,
    /// Pairs still passing through each other that nothing could stop.
    #[pyo3(get)]
    pub self_unresolved: usize,
    /// Wall time in self-collision, s.
    #[pyo3(get)]
    pub self_collision_seconds: f64,
    /// Substeps the step was taken in (1 at the full time step).
    #[pyo3(get)]
    pub substeps: u32,
    /// Substeps undone and taken again at half the length.
    #[pyo3(get)]
    pub retries: u32,
    /// The shortest substep taken, s.
    #[pyo3(get)]
    pub smallest_substep: f64,
    raw: cloth::StepStats,
}

impl From<cloth::StepStats> for StepStats {
    fn from(s: cloth::StepStats) -> Self {
        Self {
            step: s.step,
            time: s.time,
            cg_iterations: s.cg_iterations,
            cg_residual: s.cg_residual,
            cg_converged: s.cg_converged,
            assembly_seconds: s.assembly_seconds,
            solve_seconds: s.solve_seconds,
            max_speed: s.max_speed,
            max_displacement: s.max_displacement,
            kinetic_energy: s.kinetic_energy,
            potential_energy: s.potential_energy,
            contacts: s.contacts,
            contact_corrections: s.contact_corrections,
            crossings: s.crossings,
            feature_contacts: s.feature_contacts,
            feature_corrections: s.feature_corrections,
            contact_seconds: s.contact_seconds,
            self_contacts: s.self_contacts,
            self_impacts: s.self_impacts,
            self_zone_particles: s.self_zone_particles,
            self_frozen: s.self_frozen,
            self_unresolved: s.self_unresolved,
            self_collision_seconds: s.self_collision_seconds,
            substeps: s.substeps,
            retries: s.retries,
            smallest_substep: s.smallest_substep,
            raw: s,
        }
    }
}

#[pymethods]
impl StepStats {
    /// Every field as a dict.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.raw)
    }
    fn __repr__(&self) -> String {
        format!(
            "StepStats(step={}, time={:.4}, cg_iterations={}, max_speed={:.3e}, contacts={})",
            self.step, self.time, self.cg_iterations, self.max_speed, self.contacts
        )
    }
}

/// How a run to rest ended: `reason` is "at_rest", "step_limit" or "stopped" (the callback
/// returned False).
#[pyclass(frozen, get_all, module = "cloth")]
pub struct RestOutcome {
    /// "at_rest", "step_limit" or "stopped".
    pub reason: &'static str,
    /// Steps taken by this run.
    pub steps: u64,
    /// Statistics of the last step.
    pub last: Py<StepStats>,
}

impl RestOutcome {
    pub fn new(py: Python<'_>, o: &cloth::RestOutcome) -> PyResult<Self> {
        Ok(Self {
            reason: match o.reason {
                StopReason::AtRest => "at_rest",
                StopReason::StepLimit => "step_limit",
                StopReason::Stopped => "stopped",
            },
            steps: o.steps,
            last: Py::new(py, StepStats::from(o.last))?,
        })
    }
}

#[pymethods]
impl RestOutcome {
    fn __repr__(&self) -> String {
        format!("RestOutcome(reason='{}', steps={})", self.reason, self.steps)
    }
}

/// What a callback sees: the stage ("running", "sewing", "draping"), the step's
/// statistics, and copies of the positions and velocities after it.
#[pyclass(frozen, get_all, module = "cloth")]
pub struct Snapshot {
    /// "running", "sewing" or "draping".
    pub stage: String,
    /// The step's statistics.
    pub stats: StepStats,
    /// (N, 3) positions after the step (a copy).
    pub positions: Py<PyAny>,
    /// (N, 3) velocities after the step (a copy).
    pub velocities: Py<PyAny>,
}

#[pymethods]
impl Snapshot {
    fn __repr__(&self) -> String {
        format!("Snapshot(stage='{}', step={})", self.stage, self.stats.step)
    }
}

/// Warp and weft strain of every triangle, % (positive: stretched).
#[pyclass(frozen, get_all, module = "cloth")]
pub struct Strain {
    /// (M,) warp strain of each triangle, %.
    pub warp: Py<PyAny>,
    /// (M,) weft strain of each triangle, %.
    pub weft: Py<PyAny>,
    /// Largest warp strain, %.
    pub max_warp: f64,
    /// Largest weft strain, %.
    pub max_weft: f64,
    /// 99th percentile of the warp strain, %.
    pub p99_warp: f64,
    /// 99th percentile of the weft strain, %.
    pub p99_weft: f64,
}

impl Strain {
    pub fn new(py: Python<'_>, r: cloth::StrainReport) -> Self {
        Self {
            max_warp: r.max_warp,
            max_weft: r.max_weft,
            p99_warp: r.p99_warp,
            p99_weft: r.p99_weft,
            warp: PyArray1::from_vec(py, r.warp).into_any().unbind(),
            weft: PyArray1::from_vec(py, r.weft).into_any().unbind(),
        }
    }
}

#[pymethods]
impl Strain {
    fn __repr__(&self) -> String {
        format!(
            "Strain(max_warp={:.3} %, max_weft={:.3} %, p99_warp={:.3} %, p99_weft={:.3} %)",
            self.max_warp, self.max_weft, self.p99_warp, self.p99_weft
        )
    }
}

/// Warp and weft strain of `mesh` at `positions`.
#[pyfunction]
pub fn strain(py: Python<'_>, mesh: &ClothMesh, positions: &Bound<'_, PyAny>) -> PyResult<Strain> {
    let x = points(positions, "positions", Some(mesh.inner.vertex_count()))?;
    let report = py.detach(|| cloth::StrainReport::new(&mesh.inner, &x));
    Ok(Strain::new(py, report))
}

/// The source's measure on a grid: the largest stretch between neighbouring particles
/// along the warp and along the weft, %; None if the mesh is not a grid.
#[pyfunction]
pub fn grid_stretch(mesh: &ClothMesh, positions: &Bound<'_, PyAny>) -> PyResult<Option<(f64, f64)>> {
    let x = points(positions, "positions", Some(mesh.inner.vertex_count()))?;
    Ok(cloth::GridStretch::new(&mesh.inner, &x).map(|s| (s.horizontal, s.vertical)))
}

/// History rows as columns: the stage names as a list, the rest as numpy arrays (the
/// columns of `history.csv`, in its order).
pub fn history_columns<'py>(py: Python<'py>, rows: &[HistoryRow]) -> PyResult<Bound<'py, PyDict>> {
    let columns = PyDict::new(py);
    let floats = |get: fn(&HistoryRow) -> f64| PyArray1::from_vec(py, rows.iter().map(get).collect());
    let integers = |get: fn(&HistoryRow) -> i64| PyArray1::from_vec(py, rows.iter().map(get).collect());
    columns.set_item("stage", rows.iter().map(|r| r.stage).collect::<Vec<_>>())?;
    columns.set_item("step", integers(|r| r.step as i64))?;
    columns.set_item("time", floats(|r| r.time))?;
    columns.set_item("cg_iterations", integers(|r| r.cg_iterations as i64))?;
    columns.set_item("cg_residual", floats(|r| r.cg_residual))?;
    columns.set_item("kinetic_energy", floats(|r| r.kinetic_energy))?;
    columns.set_item("potential_energy", floats(|r| r.potential_energy))?;
    columns.set_item("max_speed", floats(|r| r.max_speed))?;
    columns.set_item("substeps", integers(|r| i64::from(r.substeps)))?;
    columns.set_item("retries", integers(|r| i64::from(r.retries)))?;
    columns.set_item("contacts", integers(|r| r.contacts as i64))?;
    columns.set_item("self_contacts", integers(|r| r.self_contacts as i64))?;
    columns.set_item("step_ms", floats(|r| r.step_ms))?;
    Ok(columns)
}
