//! What can be wrong with a scene, named by file and key; and what can go wrong running it.

use crate::presets::PresetError;
use cloth_collide::{BodyError, SurfaceError};
use cloth_core::{MeshError, ParamError};
use cloth_garment::mannequin::MannequinError;
use cloth_garment::{GarmentError, PatternError};
use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum SceneFileError {
    #[error("cannot read scene '{path}': {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// Syntax, an unknown key or a wrong type: `message` carries the line and column.
    #[error("{file}: {message}")]
    Parse { file: String, message: String },
    /// A value that parses but cannot be: `key` is its place in the file.
    #[error("{file}: {key}: {reason}")]
    Invalid {
        file: String,
        key: String,
        reason: String,
    },
    #[error("{file}: {key}: {source}")]
    Surface {
        file: String,
        key: String,
        #[source]
        source: Box<SurfaceError>,
    },
    #[error("{file}: {key}: {source}")]
    Body {
        file: String,
        key: String,
        #[source]
        source: BodyError,
    },
    #[error("{file}: {key}: {source}")]
    Mannequin {
        file: String,
        key: String,
        #[source]
        source: Box<MannequinError>,
    },
    #[error("{file}: fabric: {source}")]
    Preset {
        file: String,
        #[source]
        source: PresetError,
    },
    #[error(transparent)]
    Pattern(#[from] PatternError),
    #[error("{file}: {source}")]
    Param {
        file: String,
        #[source]
        source: ParamError,
    },
    #[error("{file}: cloth: {source}")]
    Mesh {
        file: String,
        #[source]
        source: MeshError,
    },
    /// A garment that cannot be made.
    #[error(transparent)]
    Garment(#[from] GarmentError),
}
