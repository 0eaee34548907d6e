//! OBJ through `tobj`: every object and group merged, polygons split into triangles,
//! points and lines dropped, vertex colours (`v x y z r g b`) kept when present.

use super::{Colouring, LoadedMesh};
use crate::error::RenderError;
use crate::NEUTRAL_GREY;
use cloth_core::math::Vec3;
use std::path::Path;

pub(super) fn read(path: &Path) -> Result<LoadedMesh, RenderError> {
    let bytes = std::fs::read(path).map_err(|source| RenderError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    // One index per corner into the positions, so neighbouring triangles share vertices
    // and shading is smooth across them.
    let options = tobj::LoadOptions {
        single_index: false,
        ..tobj::GPU_LOAD_OPTIONS
    };
    // Materials are not drawn, so `mtllib` files are not opened.
    let (models, _) =
        tobj::load_obj_buf(&mut &bytes[..], &options, |_| Ok(Default::default())).map_err(|e| {
            RenderError::Parse {
                path: path.to_path_buf(),
                line: None,
                message: e.to_string(),
            }
        })?;
    let any_colours = models.iter().any(|m| has_colours(&m.mesh));
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    let mut colours = Vec::new();
    for model in &models {
        let mesh = &model.mesh;
        let first = positions.len();
        positions.extend(
            mesh.positions
                .chunks_exact(3)
                .map(|c| Vec3::new(c[0], c[1], c[2])),
        );
        triangles.extend(
            mesh.indices
                .chunks_exact(3)
                .map(|c| [0, 1, 2].map(|k| first + c[k] as usize)),
        );
        if any_colours {
            if has_colours(mesh) {
                colours.extend(
                    mesh.vertex_color
                        .chunks_exact(3)
                        .map(|c| [0, 1, 2].map(|k| (c[k].clamp(0.0, 1.0) * 255.0).round() as u8)),
                );
            } else {
                colours.resize(positions.len(), NEUTRAL_GREY);
            }
        }
    }
    let colouring = if any_colours {
        Colouring::FromFile
    } else {
        Colouring::Plain
    };
    Ok(LoadedMesh::new(positions, triangles, colours, colouring))
}

fn has_colours(mesh: &tobj::Mesh) -> bool {
    !mesh.vertex_color.is_empty() && mesh.vertex_color.len() == mesh.positions.len()
}
