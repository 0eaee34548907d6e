//! PLY with strain colours: each vertex coloured by the larger of the warp and weft strain
//! of its triangles (mean over them), blue at 0 % through green and yellow to red at 5 %
//! and beyond; compression is shown as 0.

use crate::obj::write_atomically;
use cloth_core::{ClothMesh, StrainReport, Vec3};
use std::path::Path;

/// The strain at which the colour scale saturates, %.
pub const FULL_SCALE_PERCENT: f64 = 5.0;

/// Writes an ASCII PLY of the cloth with per-vertex colours and a `strain` property (%).
pub fn write_strain_ply(path: &Path, mesh: &ClothMesh, positions: &[Vec3]) -> std::io::Result<()> {
    let strain = StrainReport::new(mesh, positions);
    let n = mesh.vertex_count();
    let (mut sum, mut count) = (vec![0.0; n], vec![0u32; n]);
    for (t, tri) in mesh.triangles().iter().enumerate() {
        let s = strain.warp[t].max(strain.weft[t]).max(0.0);
        for &i in tri {
            sum[i] += s;
            count[i] += 1;
        }
    }
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
        for (i, p) in positions.iter().enumerate() {
            let s = sum[i] / count[i].max(1) as f64;
            let [r, g, b] = colour(s / FULL_SCALE_PERCENT);
            writeln!(out, "{} {} {} {r} {g} {b} {s}", p.x, p.y, p.z)?;
        }
        for t in mesh.triangles() {
            writeln!(out, "3 {} {} {}", t[0], t[1], t[2])?;
        }
        Ok(())
    })
}

/// Blue, cyan, green, yellow, red for `f` from 0 to 1 (clamped).
pub fn colour(f: f64) -> [u8; 3] {
    let f = if f.is_finite() { f.clamp(0.0, 1.0) } else { 1.0 };
    let stops = [
        [0.0, 0.0, 1.0],
        [0.0, 1.0, 1.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
        [1.0, 0.0, 0.0],
    ];
    let x = f * 4.0;
    let k = (x.floor() as usize).min(3);
    let w = x - k as f64;
    let c: Vec<u8> = (0..3)
        .map(|j| ((stops[k][j] * (1.0 - w) + stops[k + 1][j] * w) * 255.0).round() as u8)
        .collect();
    [c[0], c[1], c[2]]
}
