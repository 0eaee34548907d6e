//! `cloth.Pattern`, `cloth.Garment` and the sewing and draping stages.

use crate::arrays::{index_array, index_vector, points};
use crate::body::{collider, Body};
use crate::convert::{from_dict, json_to_python};
use crate::errors::{garment as garment_error, input};
use crate::fabric::Fabric;
use crate::mesh::ClothMesh;
use crate::observe::Watcher;
use crate::results::RestOutcome;
use crate::self_collision::self_collision_of;
use crate::simulation::Simulation;
use cloth::garment::garmentcode::{self, ImportOptions};
use cloth::garment::sewing::{drape, sew, DrapeSettings, SewingSettings, Sewn};
use cloth::garment::GarmentBuilder;
use cloth::presets::FabricLibrary;
use cloth::Interrupt;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// A sewing pattern: panels (outlines of lines, Béziers and arcs, with grain lines and
/// placements round the body) and the seams between their edges.
#[pyclass(frozen, module = "cloth")]
#[derive(Clone)]
pub struct Pattern {
    inner: cloth::garment::Pattern,
    /// The source, named in meshing errors.
    file: String,
}

#[pymethods]
impl Pattern {
    /// Our TOML pattern (`.toml`) or GarmentCode's JSON (`.json`).
    #[staticmethod]
    fn load(path: PathBuf) -> PyResult<Self> {
        let is_json = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("json"));
        let inner = if is_json {
            garmentcode::from_path(&path, &ImportOptions::default())
        } else {
            cloth::garment::Pattern::from_toml_path(&path)
        }
        .map_err(input)?;
        Ok(Self {
            inner,
            file: path.display().to_string(),
        })
    }
    /// Our TOML pattern format; `name` is the file named in errors.
    #[staticmethod]
    #[pyo3(signature = (text, *, name = "<pattern>".to_string()))]
    fn from_toml(text: &str, name: String) -> PyResult<Self> {
        let inner = cloth::garment::Pattern::from_toml_str(text, &name).map_err(input)?;
        Ok(Self { inner, file: name })
    }
    /// A GarmentCode specification (JSON text); `name` is the file named in errors.
    #[staticmethod]
    #[pyo3(signature = (text, *, name = "<pattern>".to_string()))]
    fn from_garmentcode(text: &str, name: String) -> PyResult<Self> {
        let inner = garmentcode::from_json_str(text, &name, &ImportOptions::default()).map_err(input)?;
        Ok(Self { inner, file: name })
    }
    /// The panels' names.
    #[getter]
    fn panel_names(&self) -> Vec<String> {
        self.inner.panels.iter().map(|p| p.name.clone()).collect()
    }
    /// Number of seams.
    #[getter]
    fn seam_count(&self) -> usize {
        self.inner.seams.len()
    }
    fn __repr__(&self) -> String {
        format!(
            "Pattern('{}', {} panels, {} seams)",
            self.inner.name,
            self.inner.panels.len(),
            self.inner.seams.len()
        )
    }
}

/// A pattern meshed for simulation: each panel discretised at `edge_length` (m), placed in
/// 3D, and the seams' vertex pairs matched one to one.
#[pyclass(frozen, module = "cloth")]
pub struct Garment {
    inner: cloth::garment::Garment,
}

