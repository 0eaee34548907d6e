//! Why a surface was refused. Each error names the vertex, triangle, edge or file at fault
//! and says what to change.

use std::path::PathBuf;

use cloth_formats::FormatError;
use thiserror::Error;

/// A rigid-body surface that cannot be built or read: one that could have no inside.
/// Imperfect meshes load with [`SurfaceDefect`](super::SurfaceDefect)s instead.
///
/// Vertex and triangle indices refer to the mesh as given; for a file, as the file numbers
/// them from 0 (STL has three vertices per facet).
#[derive(Debug, Error)]
pub enum SurfaceError {
    /// The file cannot be read as a mesh: it names the file, and the line or element.
    #[error(transparent)]
    Format(#[from] FormatError),
    #[error("{}: {source}", path.display())]
    InFile {
        path: PathBuf,
        source: Box<SurfaceError>,
    },
    #[error("mesh has no {what}: a body needs a closed triangle surface")]
    Empty { what: String },
    #[error("vertex {vertex} has a non-finite coordinate ({value}); fix or remove it")]
    NonFinite { vertex: usize, value: f64 },
    #[error(
        "triangle {triangle} refers to vertex {index}, but the mesh has {count} vertices \
         (indices start at 0)"
    )]
    IndexOutOfRange {
        triangle: usize,
        index: usize,
        count: usize,
    },
    #[error(
        "all {triangles} triangles have zero area after joining open vertices within \
         {weld_distance:.3e} m: a body needs a surface that encloses something"
    )]
    Degenerate { triangles: usize, weld_distance: f64 },
    #[error(
        "the mesh encloses no volume (its largest part, with triangle {triangle}, has {volume:.3e} m^3): \
         it is flat or folded onto itself and cannot be a solid body"
    )]
    ZeroVolume { triangle: usize, volume: f64 },
    #[error("parameter `{name}` = {value} is invalid: {expected}")]
    Parameter {
        name: &'static str,
        value: f64,
        expected: &'static str,
    },
}

impl SurfaceError {
    /// Attaches the file a mesh came from, so the message names it. Errors that already
    /// name their file are returned unchanged.
    pub(super) fn in_file(self, path: &std::path::Path) -> Self {
        match self {
            Self::Format(_) | Self::InFile { .. } => self,
            other => Self::InFile {
                path: path.to_path_buf(),
                source: Box::new(other),
            },
        }
    }
}
