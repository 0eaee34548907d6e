//! Wavefront OBJ input and output.

use std::io::{BufWriter, Write};
use std::path::Path;

use cloth_core::math::Vec3;

use super::io::read_bytes;
use super::{SurfaceError, SurfaceOptions, TriSurface};

impl TriSurface {
    /// Reads an OBJ file: polygons are split into triangle fans, all objects and groups are
    /// merged into one surface, and points and lines (which bound nothing) are ignored.
    pub fn from_obj(path: &Path, options: &SurfaceOptions) -> Result<Self, SurfaceError> {
        let bytes = read_bytes(path)?;
        // Triangulated, points and lines dropped; one index per corner into the positions
        // (not per position/normal/uv combination), so shared corners stay shared.
        let load = tobj::LoadOptions {
            single_index: false,
            ..tobj::GPU_LOAD_OPTIONS
        };
        // Materials do not matter to a rigid body, so `mtllib` files are not opened.
        let (models, _) =
            tobj::load_obj_buf(&mut &bytes[..], &load, |_| Ok(Default::default())).map_err(|e| {
                SurfaceError::Parse {
                    path: path.to_path_buf(),
                    line: obj_error_line(&String::from_utf8_lossy(&bytes), &e),
                    message: e.to_string(),
                }
            })?;
        let mut vertices = Vec::new();
        let mut triangles = Vec::new();
        for model in &models {
            let first = vertices.len() as u32;
            let mesh = &model.mesh;
            vertices.extend(
                mesh.positions
                    .chunks_exact(3)
                    .map(|c| Vec3::new(c[0], c[1], c[2])),
            );
            triangles.extend(
                mesh.indices
                    .chunks_exact(3)
                    .map(|c| [c[0] + first, c[1] + first, c[2] + first]),
            );
        }
        TriSurface::new(vertices, triangles, options).map_err(|e| e.in_file(path))
    }

    /// Writes the surface as plain OBJ ('v' and 'f' lines), e.g. to look at a body.
    pub fn write_obj(&self, path: &Path) -> std::io::Result<()> {
        let mut out = BufWriter::new(std::fs::File::create(path)?);
        self.write_obj_to(&mut out)?;
        out.flush()
    }

    /// The same, to any writer.
    pub fn write_obj_to(&self, out: &mut dyn Write) -> std::io::Result<()> {
        writeln!(
            out,
            "# {} vertices, {} triangles",
            self.vertices.len(),
            self.triangles.len()
        )?;
        // `{}` prints the shortest decimal that reads back to the same f64.
        for p in &self.vertices {
            writeln!(out, "v {} {} {}", p.x, p.y, p.z)?;
        }
        for [a, b, c] in &self.triangles {
            writeln!(out, "f {} {} {}", a + 1, b + 1, c + 1)?;
        }
        Ok(())
    }
}

/// tobj reports what went wrong but not where; for the common errors, find the first line
/// that shows it (1-based).
fn obj_error_line(text: &str, error: &tobj::LoadError) -> Option<usize> {
    use tobj::LoadError as E;
    let vertex_count = text
        .lines()
        .filter(|l| l.split_whitespace().next() == Some("v"))
        .count();
    let mut seen = 0usize;
    for (n, line) in text.lines().enumerate() {
        let mut tokens = line.split_whitespace();
        let (Some(keyword), rest) = (tokens.next(), tokens.collect::<Vec<_>>()) else {
            continue;
        };
        let bad = match (keyword, error) {
            ("v", E::PositionParseError) => rest.len() < 3 || rest.iter().any(|t| t.parse::<f64>().is_err()),
            ("f", E::FaceParseError | E::FaceVertexOutOfBounds | E::InvalidPolygon) => {
                rest.len() < 3
                    || rest.iter().any(|t| {
                        let index = t.split('/').next().and_then(|i| i.parse::<i64>().ok());
                        match index {
                            Some(i) if i > 0 => i as usize > vertex_count,
                            Some(i) if i < 0 => i.unsigned_abs() as usize > seen,
                            _ => true,
                        }
                    })
            }
            _ => false,
        };
        if bad {
            return Some(n + 1);
        }
        seen += usize::from(keyword == "v");
    }
    None
}