#[pymethods]
impl Garment {
    #[new]
    #[pyo3(signature = (pattern, edge_length = cloth::garment::garment::DEFAULT_EDGE_LENGTH))]
    fn new(py: Python<'_>, pattern: &Pattern, edge_length: f64) -> PyResult<Self> {
        let builder = GarmentBuilder::new(pattern.inner.clone())
            .edge_length(edge_length)
            .file(pattern.file.clone());
        let inner = py.detach(|| builder.build()).map_err(|e| garment_error(py, &e))?;
        Ok(Self { inner })
    }
    /// The unsewn mesh, panels placed.
    #[getter]
    fn mesh(&self) -> ClothMesh {
        ClothMesh {
            inner: self.inner.mesh.clone(),
        }
    }
    /// The panels' names.
    #[getter]
    fn panel_names(&self) -> Vec<String> {
        self.inner.panel_names.clone()
    }
    /// The panel of each triangle.
    #[getter]
    fn triangle_panel<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        index_vector(py, self.inner.triangle_panel.iter().copied())
    }
    /// `(K, 2)` vertex pairs the seams join.
    #[getter]
    fn seam_pairs<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<i64>> {
        index_array(py, &self.inner.seam_pairs())
    }
    /// The widest seam gap at `positions` (the placed mesh when None), m.
    #[pyo3(signature = (positions = None))]
    fn widest_gap(&self, positions: Option<&Bound<'_, PyAny>>) -> PyResult<f64> {
        let x = match positions {
            Some(p) => points(p, "positions", Some(self.inner.mesh.vertex_count()))?,
            None => self.inner.mesh.positions().to_vec(),
        };
        Ok(self.inner.widest_gap(&x).1)
    }
    /// Panels placed inside a body, with the fix.
    fn placement_warnings(&self, bodies: Vec<PyRef<'_, Body>>) -> Vec<String> {
        let bodies = collider(&bodies);
        self.inner
            .placement_warnings(&bodies)
            .iter()
            .map(ToString::to_string)
            .collect()
    }
    /// The source's second stage: gravity off, the seams pulled closed and welded. `fabric`
    /// is one fabric for every panel (panels that name a preset get theirs) or one per
    /// panel. `settings` are a scene's `[sewing]` keys; `self_collision` as for
    /// Simulation. `callback` sees a Snapshot every `every` steps; returning False stops
    /// the sewing (SimulationError). Seams that will not close raise SimulationError.
    #[pyo3(signature = (bodies, fabric, *, settings = None, self_collision = None, callback = None, every = 1))]
    #[allow(clippy::too_many_arguments)]
    fn sew(
        &self,
        py: Python<'_>,
        bodies: Vec<PyRef<'_, Body>>,
        fabric: &Bound<'_, PyAny>,
        settings: Option<&Bound<'_, PyAny>>,
        self_collision: Option<&Bound<'_, PyAny>>,
        callback: Option<Py<PyAny>>,
        every: u64,
    ) -> PyResult<SewnGarment> {
        let panels = self.inner.panel_names.len();
        let fabrics: Vec<cloth::Fabric> = if let Ok(f) = fabric.extract::<PyRef<'_, Fabric>>() {
            FabricLibrary::builtin()
                .panel_fabrics(&self.inner, &f.inner)
                .map_err(input)?
        } else {
            let list: Vec<PyRef<'_, Fabric>> = fabric
                .extract()
                .map_err(|_| input("fabric: give a Fabric, or a list of one Fabric per panel"))?;
            if list.len() != panels {
                return Err(input(format!(
                    "fabric: {} fabrics given for {panels} panels",
                    list.len()
                )));
            }
            list.iter().map(|f| f.inner.clone()).collect()
        };
        let settings = SewingSettings {
            self_collision: self_collision_of(self_collision)?,
            ..match settings {
                Some(s) => from_dict(s, "sewing")?,
                None => SewingSettings::default(),
            }
        };
        settings.validate().map_err(input)?;
        let mut watcher = Watcher::new(callback, every)?;
        let bodies = collider(&bodies);
        let garment = &self.inner;
        let sewn = py.detach(|| {
            sew(
                garment,
                &fabrics,
                bodies,
                &settings,
                &Interrupt::default(),
                |sim, stats, _| watcher.observe("sewing", sim, stats),
            )
        });
        if let Some(e) = watcher.take_error() {
            return Err(e);
        }
        let sewn = sewn.map_err(|e| garment_error(py, &e))?;
        Ok(SewnGarment { inner: sewn })
    }

    fn __repr__(&self) -> String {
        format!(
            "Garment({} panels, {} particles, {} seam pairs)",
            self.inner.panel_names.len(),
            self.inner.mesh.vertex_count(),
            self.inner.seam_pairs().len()
        )
    }
}

