//! Reading PLY, ASCII or binary: `vertex` elements with x, y, z (and, when the header has
//! them, red/green/blue colours and the `strain` and `panel` our output writes), `face` elements with a
//! `vertex_indices` (or `vertex_index`) list.

use crate::error::{read_bytes, FormatError};
use crate::mesh::fan;
use cloth_core::math::Vec3;
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{DefaultElement, ElementDef, Property, PropertyType};
use std::path::Path;

/// A PLY mesh, its vertices in the file's order.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PlyMesh {
    pub positions: Vec<Vec3>,
    /// Each face's corners, every one a vertex of the file.
    pub faces: Vec<Vec<u32>>,
    /// Per vertex, when the header declares red, green and blue: bytes as they are,
    /// floating point as a fraction of full intensity.
    pub colours: Option<Vec<[u8; 3]>>,
    /// Per vertex, when the header declares a `strain` property (%).
    pub strain: Option<Vec<f64>>,
    /// Per vertex, when the header declares a `panel` property: a garment's panel, as our
    /// output writes it.
    pub panel: Option<Vec<i32>>,
}

impl PlyMesh {
    pub fn read(path: &Path) -> Result<Self, FormatError> {
        let bytes = read_bytes(path)?;
        let ply = Parser::<DefaultElement>::new()
            .read_ply(&mut &bytes[..])
            .map_err(|e| {
                let line = e.line();
                let message = e.to_string();
                // The parser's message starts with the line; the error says it its own way.
                let message = match line {
                    Some(l) => message
                        .strip_prefix(&format!("Line {l}: "))
                        .map_or(message.clone(), str::to_string),
                    None => message,
                };
                FormatError::Parse {
                    path: path.to_path_buf(),
                    line,
                    message: condense(&message),
                }
            })?;
        let missing_property = |element, property: &str| FormatError::MissingProperty {
            path: path.to_path_buf(),
            element,
            property: property.to_string(),
        };
        let bad = |element, index, message: String| FormatError::BadElement {
            path: path.to_path_buf(),
            element,
            index,
            message,
        };

        let vertex_def = ply
            .header
            .elements
            .get("vertex")
            .ok_or_else(|| FormatError::MissingElement {
                path: path.to_path_buf(),
                element: "vertex",
            })?;
        for p in ["x", "y", "z"] {
            if !is_scalar(vertex_def, p) {
                return Err(missing_property("vertex", p));
            }
        }
        let has_strain = is_scalar(vertex_def, "strain");
        let has_panel = is_scalar(vertex_def, "panel");
        let has_colours = ["red", "green", "blue"].iter().all(|c| is_scalar(vertex_def, c));

        let none = Vec::new();
        let vertices = ply.payload.get("vertex").unwrap_or(&none);
        let mut mesh = PlyMesh {
            positions: Vec::with_capacity(vertices.len()),
            faces: Vec::new(),
            colours: has_colours.then(|| Vec::with_capacity(vertices.len())),
            strain: has_strain.then(|| Vec::with_capacity(vertices.len())),
            panel: has_panel.then(|| Vec::with_capacity(vertices.len())),
        };
        for (i, v) in vertices.iter().enumerate() {
            let get = |name: &str| {
                v.get(name)
                    .and_then(number)
                    .ok_or_else(|| bad("vertex", i, format!("{name} is not a number")))
            };
            let p = Vec3::new(get("x")?, get("y")?, get("z")?);
            if !p.iter().all(|c| c.is_finite()) {
                return Err(bad(
                    "vertex",
                    i,
                    format!("non-finite coordinate in ({}, {}, {})", p.x, p.y, p.z),
                ));
            }
            mesh.positions.push(p);
            if let Some(strain) = &mut mesh.strain {
                strain.push(get("strain")?);
            }
            if let Some(panel) = &mut mesh.panel {
                let p = get("panel")?;
                if p.fract() != 0.0 || p.abs() > f64::from(i32::MAX) {
                    return Err(bad("vertex", i, format!("panel {p} is not an integer")));
                }
                panel.push(p as i32);
            }
            if let Some(colours) = &mut mesh.colours {
                let channel = |name: &str| {
                    v.get(name)
                        .and_then(channel)
                        .ok_or_else(|| bad("vertex", i, format!("{name} is not a colour")))
                };
                colours.push([channel("red")?, channel("green")?, channel("blue")?]);
            }
        }

        if let Some(face_def) = ply.header.elements.get("face") {
            let key = ["vertex_indices", "vertex_index"]
                .into_iter()
                .find(|k| face_def.properties.contains_key(*k))
                .ok_or_else(|| missing_property("face", "vertex_indices (or vertex_index)"))?;
            let count = mesh.positions.len();
            for (face, f) in ply.payload.get("face").unwrap_or(&none).iter().enumerate() {
                let corners = f.get(key).and_then(Property::to_u32_list).ok_or_else(|| {
                    bad(
                        "face",
                        face,
                        format!("{key} is not a list of non-negative integers"),
                    )
                })?;
                if let Some(&vertex) = corners.iter().find(|&&i| i as usize >= count) {
                    return Err(FormatError::IndexOutOfRange {
                        path: path.to_path_buf(),
                        face,
                        vertex: vertex as usize,
                        count,
                    });
                }
                mesh.faces.push(corners);
            }
        }
        Ok(mesh)
    }

    /// The faces as triangles: each polygon a fan from its first corner.
    pub fn triangles(&self) -> impl Iterator<Item = [u32; 3]> + '_ {
        self.faces.iter().flat_map(|f| fan(f))
    }
}

/// The parser nests its messages over several lines, quoting the line at each level:
/// keep the outermost and the innermost, on one line.
fn condense(message: &str) -> String {
    let lines: Vec<&str> = message.lines().map(str::trim).filter(|l| !l.is_empty()).collect();
    match lines.as_slice() {
        [first, .., last] => format!("{first} ({})", last.trim_start_matches("Error: ")),
        _ => message.trim().to_string(),
    }
}

fn is_scalar(element: &ElementDef, property: &str) -> bool {
    element
        .properties
        .get(property)
        .is_some_and(|p| matches!(p.data_type, PropertyType::Scalar(_)))
}

/// A scalar property as a number (`None` for a list).
fn number(p: &Property) -> Option<f64> {
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

/// Bytes as they are; floating point as a fraction of full intensity.
fn channel(p: &Property) -> Option<u8> {
    match *p {
        Property::UChar(v) => Some(v),
        Property::Float(v) => Some((v.clamp(0.0, 1.0) * 255.0).round() as u8),
        Property::Double(v) => Some((v.clamp(0.0, 1.0) * 255.0).round() as u8),
        _ => number(p).map(|v| v.clamp(0.0, 255.0) as u8),
    }
}
