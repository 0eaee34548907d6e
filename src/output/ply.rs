//! PLY with strain colours: each vertex coloured by the larger of the warp and weft strain
//! of its triangles (mean over them), blue at 0 % through green and yellow to red at 5 %
//! and beyond; compression is shown as 0.

use crate::scene_file::UpAxis;
use cloth_core::{math::Vec3, ClothMesh};
use cloth_formats::panels::PanelLabels;
use cloth_formats::ply::{write_strain_ply as write_ply, StrainPly};
use cloth_render::strain_colours::{strain_colour, vertex_strain, FULL_SCALE_PERCENT};
use std::path::Path;

/// Writes an ASCII PLY of the cloth with per-vertex colours and a `strain` property (%),
/// and a garment's `panel` per vertex (its lowest-numbered panel on a seam); `positions`
/// are in the frame `up`, which the header names.
pub fn write_strain_ply(
    path: &Path,
    mesh: &ClothMesh,
    positions: &[Vec3],
    up: UpAxis,
    panels: Option<&PanelLabels>,
) -> std::io::Result<()> {
    let strain = vertex_strain(mesh, positions);
    let colours: Vec<[u8; 3]> = strain.iter().map(|&s| strain_colour(s)).collect();
    let mut comments = up.file_header("the cloth");
    comments.push(format!("strain, % (colour full scale {FULL_SCALE_PERCENT} %)"));
    let labels = panels.map(|p| p.vertex_label(mesh.triangles(), mesh.vertex_count()));
    write_ply(
        path,
        &StrainPly {
            comments: &comments,
            positions,
            triangles: mesh.triangles(),
            colours: &colours,
            strain: &strain,
            panels: labels.as_deref().zip(panels.map(PanelLabels::names)),
        },
    )
}
