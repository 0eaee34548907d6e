//! PLY through `ply-rs-bw`, ASCII or binary: `vertex` elements with x, y, z, and `face`
//! elements with a `vertex_indices` (or `vertex_index`) list, polygons split into fans. A
//! `strain` property (%, as our PLY output writes) colours the vertices on the output's
//! scale; otherwise red, green and blue are used if present.

use super::{Colouring, LoadedMesh};
use crate::error::RenderError;
use crate::strain_colours::strain_colour;
use cloth_collide::surface::ply_number;
use cloth_core::math::Vec3;
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{DefaultElement, ElementDef, Property, PropertyType};
use std::path::Path;

pub(super) fn read(path: &Path) -> Result<LoadedMesh, RenderError> {
    let file = std::fs::File::open(path).map_err(|source| RenderError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let ply = Parser::<DefaultElement>::new()
        .read_ply(&mut std::io::BufReader::new(file))
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
            let message = condense(&message);
            RenderError::Parse {
                path: path.to_path_buf(),
                line,
                message,
            }
        })?;
    let missing_property = |element, property: &str| RenderError::MissingProperty {
        path: path.to_path_buf(),
        element,
        property: property.to_string(),
    };
    let bad = |element, index, message: String| RenderError::BadElement {
        path: path.to_path_buf(),
        element,
        index,
        message,
    };

    let vertex_def = ply
        .header
        .elements
        .get("vertex")
        .ok_or_else(|| RenderError::MissingElement {
            path: path.to_path_buf(),
            element: "vertex",
        })?;
    for p in ["x", "y", "z"] {
        if !is_scalar(vertex_def, p) {
            return Err(missing_property("vertex", p));
        }
    }
    let colouring = if is_scalar(vertex_def, "strain") {
        Colouring::Strain
    } else if ["red", "green", "blue"].iter().all(|c| is_scalar(vertex_def, c)) {
        Colouring::FromFile
    } else {
        Colouring::Plain
    };

    let none = Vec::new();
    let vertices = ply.payload.get("vertex").unwrap_or(&none);
    let mut positions = Vec::with_capacity(vertices.len());
    let mut colours = Vec::with_capacity(vertices.len());
    for (i, v) in vertices.iter().enumerate() {
        let get = |name: &str| {
            v.get(name)
                .and_then(ply_number)
                .ok_or_else(|| bad("vertex", i, format!("{name} is not a number")))
        };
        positions.push(Vec3::new(get("x")?, get("y")?, get("z")?));
        match colouring {
            Colouring::Strain => colours.push(strain_colour(get("strain")?)),
            Colouring::FromFile => {
                let channel = |name: &str| {
                    v.get(name)
                        .and_then(channel)
                        .ok_or_else(|| bad("vertex", i, format!("{name} is not a colour")))
                };
                colours.push([channel("red")?, channel("green")?, channel("blue")?]);
            }
            Colouring::Plain => {}
        }
    }

    let mut triangles = Vec::new();
    if let Some(face_def) = ply.header.elements.get("face") {
        let key = ["vertex_indices", "vertex_index"]
            .into_iter()
            .find(|k| face_def.properties.contains_key(*k))
            .ok_or_else(|| missing_property("face", "vertex_indices (or vertex_index)"))?;
        let count = positions.len();
        for (face, f) in ply.payload.get("face").unwrap_or(&none).iter().enumerate() {
            let corners = f.get(key).and_then(Property::to_u32_list).ok_or_else(|| {
                bad(
                    "face",
                    face,
                    format!("{key} is not a list of non-negative integers"),
                )
            })?;
            if let Some(&vertex) = corners.iter().find(|&&i| i as usize >= count) {
                return Err(RenderError::IndexOutOfRange {
                    path: path.to_path_buf(),
                    face,
                    vertex: vertex as usize,
                    count,
                });
            }
            for k in 1..corners.len().saturating_sub(1) {
                triangles.push([corners[0], corners[k], corners[k + 1]].map(|i| i as usize));
            }
        }
    }

    Ok(LoadedMesh::new(positions, triangles, colours, colouring))
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

/// Bytes as they are; floating point as a fraction of full intensity.
fn channel(p: &Property) -> Option<u8> {
    match *p {
        Property::UChar(v) => Some(v),
        Property::Float(v) => Some((v.clamp(0.0, 1.0) * 255.0).round() as u8),
        Property::Double(v) => Some((v.clamp(0.0, 1.0) * 255.0).round() as u8),
        _ => ply_number(p).map(|v| v.clamp(0.0, 255.0) as u8),
    }
}
