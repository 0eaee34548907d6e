//! The strain colour scale every output shares (PLY, glTF, pictures): blue at 0 % through
//! cyan, green and yellow to red at [`FULL_SCALE_PERCENT`] and beyond, each vertex taking
//! the mean strain of its triangles with compression shown as 0.

use cloth_core::{math::Vec3, ClothMesh, StrainReport};

/// The strain at which the colour scale saturates, %.
pub const FULL_SCALE_PERCENT: f64 = 5.0;

/// Each vertex's mean over its triangles of `per_triangle` (negative values, compression,
/// count as 0).
pub fn vertex_means(vertices: usize, triangles: &[[usize; 3]], per_triangle: &[f64]) -> Vec<f64> {
    let (mut sum, mut count) = (vec![0.0; vertices], vec![0u32; vertices]);
    for (t, value) in triangles.iter().zip(per_triangle) {
        for &i in t {
            sum[i] += value.max(0.0);
            count[i] += 1;
        }
    }
    sum.iter()
        .zip(&count)
        .map(|(s, &c)| s / f64::from(c.max(1)))
        .collect()
}

/// Each vertex's strain, %: the mean over its triangles of the larger of warp and weft.
pub fn vertex_strain(mesh: &ClothMesh, positions: &[Vec3]) -> Vec<f64> {
    let strain = StrainReport::new(mesh, positions);
    let larger: Vec<f64> = strain
        .warp
        .iter()
        .zip(&strain.weft)
        .map(|(a, b)| a.max(*b))
        .collect();
    vertex_means(mesh.vertex_count(), mesh.triangles(), &larger)
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
    [0, 1, 2].map(|j| ((stops[k][j] * (1.0 - w) + stops[k + 1][j] * w) * 255.0).round() as u8)
}

/// The colour of a strain of `percent` % on the scale.
pub fn strain_colour(percent: f64) -> [u8; 3] {
    colour(percent / FULL_SCALE_PERCENT)
}
