//! PLY input (ASCII or binary): `vertex` elements with x, y, z and `face` elements with a
//! `vertex_indices` (or `vertex_index`) list, polygons split into fans.

use std::path::Path;

use cloth_core::math::Vec3;
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{DefaultElement, Property};

use super::io::read_bytes;
use super::{SurfaceError, SurfaceOptions, TriSurface};

impl TriSurface {
    /// Reads a PLY file.
    pub fn from_ply(path: &Path, options: &SurfaceOptions) -> Result<Self, SurfaceError> {
        let bytes = read_bytes(path)?;
        let parse = |line: Option<usize>, message: String| SurfaceError::Parse {
            path: path.to_path_buf(),
            line,
            message,
        };
        let ply = Parser::<DefaultElement>::new()
            .read_ply(&mut &bytes[..])
            .map_err(|e| parse(e.line(), first_line(&e.to_string())))?;
        let none = Vec::new();
        let mut vertices = Vec::new();
        for (i, v) in ply.payload.get("vertex").unwrap_or(&none).iter().enumerate() {
            let get = |name: &str| {
                v.get(name)
                    .and_then(ply_number)
                    .ok_or_else(|| parse(None, format!("vertex {i}: `{name}` is missing or not a number")))
            };
            vertices.push(Vec3::new(get("x")?, get("y")?, get("z")?));
        }
        let mut triangles = Vec::new();
        for (face, f) in ply.payload.get("face").unwrap_or(&none).iter().enumerate() {
            let corners = ["vertex_indices", "vertex_index"]
                .iter()
                .find_map(|k| f.get(*k))
                .and_then(Property::to_u32_list)
                .ok_or_else(|| {
                    parse(
                        None,
                        format!("face {face}: no `vertex_indices` list of non-negative integers"),
                    )
                })?;
            for k in 1..corners.len().saturating_sub(1) {
                triangles.push([corners[0], corners[k], corners[k + 1]]);
            }
        }
        TriSurface::new(vertices, triangles, options).map_err(|e| e.in_file(path))
    }
}

/// The parser nests its messages over several lines: the first says what went wrong.
fn first_line(message: &str) -> String {
    message
        .lines()
        .map(str::trim)
        .find(|l| !l.is_empty())
        .unwrap_or(message)
        .to_string()
}

/// A scalar PLY property as a number (`None` for a list).
pub fn ply_number(p: &Property) -> Option<f64> {
    match *p {
        Property::Char(v) => Some(v.into()),
        Property::UChar(v) => Some(v.into()),
        Property::Short(v) => Some(v.into()),
        Property::UShort(v) => Some(v.into()),
        Property::Int(v) => Some(v.into()),
        Property::UInt(v) => Some(v.into()),
        Property::Float(v) => Some(v.into()),
        Property::Double(v) => Some(v),
        _ => None,
    }
}
