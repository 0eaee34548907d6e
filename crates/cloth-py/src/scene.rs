//! `cloth.Scene`: a scene file run exactly as `cloth run` runs it, into the same outputs.

use crate::arrays::{index_array, index_vector, vec3_array};
use crate::convert::{json_to_python, to_toml};
use crate::errors::{input, simulation};
use crate::mesh::ClothMesh;
use crate::observe::Watcher;
use crate::results::history_columns;
use cloth::formats::panels::PanelLabels;
use cloth::math::Vec3;
use cloth::run_folder::{claim_output_folder, FolderRun, RunFolderError};
use cloth::scene_file::{HistoryRow, RunOutcome, SceneFile};
use numpy::{PyArray1, PyArray2};
use pyo3::exceptions::{PyImportError, PyOSError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// A scene file: the cloth, fabric, bodies, solver, stages and outputs of a whole run, as
/// the `cloth` command reads it. Relative paths start at the scene's folder.
#[pyclass(frozen, module = "cloth")]
pub struct Scene {
    file: SceneFile,
    /// The file (or name) errors refer to.
    path: String,
    dir: PathBuf,
}

#[pymethods]
impl Scene {
    /// Reads a TOML scene; ValueError carries the command's message (file, line and
    /// column, or key).
    #[staticmethod]
    fn load(path: PathBuf) -> PyResult<Self> {
        let (file, dir) = SceneFile::from_path(&path).map_err(input)?;
        Ok(Self {
            file,
            path: path.display().to_string(),
            dir,
        })
    }

    /// A scene from TOML text; relative paths start at `base_dir`, errors name `name`.
    #[staticmethod]
    #[pyo3(signature = (text, *, base_dir = PathBuf::from("."), name = "<scene>".to_string()))]
    fn from_toml(text: &str, base_dir: PathBuf, name: String) -> PyResult<Self> {
        let file = SceneFile::from_toml_str(text, &name).map_err(input)?;
        Ok(Self {
            file,
            path: name,
            dir: base_dir,
        })
    }

    /// From the scene's tables as a dict (what `tomllib` reads from a scene file).
    #[staticmethod]
    #[pyo3(signature = (values, *, base_dir = PathBuf::from("."), name = "<scene>".to_string()))]
    fn from_dict(values: &Bound<'_, PyAny>, base_dir: PathBuf, name: String) -> PyResult<Self> {
        // The records straight from the dict's values, read as the file's tables are.
        let file = SceneFile::from_toml_value(to_toml(values, "scene")?, &name).map_err(input)?;
        Ok(Self {
            file,
            path: name,
            dir: base_dir,
        })
    }

    /// The scene's `name`.
    #[getter]
    fn name(&self) -> &str {
        &self.file.name
    }
    /// The file (or name) errors refer to.
    #[getter]
    fn path(&self) -> &str {
        &self.path
    }
    /// Where the scene's relative paths start.
    #[getter]
    fn base_dir(&self) -> String {
        self.dir.display().to_string()
    }

    /// Reads and builds everything a run needs without simulating, as `cloth check`;
    /// returns the warnings (panels placed inside a body).
    fn check(&self, py: Python<'_>) -> PyResult<Vec<String>> {
        let prepared = py
            .detach(|| self.file.prepare(&self.path, &self.dir))
            .map_err(input)?;
        Ok(prepared.warnings.iter().map(ToString::to_string).collect())
    }

    /// Runs as `cloth run SCENE --out OUT_DIR` and writes the same outputs. Bad input
    /// raises ValueError before anything runs; a divergence writes the last good state and
    /// the report, then raises SimulationError; `callback` returning False stops the run,
    /// which is then reported and returned as interrupted; Ctrl-C writes the state reached
    /// and raises KeyboardInterrupt.
    /// `progress=True` shows a tqdm bar of each stage's steps towards its limit.
    #[pyo3(signature = (out_dir, *, force = false, callback = None, every = 1, progress = false))]
    fn run(
        &self,
        py: Python<'_>,
        out_dir: PathBuf,
        force: bool,
        callback: Option<Py<PyAny>>,
        every: u64,
        progress: bool,
    ) -> PyResult<RunResult> {
        let mut watcher = Watcher::new(callback, every)?.with_progress(py, progress, None, "preparing")?;
        claim_output_folder(&out_dir, force)
            .map_err(|e| input(format!("{e}: pass force=True to write into it")))?;
        let prepared = py
            .detach(|| self.file.prepare(&self.path, &self.dir))
            .map_err(input)?;
        if !prepared.warnings.is_empty() {
            let warnings = py.import("warnings")?;
            for w in &prepared.warnings {
                warnings.call_method1("warn", (w.to_string(),))?;
            }
        }
        let run = py.detach(|| prepared.run_into(&self.file, &out_dir, &mut watcher));
        let FolderRun { result, written } = run.map_err(|e| match e {
            RunFolderError::Write { .. } | RunFolderError::Create { .. } => PyOSError::new_err(e.to_string()),
            e => input(e),
        })?;
        // The run keeps its own history; the watcher only closes its bar.
        watcher.finish(py)?;
        // Python stopped it (Ctrl-C, or the callback raised): the state reached is written.
        if let Some(e) = watcher.take_error() {
            return Err(e);
        }
        let report = json_to_python(py, &result.report)?;
        if let RunOutcome::Failed { stage, step, error } = &result.report.outcome {
            let message = format!(
                "{error} (the state after {stage} step {step} and the report are in '{}')",
                out_dir.join("report.json").display()
            );
            return Err(simulation(py, &message, *step + 1, Some(report)));
        }
        let outcome = match result.report.outcome {
            RunOutcome::Finished => "finished",
            RunOutcome::Interrupted { .. } => "interrupted",
            RunOutcome::Failed { .. } => unreachable!("raised above"),
        };
        Ok(RunResult {
            mesh: ClothMesh { inner: result.mesh },
            positions: result.positions,
            report: report.unbind(),
            outcome,
            outputs: written.iter().map(|p| p.display().to_string()).collect(),
            panels: result.panels,
            history: result.history,
        })
    }

    fn __repr__(&self) -> String {
        format!("Scene('{}', from '{}')", self.file.name, self.path)
    }
}

/// A scene's run: the cloth where it ended, the report, and the files written.
#[pyclass(frozen, module = "cloth")]
pub struct RunResult {
    mesh: ClothMesh,
    positions: Vec<Vec3>,
    report: Py<PyAny>,
    outcome: &'static str,
    outputs: Vec<String>,
    panels: Option<PanelLabels>,
    history: Vec<HistoryRow>,
}

#[pymethods]
impl RunResult {
    /// The cloth's mesh (welded, for a garment).
    #[getter]
    fn mesh(&self) -> ClothMesh {
        self.mesh.clone()
    }
    /// `(N, 3)` positions where the run ended.
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        vec3_array(py, &self.positions)
    }
    /// The report, as report.json.
    #[getter]
    fn report(&self, py: Python<'_>) -> Py<PyAny> {
        self.report.clone_ref(py)
    }
    /// "finished" or "interrupted" (a failed run raises SimulationError).
    #[getter]
    fn outcome(&self) -> &'static str {
        self.outcome
    }
    /// Whether every stage ran to its end.
    #[getter]
    fn finished(&self) -> bool {
        self.outcome == "finished"
    }
    /// The files written.
    #[getter]
    fn outputs(&self) -> Vec<String> {
        self.outputs.clone()
    }
    /// Every step of every stage, as columns (see `Simulation.history`): what
    /// `history.csv` holds.
    #[getter]
    fn history<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        history_columns(py, &self.history)
    }
    /// A garment's panel names (None for a sheet).
    #[getter]
    fn panel_names(&self) -> Option<Vec<String>> {
        self.panels.as_ref().map(|p| p.names().to_vec())
    }
    /// `(M,)` each triangle's panel, an index into `panel_names` (None for a sheet).
    #[getter]
    fn triangle_panel<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<i64>>> {
        self.panels
            .as_ref()
            .map(|p| index_vector(py, p.of_triangle().iter().copied()))
    }
    /// The cloth where the run ended as a `trimesh.Trimesh` (z up, m; not merged or
    /// repaired), a garment's panel per face in `face_attributes["panel"]` with the names
    /// in `metadata["panels"]`. Needs trimesh (`pip install cloth-drape[trimesh]`).
    fn to_trimesh<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let trimesh = py.import("trimesh").map_err(|_| {
            PyImportError::new_err("to_trimesh needs trimesh: pip install trimesh (or cloth-drape[trimesh])")
        })?;
        let options = PyDict::new(py);
        options.set_item("vertices", vec3_array(py, &self.positions))?;
        options.set_item("faces", index_array(py, self.mesh.inner.triangles()))?;
        options.set_item("process", false)?;
        let metadata = PyDict::new(py);
        metadata.set_item("units", "m")?;
        metadata.set_item("up_axis", "z")?;
        if let Some(p) = &self.panels {
            let faces = PyDict::new(py);
            faces.set_item("panel", index_vector(py, p.of_triangle().iter().copied()))?;
            options.set_item("face_attributes", faces)?;
            metadata.set_item("panels", p.names().to_vec())?;
        }
        options.set_item("metadata", metadata)?;
        trimesh.getattr("Trimesh")?.call((), Some(&options))
    }
    fn __repr__(&self) -> String {
        format!("RunResult({}, {} files)", self.outcome, self.outputs.len())
    }
}
