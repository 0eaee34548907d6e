//! Why a mesh file could not be read for drawing. Every message names the file, and the
//! line or element at fault when that is known.

use cloth_formats::FormatError;
use std::path::PathBuf;
use thiserror::Error;

#[derive(Debug, Error)]
pub enum RenderError {
    /// The file cannot be read as a mesh: it names the file, and the line or element.
    #[error(transparent)]
    Format(#[from] FormatError),
    #[error("{}: unknown mesh format; use a .obj or .ply file", path.display())]
    UnknownFormat { path: PathBuf },
    #[error("{}: no triangles to draw (points, lines and faces of fewer than 3 corners are skipped)", path.display())]
    NoTriangles { path: PathBuf },
}
