//! What can be wrong with a scene: one error, naming the file, the key in it when one is at
//! fault, and what kind of fault it is.

use crate::presets::PresetError;
use cloth_collide::{BodyError, SurfaceError};
use cloth_core::{MeshError, ParamError};
use cloth_garment::mannequin::MannequinError;
use cloth_garment::{GarmentError, PatternError};

/// A scene that cannot be read, built or run.
#[derive(Debug, thiserror::Error)]
#[error("{}", self.message())]
pub struct SceneFileError {
    /// The scene file (or the name given to a scene that is not one).
    pub file: String,
    /// The key at fault (`bodies[1].rotation`, `fabric`), when one is.
    pub key: Option<String>,
    pub kind: SceneErrorKind,
}

/// What went wrong.
#[derive(Debug, thiserror::Error)]
pub enum SceneErrorKind {
    #[error("{0}")]
    Io(#[source] std::io::Error),
    /// Syntax, an unknown key, a wrong type, a record that does not say one thing: the
    /// message carries the line and column.
    #[error("{0}")]
    Parse(String),
    /// A value that parses but cannot be.
    #[error("{0}")]
    Invalid(String),
    #[error("{0}")]
    Surface(#[source] Box<SurfaceError>),
    #[error("{0}")]
    Body(#[source] BodyError),
    #[error("{0}")]
    Mannequin(#[source] Box<MannequinError>),
    #[error("{0}")]
    Preset(#[source] PresetError),
    #[error("{0}")]
    Param(#[source] ParamError),
    #[error("{0}")]
    Mesh(#[source] MeshError),
    /// The pattern file (its error names it).
    #[error("{0}")]
    Pattern(#[source] PatternError),
    /// A garment that cannot be made from the pattern (its error names the file).
    #[error("{0}")]
    Garment(#[source] GarmentError),
}

impl SceneFileError {
    /// `kind`, in `file` at `key`.
    pub fn new(file: &str, key: Option<&str>, kind: SceneErrorKind) -> Self {
        Self {
            file: file.to_string(),
            key: key.map(str::to_string),
            kind,
        }
    }

    /// A value at `key` of `file` that cannot be, and why.
    pub fn invalid(file: &str, key: &str, reason: String) -> Self {
        Self::new(file, Some(key), SceneErrorKind::Invalid(reason))
    }

    fn message(&self) -> String {
        match (&self.kind, &self.key) {
            (SceneErrorKind::Io(e), _) => format!("cannot read scene '{}': {e}", self.file),
            // These name the pattern's file themselves.
            (SceneErrorKind::Pattern(e), _) => e.to_string(),
            (SceneErrorKind::Garment(e), _) => e.to_string(),
            (kind, Some(key)) => format!("{}: {key}: {kind}", self.file),
            (kind, None) => format!("{}: {kind}", self.file),
        }
    }
}
