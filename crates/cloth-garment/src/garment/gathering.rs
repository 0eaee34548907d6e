//! Gathering: a seam whose sides differ in length is sewn as a gathering stitch sews it.
//! Its vertices pair one to one, spaced evenly along each side, so each step along the
//! longer side is longer than its partner's, and the triangle on that step is squeezed
//! along the seam when sewn. Real gathered cloth at the seam line is pleated finer than
//! any cell, and such pleats carry no more compression than it takes to buckle them: the
//! triangles along the longer side are marked here, and the sewing gives them the
//! compressive stiffness of a buckling cell (see [`crate::sewing`]). The rest of the
//! panel keeps its own, so the fullness folds out of the cloth beside the seam: the
//! gathers.
//!
//! With the fabric's own compressive stiffness those triangles pushed the shorter side
//! apart: a 2:1 skirt's waistband stretched 2-3 % and its seams would not close in 3,000
//! sewing steps (14.5 mm still open). Drawing the seam edges up in the rest shape instead
//! held a seam pair 3-9 mm open: the shortened edges are not those of any flat cell, and
//! the cells beside them fought over it.

use super::SeamPairs;
use cloth_core::ClothMesh;

/// Sides whose steps differ by less than this fraction are sewn as they are.
const SAME: f64 = 1e-3;

/// The triangles touching a vertex on the longer side of a seam step, in order.
pub(super) fn gathered_triangles(mesh: &ClothMesh, seams: &[SeamPairs]) -> Vec<usize> {
    let uv = mesh.uv();
    let mut gathered_vertex = vec![false; uv.len()];
    for seam in seams {
        for w in seam.pairs.windows(2) {
            let step = |side: usize| (w[0][side], w[1][side]);
            let length = |(i, j): (usize, usize)| (uv[j] - uv[i]).norm();
            let (a, b) = (step(0), step(1));
            let (long, short) = if length(a) > length(b) { (a, b) } else { (b, a) };
            if length(long) <= (1.0 + SAME) * length(short) {
                continue;
            }
            gathered_vertex[long.0] = true;
            gathered_vertex[long.1] = true;
        }
    }
    (0..mesh.triangles().len())
        .filter(|&t| mesh.triangles()[t].iter().any(|&v| gathered_vertex[v]))
        .collect()
}
