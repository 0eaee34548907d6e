//! PLY with strain colours: each vertex coloured by the larger of the warp and weft strain
//! of its triangles (mean over them), blue at 0 % through green and yellow to red at 5 %
//! and beyond; compression is shown as 0.

use cloth_core::{math::Vec3, ClothMesh};
use cloth_formats::atomic::write_atomically;
use cloth_render::strain_colours::{strain_colour, vertex_strain, FULL_SCALE_PERCENT};
use std::path::Path;

/// Writes an ASCII PLY of the cloth with per-vertex colours and a `strain` property (%).
pub fn write_strain_ply(path: &Path, mesh: &ClothMesh, positions: &[Vec3]) -> std::io::Result<()> {
    let strain = vertex_strain(mesh, positions);
    let n = mesh.vertex_count();
    write_atomically(path, |out| {
        writeln!(
            out,
            "ply\nformat ascii 1.0\ncomment cloth strain, % (colour full scale {FULL_SCALE_PERCENT} %)"
        )?;
        writeln!(out, "element vertex {n}")?;
        writeln!(out, "property double x\nproperty double y\nproperty double z")?;
        writeln!(
            out,
            "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty float strain"
        )?;
        writeln!(out, "element face {}", mesh.triangles().len())?;
        writeln!(out, "property list uchar int vertex_indices\nend_header")?;
        for (p, &s) in positions.iter().zip(&strain) {
            let [r, g, b] = strain_colour(s);
            writeln!(out, "{} {} {} {r} {g} {b} {s}", p.x, p.y, p.z)?;
        }
        for t in mesh.triangles() {
            writeln!(out, "3 {} {} {}", t[0], t[1], t[2])?;
        }
        Ok(())
    })
}
