//! Scene files: one TOML description of a whole run (the cloth, its fabric, the bodies,
//! the solver and its stages, the outputs), read by the `cloth` command and the Python
//! package alike. Paths in it are relative to the scene file.

mod error;
mod warning;
mod frame;
mod records;
mod cloth_file;
mod fit;
mod observer;
mod strain_summary;
mod history;
mod panel_report;
mod report;
mod recorder;
mod verdict;
mod build;
mod run;

pub use build::{Prepared, PreparedCloth, SheetTest};
pub use cloth_file::read_cloth_obj;
pub use error::{SceneErrorKind, SceneFileError};
pub use fit::Fit;
pub use frame::{placement, UpAxis};
pub use history::HistoryRow;
pub use observer::{RunObserver, Silent};
pub use panel_report::PanelReport;
pub(crate) use recorder::median;
pub use records::{
    BodyShape, BodySpec, BoxSpec, ClothSpec, ContactSpec, CylinderSpec, FabricSpec, FileSpec, GarmentPin,
    MeshSpec, OutputSpec, Placement, SceneFile, SphereSpec, TableSpec,
};
pub use report::{
    Checkpoint, FrameRecord, Measurement, RunOutcome, RunReport, RunSettings, StageReport, TangleRecord,
};
pub use run::RunResult;
pub use strain_summary::StrainSummary;
pub use verdict::{CLEAN, CLEAN_P99_STRAIN, REASONS, STRETCHED};
pub use warning::SceneWarning;

use serde::Deserialize;
use std::path::{Path, PathBuf};

impl SceneFile {
    /// Reads and parses a scene file; unknown keys are refused, and syntax errors give the
    /// line and column.
    pub fn from_path(path: &Path) -> Result<(SceneFile, PathBuf), SceneFileError> {
        let text = std::fs::read_to_string(path).map_err(|source| {
            SceneFileError::new(&path.display().to_string(), None, SceneErrorKind::Io(source))
        })?;
        let scene = Self::from_toml_str(&text, &path.display().to_string())?;
        let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
        Ok((scene, dir))
    }

    /// Parses a scene; `file` names it in errors.
    pub fn from_toml_str(text: &str, file: &str) -> Result<SceneFile, SceneFileError> {
        toml::from_str(text)
            .map_err(|e| SceneFileError::new(file, None, SceneErrorKind::Parse(e.to_string())))
    }

    /// A scene from its tables as values (what a TOML reader makes of a scene file, or a
    /// Python dict); `file` names it in errors.
    pub fn from_toml_value(value: toml::Value, file: &str) -> Result<SceneFile, SceneFileError> {
        SceneFile::deserialize(value)
            .map_err(|e| SceneFileError::new(file, None, SceneErrorKind::Parse(e.to_string())))
    }
}
