//! A contact layer thinned where the surface is flat. The contact keeps the cloth's
//! particles a thickness off the surface, but not its edges: a straight edge between two
//! particles on a convex surface of radius `R` dips `L^2 / (8 R)` below them (1.9 mm for
//! an edge of 1.5 cm on a 1.5 cm arm crease). A layer thick enough for the tightest curve
//! of a body lies centimetres round a waist or a chest, where it adds `2 pi` times its
//! thickness to every girth (1.9 cm at 3 mm): GarmentCode's close-fitting designs,
//! cut 4-7 % under the body's girths, were stretched past 5 % by the layer as much as by
//! the fit. So the layer can follow the surface: at each vertex, a floor plus the dip of
//! the cloth's edge over the surface's sharpest convex curve there (the largest within an
//! edge's length, since an edge spans more than one of the surface's), up to the body's
//! thickness.

use cloth_core::math::Vec3;

/// The contact thickness at each of `vertices`, over `triangles`: `floor` plus the dip
/// of a straight edge `edge_length` long over the surface's sharpest convex curvature
/// within that length (along the surface's edges), at most `ceiling`, m. Vertices on no
/// triangle get `ceiling`.
pub(crate) fn thinned_layer(
    vertices: &[Vec3],
    triangles: &[[u32; 3]],
    edge_length: f64,
    floor: f64,
    ceiling: f64,
) -> Vec<f64> {
    let n = vertices.len();
    let mut normals = vec![Vec3::zeros(); n];
    for t in triangles {
        let [a, b, c] = t.map(|i| vertices[i as usize]);
        // Weighted by area: the cross product's length.
        let face = (b - a).cross(&(c - a));
        for &i in t {
            normals[i as usize] += face;
        }
    }
    let normals: Vec<Option<Vec3>> = normals.iter().map(|m| m.try_normalize(1e-30)).collect();
    // The sharpest convex curvature along the edges at each vertex: along an edge from
    // `p` to `q` with normals `m` and `n`, `(m - n) . (p - q) / |p - q|^2` (1 / R on a
    // sphere of radius R, negative where concave).
    let mut curvature = vec![0.0f64; n];
    let mut used = vec![false; n];
    for t in triangles {
        for k in 0..3 {
            let (i, j) = (t[k] as usize, t[(k + 1) % 3] as usize);
            used[i] = true;
            let d = vertices[i] - vertices[j];
            let length2 = d.norm_squared();
            let kappa = match (normals[i], normals[j]) {
                (Some(m), Some(q)) if length2 > 0.0 => (m - q).dot(&d) / length2,
                // No direction to measure along: as curved as may be.
                _ => f64::INFINITY,
            };
            curvature[i] = curvature[i].max(kappa);
            curvature[j] = curvature[j].max(kappa);
        }
    }
    let own: Vec<f64> = (0..n)
        .map(|i| {
            if used[i] {
                (floor + edge_length * edge_length * curvature[i] / 8.0).min(ceiling)
            } else {
                ceiling
            }
        })
        .collect();
    // The largest within an edge's length of each vertex too: an edge whose ends touch
    // the surface either side of a ridge dips over the ridge.
    let mut neighbours: Vec<Vec<u32>> = vec![Vec::new(); n];
    for t in triangles {
        for k in 0..3 {
            let (i, j) = (t[k], t[(k + 1) % 3]);
            neighbours[i as usize].push(j);
            neighbours[j as usize].push(i);
        }
    }
    let mut layer = own.clone();
    let mut seen = vec![usize::MAX; n];
    let mut stack = Vec::new();
    for (i, out) in layer.iter_mut().enumerate() {
        seen[i] = i;
        stack.push(i as u32);
        while let Some(j) = stack.pop() {
            *out = out.max(own[j as usize]);
            for &k in &neighbours[j as usize] {
                let k = k as usize;
                if seen[k] != i && (vertices[k] - vertices[i]).norm() <= edge_length {
                    seen[k] = i;
                    stack.push(k as u32);
                }
            }
        }
    }
    layer
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::TriSurface;

    #[test]
    fn the_layer_is_the_floor_and_the_dip_of_an_edge_over_convex_curves_only() {
        // On a sphere of radius 5 cm, an edge of 1.5 cm dips 1.5^2 / (8 * 5) cm = 0.5625 mm
        // below its ends.
        let sphere = TriSurface::icosphere(0.05, 5).unwrap();
        let layer = thinned_layer(sphere.vertices(), sphere.triangles(), 0.015, 0.001, 0.003);
        let dip = 0.015f64.powi(2) / (8.0 * 0.05);
        // Within 5 %: an icosphere's facets differ in size, so the normals averaged from
        // them lean off the radius by a fraction of a facet's angle.
        for &t in &layer {
            assert!(
                (t - 0.001 - dip).abs() < 0.05 * dip,
                "{t} against {}",
                0.001 + dip
            );
        }
        // A sphere of 5 mm: the dip (5.6 mm) is over the ceiling.
        let small = TriSurface::icosphere(0.005, 3).unwrap();
        let layer = thinned_layer(small.vertices(), small.triangles(), 0.015, 0.001, 0.003);
        assert!(layer.iter().all(|&t| t == 0.003));
        // A sheet bent round y into an arc of radius 10 cm, its normals out of the arc: as
        // a ridge, the floor and the dip over it, the same at every vertex; as a valley,
        // concave, the floor.
        let dip = 0.015f64.powi(2) / (8.0 * 0.1);
        for (ridge, dip) in [(true, dip), (false, 0.0)] {
            let (vertices, triangles) = arc_sheet(0.1, ridge);
            let layer = thinned_layer(&vertices, &triangles, 0.015, 0.001, 0.003);
            for &t in &layer {
                assert!(
                    (t - 0.001 - dip).abs() < 0.02 * dip.max(1e-5),
                    "{t} against {}",
                    0.001 + dip
                );
            }
        }
    }

    /// A 21 by 21 sheet 1 cm apart, bent round the y axis into an arc of `radius` whose
    /// normals point up: a ridge (the arc's outside up) or a valley.
    fn arc_sheet(radius: f64, ridge: bool) -> (Vec<Vec3>, Vec<[u32; 3]>) {
        let sign = if ridge { 1.0 } else { -1.0 };
        let vertices = (0..21 * 21)
            .map(|k| {
                let angle = (k % 21) as f64 * 0.01 / radius - 0.1 / radius;
                let y = ((k / 21) as f64 - 10.0) * 0.01;
                Vec3::new(radius * angle.sin(), y, sign * radius * (angle.cos() - 1.0))
            })
            .collect();
        let mut triangles = Vec::new();
        for j in 0..20u32 {
            for i in 0..20u32 {
                let k = j * 21 + i;
                triangles.push([k, k + 1, k + 22]);
                triangles.push([k, k + 22, k + 21]);
            }
        }
        (vertices, triangles)
    }
}
