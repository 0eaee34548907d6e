//! `cloth.Simulation` and what it reports: step statistics, rest outcomes, the snapshots
//! callbacks see, strain.

use crate::arrays::{index_list, index_vector, points, vec3_array};
use crate::body::{collider, Body};
use crate::convert::{from_dict, to_python};
use crate::errors::{input, sim};
use crate::fabric::Fabric;
use crate::mesh::ClothMesh;
use crate::observe::Watcher;
use cloth::{Pin, RestCriteria, SimulationBuilder, SolverSettings, StopReason};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use std::sync::Arc;

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
    fn new(py: Python<'_>, r: cloth::StrainReport) -> Self {
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

/// Self-collision from Python: None or True, the default; False, off; or a scene's
/// `[self_collision]` keys.
pub fn self_collision_of(value: Option<&Bound<'_, PyAny>>) -> PyResult<cloth::SelfCollision> {
    match value {
        None => Ok(cloth::SelfCollision::default()),
        Some(v) if v.is_instance_of::<pyo3::types::PyBool>() => Ok(if v.extract::<bool>()? {
            cloth::SelfCollision::default()
        } else {
            cloth::SelfCollision::off()
        }),
        Some(v) => {
            let s: cloth::SelfCollision = from_dict(v, "self_collision")?;
            s.validate().map_err(input)?;
            Ok(s)
        }
    }
}

/// The source's measure on a grid: the largest stretch between neighbouring particles
/// along the warp and along the weft, %; None if the mesh is not a grid.
#[pyfunction]
pub fn grid_stretch(mesh: &ClothMesh, positions: &Bound<'_, PyAny>) -> PyResult<Option<(f64, f64)>> {
    let x = points(positions, "positions", Some(mesh.inner.vertex_count()))?;
    Ok(cloth::GridStretch::new(&mesh.inner, &x).map(|s| (s.horizontal, s.vertical)))
}

/// A cloth on bodies, stepped by explicit or implicit Euler. `pins` are particle numbers
/// held where they start (or at `pin_positions`, `(K, 3)`); `settings` are a scene's
/// `[solver]` keys (`integrator`, `time_step`, `gravity`, `wind`, `pcg`, `max_speed`, `max_halvings`,
/// `max_kinetic_energy`, `parallel`); `self_collision` is True (the default), False, or a
/// scene's `[self_collision]` keys (`enabled`, `thickness`, `friction`, `stiffness`).
/// Stepping releases the GIL; a divergence raises SimulationError and keeps the last good
/// state.
#[pyclass(module = "cloth")]
pub struct Simulation {
    pub inner: cloth::Simulation,
    pub bodies: Arc<cloth::collide::Bodies>,
}

impl Simulation {
    /// Runs to rest, the GIL released, watched by `watcher`.
    fn rest(
        &mut self,
        py: Python<'_>,
        criteria: RestCriteria,
        watcher: &mut Watcher,
    ) -> PyResult<cloth::RestOutcome> {
        let inner = &mut self.inner;
        let result =
            py.detach(|| inner.run_to_rest_with(&criteria, |s, stats| watcher.observe("running", s, stats)));
        if let Some(e) = watcher.take_error() {
            return Err(e);
        }
        result.map_err(|e| sim(py, &e))
    }
}

#[pymethods]
impl Simulation {
    #[new]
    #[pyo3(signature = (mesh, fabric, *, bodies = Vec::new(), pins = None, pin_positions = None, settings = None, velocities = None, self_collision = None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        mesh: &ClothMesh,
        fabric: &Fabric,
        bodies: Vec<PyRef<'_, Body>>,
        pins: Option<&Bound<'_, PyAny>>,
        pin_positions: Option<&Bound<'_, PyAny>>,
        settings: Option<&Bound<'_, PyAny>>,
        velocities: Option<&Bound<'_, PyAny>>,
        self_collision: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let n = mesh.inner.vertex_count();
        let settings = SolverSettings {
            self_collision: self_collision_of(self_collision)?,
            ..match settings {
                Some(s) => from_dict(s, "solver")?,
                None => SolverSettings::default(),
            }
        };
        let pinned = match pins {
            Some(p) => index_list(p, "pins", n)?,
            None => Vec::new(),
        };
        let targets = match pin_positions {
            Some(p) => Some(points(p, "pin_positions", Some(pinned.len()))?),
            None => None,
        };
        let pins = pinned.iter().enumerate().map(|(k, &i)| match &targets {
            Some(t) => Pin::at(i, t[k]),
            None => Pin::fixed(i),
        });
        let mut builder = SimulationBuilder::new(mesh.inner.clone(), fabric.inner.clone())
            .settings(settings)
            .pins(pins);
        if let Some(v) = velocities {
            builder = builder.velocities(points(v, "velocities", Some(n))?);
        }
        let bodies = collider(&bodies);
        if !bodies.bodies().is_empty() {
            builder = builder.collider(bodies.clone());
        }
        let inner = builder.build().map_err(input)?;
        Ok(Self { inner, bodies })
    }

    /// Takes `n` steps; returns the last one's statistics.
    #[pyo3(signature = (n = 1))]
    fn step(&mut self, py: Python<'_>, n: u64) -> PyResult<StepStats> {
        if n == 0 {
            return Err(input("n: must be at least 1 step"));
        }
        let mut watcher = Watcher::new(None, 1)?;
        let inner = &mut self.inner;
        let result = py.detach(|| {
            let mut last = None;
            for _ in 0..n {
                let stats = inner.step()?;
                last = Some(stats);
                if watcher.observe("running", inner, &stats).is_break() {
                    break;
                }
            }
            Ok(last.expect("at least one step was taken"))
        });
        if let Some(e) = watcher.take_error() {
            return Err(e);
        }
        result.map(StepStats::from).map_err(|e| sim(py, &e))
    }

    /// Steps until every particle (all but `moving_fraction` of them) has moved less than
    /// `tolerance` m per step over a window of `consecutive_steps` steps (end to end), or
    /// `max_steps`. `callback`
    /// sees a Snapshot every `every` steps; returning False stops the run (reason
    /// "stopped"); an exception it raises stops the run and propagates. Ctrl-C stops it
    /// too (KeyboardInterrupt, the state kept). With `max_time_step`, each step taken
    /// whole lets the next grow by a quarter up to it (a cut one starts again from the
    /// solver's), and `tolerance` grows with the step.
    #[pyo3(signature = (*, tolerance = 1e-5, consecutive_steps = 10, max_steps = 10000, moving_fraction = 0.0, callback = None, every = 1, max_time_step = None))]
    #[allow(clippy::too_many_arguments)]
    fn run_to_rest(
        &mut self,
        py: Python<'_>,
        tolerance: f64,
        consecutive_steps: u32,
        max_steps: u64,
        moving_fraction: f64,
        callback: Option<Py<PyAny>>,
        every: u64,
        max_time_step: Option<f64>,
    ) -> PyResult<RestOutcome> {
        let criteria = RestCriteria {
            max_time_step,
            tolerance,
            consecutive_steps,
            max_steps,
            moving_fraction,
        };
        criteria.validate().map_err(input)?;
        let mut watcher = Watcher::new(callback, every)?;
        let outcome = self.rest(py, criteria, &mut watcher)?;
        RestOutcome::new(py, &outcome)
    }

    /// `(N, 3)` positions. Setting them moves the particles (pinned ones go back to their
    /// pins in the next step).
    #[getter]
    fn get_positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        vec3_array(py, self.inner.positions())
    }
    #[setter]
    fn set_positions(&mut self, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let x = points(value, "positions", Some(self.inner.positions().len()))?;
        self.inner.set_positions(&x).map_err(input)
    }
    /// `(N, 3)` velocities, settable.
    #[getter]
    fn get_velocities<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        vec3_array(py, self.inner.velocities())
    }
    #[setter]
    fn set_velocities(&mut self, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let v = points(value, "velocities", Some(self.inner.velocities().len()))?;
        self.inner.set_velocities(&v).map_err(input)
    }
    /// `(N,)` lumped particle masses, kg.
    #[getter]
    fn masses<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, self.inner.masses())
    }
    /// The pinned particles.
    #[getter]
    fn pins<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        index_vector(py, self.inner.pins().iter().map(|p| p.particle))
    }
    /// The cloth's mesh (its positions are the initial ones).
    #[getter]
    fn mesh(&self) -> ClothMesh {
        ClothMesh {
            inner: self.inner.mesh().clone(),
        }
    }
    /// The fabrics (one, or one per panel group of a garment).
    #[getter]
    fn fabrics(&self) -> Vec<Fabric> {
        self.inner
            .fabrics()
            .iter()
            .map(|f| Fabric { inner: f.clone() })
            .collect()
    }
    /// The solver settings, as a scene's `[solver]` table.
    #[getter]
    fn settings<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, self.inner.settings())
    }
    /// Simulated time, s.
    #[getter]
    fn time(&self) -> f64 {
        self.inner.time()
    }
    /// Steps taken so far.
    #[getter]
    fn step_count(&self) -> u64 {
        self.inner.step_count()
    }
    /// Kinetic energy, J.
    #[getter]
    fn kinetic_energy(&self) -> f64 {
        self.inner.kinetic_energy()
    }
    /// The warp and weft strain now.
    fn strain(&self, py: Python<'_>) -> Strain {
        let inner = &self.inner;
        let report = py.detach(|| cloth::StrainReport::new(inner.mesh(), inner.positions()));
        Strain::new(py, report)
    }
    /// The source's measure on a grid: the largest stretch between neighbouring particles
    /// along the warp and along the weft, %; None if not a grid.
    fn grid_stretch(&self) -> Option<(f64, f64)> {
        cloth::GridStretch::new(self.inner.mesh(), self.inner.positions()).map(|s| (s.horizontal, s.vertical))
    }
    /// How deep the deepest particle is inside a body, m (0 if none is).
    fn deepest_penetration(&self, py: Python<'_>) -> f64 {
        let (bodies, inner) = (&self.bodies, &self.inner);
        py.detach(|| bodies.deepest_inside(inner.time(), inner.positions()).0)
    }
    /// How many edge-triangle pairs of the cloth pass through each other now (pairs
    /// sharing or neighbouring particles, or near in the flat cloth, exempt).
    fn self_intersections(&self, py: Python<'_>) -> usize {
        let inner = &self.inner;
        py.detach(|| inner.self_intersections().count)
    }
    /// How many cloth edges pass through a body triangle now, counted the same way.
    fn body_intersections(&self, py: Python<'_>) -> usize {
        let inner = &self.inner;
        py.detach(|| inner.body_intersections())
    }
    /// The smallest distance of a particle from a triangle of the cloth (exempt pairs
    /// aside), m, if one is under `within`: how close the layers come.
    fn closest_self_approach(&self, py: Python<'_>, within: f64) -> PyResult<Option<f64>> {
        if !(within.is_finite() && within > 0.0) {
            return Err(input(format!(
                "within = {within}: expected a positive distance in m"
            )));
        }
        let inner = &self.inner;
        Ok(py.detach(|| inner.closest_self_approach(within)))
    }

    fn __repr__(&self) -> String {
        format!(
            "Simulation({} particles, {} pins, step {}, t = {:.4} s)",
            self.inner.positions().len(),
            self.inner.pins().len(),
            self.inner.step_count(),
            self.inner.time()
        )
    }
}