/// A garment whose seams are welded, at the positions where they closed.
#[pyclass(frozen, module = "cloth")]
pub struct SewnGarment {
    inner: Sewn,
}

#[pymethods]
impl SewnGarment {
    /// The welded mesh (its positions are where the seams closed).
    #[getter]
    fn mesh(&self) -> ClothMesh {
        ClothMesh {
            inner: self.inner.welded.mesh.clone(),
        }
    }
    /// Steps, seconds, CG iterations, the widest gap at welding (m), the pull per seam pair
    /// (N); the seams that stalled and how they closed (`seam_stalls`), the layers found
    /// across them (`caught_layers`) and the crossings the weld made (`weld_crossings`), as
    /// a scene's report.json gives them.
    #[getter]
    fn report<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let r = &self.inner.report;
        let d = PyDict::new(py);
        d.set_item("steps", r.steps)?;
        d.set_item("seconds", r.seconds)?;
        d.set_item("cg_iterations", r.cg_iterations)?;
        d.set_item("max_gap", r.max_gap)?;
        d.set_item("pull", r.pull)?;
        d.set_item("seam_stalls", json_to_python(py, &r.stalls)?)?;
        d.set_item("caught_layers", json_to_python(py, &r.caught)?)?;
        d.set_item("weld_crossings", json_to_python(py, &r.weld_crossings)?)?;
        Ok(d)
    }
    /// The source's third stage: gravity on, until at rest (`settings` are a scene's
    /// `[drape]` keys; `self_collision` as for Simulation).
    #[pyo3(signature = (bodies, *, settings = None, self_collision = None, callback = None, every = 1))]
    fn drape(
        &self,
        py: Python<'_>,
        bodies: Vec<PyRef<'_, Body>>,
        settings: Option<&Bound<'_, PyAny>>,
        self_collision: Option<&Bound<'_, PyAny>>,
        callback: Option<Py<PyAny>>,
        every: u64,
    ) -> PyResult<Draped> {
        let settings = DrapeSettings {
            self_collision: self_collision_of(self_collision)?,
            ..match settings {
                Some(s) => from_dict(s, "drape")?,
                None => DrapeSettings::default(),
            }
        };
        settings.validate().map_err(input)?;
        let mut watcher = Watcher::new(callback, every)?.keeping_history();
        let bodies = collider(&bodies);
        let sewn = &self.inner;
        let collider = bodies.clone();
        let draped = py.detach(|| {
            drape(sewn, collider, &settings, &Interrupt::default(), |sim, stats| {
                watcher.observe("draping", sim, stats)
            })
        });
        let history = watcher.finish(py)?;
        if let Some(e) = watcher.take_error() {
            return Err(e);
        }
        let draped = draped.map_err(|e| garment_error(py, &e))?;
        Ok(Draped {
            untangling_at_rest: json_to_python(py, &draped.untangling)?.unbind(),
            outcome: Py::new(py, RestOutcome::new(py, &draped.outcome)?)?,
            seconds: draped.seconds,
            simulation: Py::new(
                py,
                Simulation {
                    inner: draped.simulation,
                    bodies,
                    history,
                },
            )?,
        })
    }
}

/// A draped garment: the simulation at rest (it can be stepped on) and how it ended.
#[pyclass(frozen, get_all, module = "cloth")]
pub struct Draped {
    /// The simulation, at rest.
    pub simulation: Py<Simulation>,
    /// How the drape ended.
    pub outcome: Py<RestOutcome>,
    /// Wall time, s.
    pub seconds: f64,
    /// If the drape came to rest through itself, what was done, as a dict as a scene's
    /// report.json gives it (`before`: the crossings where it first rested; `smoothed`:
    /// each smoothing apart and the drape on from there, in order; `loose`: the drape again
    /// from sewn, loose, if it still crossed); None otherwise.
    pub untangling_at_rest: Py<PyAny>,
}
