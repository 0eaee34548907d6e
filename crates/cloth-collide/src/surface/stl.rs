//! STL input (ASCII or binary).

use std::io::Cursor;
use std::path::Path;

use cloth_core::math::Vec3;

use super::io::read_bytes;
use super::{SurfaceError, SurfaceOptions, TriSurface};

impl TriSurface {
    /// Reads an ASCII or binary STL file. STL repeats every corner, so the welding of
    /// [`SurfaceOptions::weld_distance`] is what joins the facets (and is not reported as
    /// a defect).
    pub fn from_stl(path: &Path, options: &SurfaceOptions) -> Result<Self, SurfaceError> {
        let bytes = read_bytes(path)?;
        // stl_io reports a blank file as a truncated binary header; say what it is.
        if bytes.iter().all(u8::is_ascii_whitespace) {
            return Err(SurfaceError::Empty {
                what: "triangles (the file is empty)".into(),
            }
            .in_file(path));
        }
        let parse = |message: String| SurfaceError::Parse {
            path: path.to_path_buf(),
            line: None,
            message,
        };
        let mut cursor = Cursor::new(&bytes);
        let reader = stl_io::create_stl_reader(&mut cursor).map_err(|e| parse(e.to_string()))?;
        let mut vertices = Vec::new();
        let mut triangles = Vec::new();
        for (facet, triangle) in reader.enumerate() {
            // stl_io gives no line numbers; the facet number is the best locator it allows.
            let triangle = triangle.map_err(|e| parse(format!("facet {facet}: {e}")))?;
            let first = vertices.len() as u32;
            vertices.extend(triangle.vertices.iter().map(|v| Vec3::from(v.0.map(f64::from))));
            triangles.push([first, first + 1, first + 2]);
        }
        let mut surface = TriSurface::new(vertices, triangles, options).map_err(|e| e.in_file(path))?;
        // Joining the corners is how STL is read, not something wrong with the file.
        surface
            .defects
            .retain(|d| !matches!(d, super::SurfaceDefect::Welded { .. }));
        Ok(surface)
    }
}
