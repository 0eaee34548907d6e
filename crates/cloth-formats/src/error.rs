//! Why a file could not be read. Every message names the file, and the line or element at
//! fault when the format allows it.

use std::path::{Path, PathBuf};
use thiserror::Error;

/// A mesh file that cannot be read.
#[derive(Debug, Error)]
pub enum FormatError {
    #[error("cannot read {}: {source}", path.display())]
    Io { path: PathBuf, source: std::io::Error },
    /// The text or bytes break the format; `line` is 1-based where the format has lines.
    #[error("{}{}: cannot parse: {message}", path.display(), at_line(*line))]
    Parse {
        path: PathBuf,
        line: Option<usize>,
        message: String,
    },
    #[error("{}: unknown mesh format; use {expected}", path.display())]
    UnknownFormat { path: PathBuf, expected: &'static str },
    #[error("{}: no `{element}` element in the PLY header", path.display())]
    MissingElement { path: PathBuf, element: &'static str },
    #[error("{}: the `{element}` element has no {property} property", path.display())]
    MissingProperty {
        path: PathBuf,
        element: &'static str,
        property: String,
    },
    /// One element (a PLY vertex or face, an STL facet) is wrong.
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
}

pub(crate) fn read_bytes(path: &Path) -> Result<Vec<u8>, FormatError> {
    std::fs::read(path).map_err(|source| FormatError::Io {
        path: path.to_path_buf(),
        source,
    })
}

fn at_line(line: Option<usize>) -> String {
    line.map(|l| format!(", line {l}")).unwrap_or_default()
}
