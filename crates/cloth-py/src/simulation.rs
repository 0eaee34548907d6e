//! `cloth.Simulation`: a cloth on bodies, stepped from Python.

use crate::arrays::{index_list, index_vector, points, vec3_array};
use crate::body::{collider, Body};
use crate::convert::{from_dict, to_python};
use crate::errors::{input, sim};
use crate::fabric::Fabric;
use crate::mesh::ClothMesh;
use crate::observe::Watcher;
use crate::results::{history_columns, RestOutcome, StepStats, Strain};
use crate::self_collision::self_collision_of;
use cloth::scene_file::HistoryRow;
use cloth::{Pin, RestCriteria, SimulationBuilder, SolverSettings};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use std::sync::Arc;

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
    /// Every step taken through this object.
    pub history: Vec<HistoryRow>,
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
        self.history.extend(watcher.finish(py)?);
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
        Ok(Self {
            inner,
            bodies,
            history: Vec::new(),
        })
    }

    /// Takes `n` steps; returns the last one's statistics.
    #[pyo3(signature = (n = 1))]
    fn step(&mut self, py: Python<'_>, n: u64) -> PyResult<StepStats> {
        if n == 0 {
            return Err(input("n: must be at least 1 step"));
        }
        let mut watcher = Watcher::new(None, 1)?.keeping_history();
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
        self.history.extend(watcher.finish(py)?);
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
    /// solver's), and `tolerance` grows with the step. `progress=True` shows a tqdm bar
    /// of the steps towards `max_steps`.
    #[pyo3(signature = (*, tolerance = 1e-5, consecutive_steps = 10, max_steps = 10000, moving_fraction = 0.0, callback = None, every = 1, max_time_step = None, progress = false))]
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
        progress: bool,
    ) -> PyResult<RestOutcome> {
        let criteria = RestCriteria {
            max_time_step,
            tolerance,
            consecutive_steps,
            max_steps,
            moving_fraction,
        };
        criteria.validate().map_err(input)?;
        let mut watcher = Watcher::new(callback, every)?.keeping_history().with_progress(
            py,
            progress,
            Some(max_steps),
            "running",
        )?;
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
    /// Every step taken through this object, as columns (a dict of a list of the stage
    /// names and numpy arrays, one entry per step; `pandas.DataFrame(sim.history)` makes a
    /// table): `stage`, `step`, `time` (s), `cg_iterations`, `cg_residual`,
    /// `kinetic_energy`, `potential_energy` (J), `max_speed` (m/s), `substeps`, `retries`,
    /// `contacts`, `self_contacts`, `step_ms` (wall time): the columns of a run's
    /// `history.csv`.
    #[getter]
    fn history<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, pyo3::types::PyDict>> {
        history_columns(py, &self.history)
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
