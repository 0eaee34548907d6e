//! Why a surface was refused. Each error names the vertex, triangle, edge or file at fault
//! and says what to change.

use std::path::PathBuf;

use thiserror::Error;

/// A rigid-body surface that cannot be built or read.
///
/// Vertex indices refer to the vertices as given (after welding, the first of the merged
/// vertices); for a file, as the reader numbered them (tobj renumbers in order of first use,
/// STL has three per facet), so the positions, in metres after scaling, are what find them.
#[derive(Debug, Error)]
pub enum SurfaceError {
    #[error("cannot read {}: {source}", path.display())]
    Io { path: PathBuf, source: std::io::Error },
    #[error("{}{}: cannot parse: {message}", path.display(), at_line(*line))]
    Parse {
        path: PathBuf,
        line: Option<usize>,
        message: String,
    },
    #[error("{}: unknown mesh format; use a .obj or .stl file", path.display())]
    UnknownFormat { path: PathBuf },
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
        "triangle {triangle} has zero area ({area:.3e} m^2) after welding vertices within \
         {weld_distance:.3e} m: remove it, or lower weld_distance if welding collapsed it"
    )]
    Degenerate {
        triangle: usize,
        area: f64,
        weld_distance: f64,
    },
    #[error(
        "edge from vertex {a} at {a_at:?} to vertex {b} at {b_at:?} is shared by {count} triangles \
         (a closed surface has exactly 2): split the mesh into separate closed surfaces"
    )]
    NonManifold {
        a: usize,
        b: usize,
        count: usize,
        a_at: [f64; 3],
        b_at: [f64; 3],
    },
    #[error(
        "edge from vertex {a} at {a_at:?} to vertex {b} at {b_at:?} belongs to one triangle only: \
         the surface is open ({boundary_edges} boundary edges); close the holes, or raise \
         weld_distance if the gaps are tiny"
    )]
    Open {
        a: usize,
        b: usize,
        boundary_edges: usize,
        a_at: [f64; 3],
        b_at: [f64; 3],
    },
    #[error(
        "the two triangles on the edge from vertex {a} at {a_at:?} to vertex {b} at {b_at:?} run \
         along it in the same direction: orientation is inconsistent; reorient the faces \
         (e.g. 'recalculate normals' in a mesh editor)"
    )]
    Inconsistent {
        a: usize,
        b: usize,
        a_at: [f64; 3],
        b_at: [f64; 3],
    },
    #[error(
        "the closed surface containing triangle {triangle} is oriented inward (signed volume \
         {volume:.3e} m^3): reverse its triangles or set SurfaceOptions::flip_inward"
    )]
    Inward { triangle: usize, volume: f64 },
    #[error(
        "the closed surface containing triangle {triangle} encloses no volume ({volume:.3e} m^3): \
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
            Self::Io { .. } | Self::Parse { .. } | Self::UnknownFormat { .. } | Self::InFile { .. } => self,
            other => Self::InFile {
                path: path.to_path_buf(),
                source: Box::new(other),
            },
        }
    }
}

fn at_line(line: Option<usize>) -> String {
    line.map(|l| format!(", line {l}")).unwrap_or_default()
}
