//! Why a mesh file could not be read for drawing. Every message names the file, and the
//! line or element at fault when that is known.

use std::path::PathBuf;
use thiserror::Error;

#[derive(Debug, Error)]
pub enum RenderError {
    #[error("cannot read {}: {source}", path.display())]
    Io { path: PathBuf, source: std::io::Error },
    #[error("{}{}: cannot parse: {message}", path.display(), at_line(*line))]
    Parse {
        path: PathBuf,
        line: Option<usize>,
        message: String,
    },
    #[error("{}: unknown mesh format; use a .obj or .ply file", path.display())]
    UnknownFormat { path: PathBuf },
    #[error("{}: no `{element}` element in the PLY header", path.display())]
    MissingElement { path: PathBuf, element: &'static str },
    #[error("{}: the `{element}` element has no {property} property", path.display())]
    MissingProperty {
        path: PathBuf,
        element: &'static str,
        property: String,
    },
    #[error("{}: {element} {index} (counting from 0): {message}", path.display())]
    BadElement {
        path: PathBuf,
        element: &'static str,
        index: usize,
        message: String,
    },
    #[error(
        "{}: face {face} (counting from 0) refers to vertex {vertex}, but the file has {count} \
         vertices (indices start at 0)",
        path.display()
    )]
    IndexOutOfRange {
        path: PathBuf,
        face: usize,
        vertex: usize,
        count: usize,
    },
    #[error("{}: no triangles to draw (points, lines and faces of fewer than 3 corners are skipped)", path.display())]
    NoTriangles { path: PathBuf },
}

fn at_line(line: Option<usize>) -> String {
    line.map(|l| format!(", line {l}")).unwrap_or_default()
}
