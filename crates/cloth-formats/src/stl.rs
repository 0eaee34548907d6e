//! Reading STL, ASCII or binary. STL repeats every corner: facet `f` is vertices `3f`,
//! `3f + 1` and `3f + 2`, and joining them is the reader's business.

use crate::error::{read_bytes, FormatError};
use crate::mesh::FileMesh;
use cloth_core::math::Vec3;
use std::io::Cursor;
use std::path::Path;

/// Reads `path`; a blank file has no facets.
pub fn read_stl(path: &Path) -> Result<FileMesh, FormatError> {
    let bytes = read_bytes(path)?;
    // stl_io reports a blank file as a truncated binary header; it is an empty one.
    if bytes.iter().all(u8::is_ascii_whitespace) {
        return Ok(FileMesh::default());
    }
    let parse = |message: String| FormatError::Parse {
        path: path.to_path_buf(),
        line: None,
        message,
    };
    let mut cursor = Cursor::new(&bytes);
    let reader = stl_io::create_stl_reader(&mut cursor).map_err(|e| parse(e.to_string()))?;
    let mut mesh = FileMesh::default();
    for (facet, triangle) in reader.enumerate() {
        // stl_io gives no line numbers; the facet number is the best locator it allows.
        let triangle = triangle.map_err(|e| parse(format!("facet {facet}: {e}")))?;
        let first = mesh.positions.len() as u32;
        mesh.positions
            .extend(triangle.vertices.iter().map(|v| Vec3::from(v.0.map(f64::from))));
        mesh.triangles.push([first, first + 1, first + 2]);
    }
    Ok(mesh)
}
