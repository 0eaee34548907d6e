//! Measuring the meshed body as a tape measure would: the length of a horizontal section.

use cloth_collide::TriSurface;

/// Total length of the curves where the plane at height `z` cuts the surface.
///
/// A vertex counts as above the plane when `z_vertex >= z`, below otherwise. Every triangle
/// with corners on both sides contributes the segment between its two crossing edges. With
/// this half-open rule a plane through a ring of vertices still counts each ring edge
/// exactly once (from the triangle below it), so the girth at a key level is the ring's
/// polygon perimeter.
pub(crate) fn section_length(surface: &TriSurface, z: f64) -> f64 {
    let vertices = surface.vertices();
    let mut total = 0.0;
    for tri in surface.triangles() {
        let p = tri.map(|i| vertices[i as usize]);
        let above = p.map(|v| v.z >= z);
        let mut crossings = [p[0]; 2];
        let mut count = 0;
        for k in 0..3 {
            let (a, b) = (p[k], p[(k + 1) % 3]);
            if above[k] != above[(k + 1) % 3] {
                let t = (z - a.z) / (b.z - a.z);
                crossings[count] = a + t * (b - a);
                count += 1;
            }
        }
        // A triangle is crossed on exactly zero or two edges.
        if count == 2 {
            total += (crossings[1] - crossings[0]).norm();
        }
    }
    total
}
