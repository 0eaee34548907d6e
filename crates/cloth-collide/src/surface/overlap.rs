//! Parts inside parts: avatar meshes often come as overlapping closed pieces (arms pushed
//! through the torso, eyeballs in the head). The cloth can only ever touch the union's
//! outside, so the triangles lying inside other parts are found here and kept out of
//! contact.

use cloth_core::math::Vec3;
use rayon::prelude::*;

use super::winding::WindingTree;

/// Which triangles lie inside another part: those whose three corners all do. A corner is
/// tested a little off the surface along its outward normal, where its own part's winding
/// number is 0 (closed) and the others' is what remains.
pub(super) fn buried_triangles(vertices: &[Vec3], triangles: &[[u32; 3]], label: &[usize]) -> Vec<bool> {
    let parts = label.iter().copied().max().map_or(0, |m| m + 1);
    if parts < 2 {
        return vec![false; triangles.len()];
    }
    let tree = WindingTree::new(vertices, triangles);
    // Angle-weighted outward normals and the shortest edge at each vertex.
    let mut normal = vec![Vec3::zeros(); vertices.len()];
    let mut shortest = vec![f64::INFINITY; vertices.len()];
    for tri in triangles {
        let p = tri.map(|i| vertices[i as usize]);
        let n = (p[1] - p[0]).cross(&(p[2] - p[0]));
        let Some(n) = n.try_normalize(0.0) else { continue };
        for k in 0..3 {
            let (e, f) = (p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]);
            let i = tri[k] as usize;
            normal[i] += e.angle(&f) * n;
            shortest[i] = shortest[i].min(e.norm());
        }
    }
    // A tenth of the shortest edge: off the surface, yet nearer to it than to anything
    // another part could put between.
    let inside: Vec<bool> = (0..vertices.len())
        .into_par_iter()
        .map(|i| match normal[i].try_normalize(1e-12) {
            Some(n) if shortest[i].is_finite() => {
                tree.winding_number(&(vertices[i] + 0.1 * shortest[i] * n)) >= 0.5
            }
            _ => false,
        })
        .collect();
    triangles
        .iter()
        .map(|tri| tri.iter().all(|&i| inside[i as usize]))
        .collect()
}
