//! Pulling cloth out of itself: intersection contour minimisation (Volino & Magnenat-
//! Thalmann, 2006). Pieces that begin through each other are exempt from each other's
//! collision until they come apart (see [`super::Tangle`]), and a panel folded through
//! itself by the weld is not held apart by a collision that starts crossed; nothing but the
//! seams and gravity took either apart. Where three panels meet, a hood's or a collar's
//! corner folded through the shoulder it is sewn to stayed through it to rest: of the
//! crossings left at rest on GarmentCode's rand_1_042 and rand_1_076, all 16 and all 31
//! touched such a junction (a particle of three or more panels) or its ring of
//! neighbours, and 14 of 16 on rand_1_034 lay within two rings of one.
//!
//! Where two surfaces pass through each other they meet along a curve, and shrinking the
//! curve to nothing takes them apart. At a point of the curve, with the surfaces' normals
//! `n_a` and `n_b`, the curve runs along `d = n_a x n_b`; moving surface A by `u` against B
//! slides the curve across B by `(n_a . u) / (n_a . m_b)` along `m_b = d x n_b`, and
//! likewise across A. The curve shortens fastest when each point moves along its curvature
//! `k` (the sum of the unit vectors to its neighbours on the curve), so A is moved against
//! B by `(k . m_b)(n_a . m_b) n_a - (k . m_a)(n_b . m_a) n_b`: each term slides the curve
//! along `k` across one surface, whatever the normals' signs. The curve is traced from the
//! crossings: an edge through a triangle is a point of it, and two points whose edge's and
//! triangle's triangles are the same pair are joined.

use super::intersections::crossing_pairs;
use super::topology::Topology;
use crate::math::Vec3;

/// A point of the curve: the crossing of an edge through a triangle.
struct Point {
    edge: usize,
    triangle: usize,
    at: Vec3,
    normal_a: Vec3,
    normal_b: Vec3,
}

fn normal(topology: &Topology, x: &[Vec3], t: usize) -> Option<Vec3> {
    let [a, b, c] = topology.triangles[t].map(|i| x[i as usize]);
    (b - a).cross(&(c - a)).try_normalize(1e-18)
}

/// How far to move each particle (at most `step`, m) to shorten the curves along which
/// the crossings `pairs` (edge, triangle) run at `x`.
fn moves(topology: &Topology, x: &[Vec3], pairs: &[(usize, usize)], step: f64) -> Vec<Vec3> {
    let mut moves = vec![Vec3::zeros(); x.len()];
    let mut points = Vec::with_capacity(pairs.len());
    for &(edge, triangle) in pairs {
        let [p, q] = topology.edges[edge].map(|i| x[i as usize]);
        let Some(normal_b) = normal(topology, x, triangle) else {
            continue;
        };
        let corner = x[topology.triangles[triangle][0] as usize];
        let (dp, dq) = ((p - corner).dot(&normal_b), (q - corner).dot(&normal_b));
        let Some(normal_a) = topology
            .edge_triangles(edge)
            .filter_map(|s| normal(topology, x, s))
            .sum::<Vec3>()
            .try_normalize(1e-12)
        else {
            continue;
        };
        points.push(Point {
            edge,
            triangle,
            at: p + (q - p) * (dp / (dp - dq)),
            normal_a,
            normal_b,
        });
    }
    // Each pair of triangles through each other holds a piece of the curve, its ends two
    // points: an edge of either through the other. (Sorted, not hashed: the same sums in
    // the same order on every run.)
    let mut ends: Vec<((usize, usize), usize)> = Vec::with_capacity(2 * points.len());
    for (k, point) in points.iter().enumerate() {
        for s in topology.edge_triangles(point.edge) {
            ends.push(((s.min(point.triangle), s.max(point.triangle)), k));
        }
    }
    ends.sort_unstable();
    let mut curvature = vec![Vec3::zeros(); points.len()];
    for piece in ends.chunk_by(|a, b| a.0 == b.0) {
        if let [(_, i), (_, j)] = *piece {
            if let Some(towards) = (points[j].at - points[i].at).try_normalize(1e-12) {
                curvature[i] += towards;
                curvature[j] -= towards;
            }
        }
    }
    for (point, k) in points.iter().zip(&curvature) {
        let (na, nb) = (point.normal_a, point.normal_b);
        let Some(d) = na.cross(&nb).try_normalize(1e-6) else {
            continue;
        };
        let (ma, mb) = (d.cross(&na), d.cross(&nb));
        let u = step * 0.5 * (k.dot(&mb) * na.dot(&mb) * na - k.dot(&ma) * nb.dot(&ma) * nb);
        for i in topology.edges[point.edge] {
            moves[i as usize] += u;
        }
        for i in topology.triangles[point.triangle] {
            moves[i as usize] -= u;
        }
    }
    for m in &mut moves {
        let len = m.norm();
        if len > step {
            *m *= step / len;
        }
    }
    moves
}

/// Moves the cloth at `x` at most `step` (m) towards coming apart where it passes
/// through itself, but for the particles `fixed`, unless the move leaves more crossings
/// (then it is tried at half the step, once). Returns the crossings there were (edge,
/// triangle).
pub(crate) fn pull_apart(
    topology: &Topology,
    x: &mut [Vec3],
    fixed: impl Fn(usize) -> bool,
    step: f64,
) -> Vec<(usize, usize)> {
    // Layers being let through each other (see `LayerPass`) are left to pass.
    let crossings = |x: &[Vec3]| -> Vec<(usize, usize)> {
        crossing_pairs(topology, x)
            .into_iter()
            .filter(|&(e, t)| !topology.edge_triangle_passing(e, t))
            .collect()
    };
    let pairs = crossings(x);
    if pairs.is_empty() {
        return pairs;
    }
    let start = x.to_vec();
    for scale in [1.0, 0.5] {
        let by = moves(topology, &start, &pairs, scale * step);
        for (i, m) in by.iter().enumerate() {
            if !fixed(i) {
                x[i] = start[i] + m;
            }
        }
        if crossings(x).len() <= pairs.len() {
            return pairs;
        }
        x.copy_from_slice(&start);
    }
    pairs
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::ClothMesh;
    use nalgebra::Vector2;

    /// A sheet (one triangle across z = 0) and a hexagonal cone standing through it, its
    /// apex `apex` above, its rim `rim` below: the two meet along a closed curve round the
    /// apex, as a hood's corner pushed through a shoulder does.
    fn cone_through_sheet(apex: f64, rim: f64) -> (ClothMesh, Vec<Vec3>) {
        let mut x = vec![
            Vec3::new(-0.1, -0.1, 0.0),
            Vec3::new(0.1, -0.1, 0.0),
            Vec3::new(0.0, 0.15, 0.0),
            Vec3::new(0.0, 0.0, apex),
        ];
        let mut triangles = vec![[0, 1, 2]];
        for k in 0..6 {
            let a = std::f64::consts::TAU * k as f64 / 6.0;
            x.push(Vec3::new(0.02 * a.cos(), 0.02 * a.sin(), rim));
            triangles.push([3, 4 + k, 4 + (k + 1) % 6]);
        }
        let uv = x.iter().map(|p| Vector2::new(p.x, p.y)).collect();
        (ClothMesh::new(x.clone(), uv, triangles).unwrap(), x)
    }

    #[test]
    fn a_cone_through_a_sheet_is_pulled_back_out_of_it_along_the_shortening_curve() {
        let (mesh, mut x) = cone_through_sheet(0.005, -0.005);
        let topology = Topology::new(&mesh, &[], 0.0);
        let start = x.clone();
        let first = pull_apart(&topology, &mut x, |_| false, 5e-4).len();
        // The six edges from the apex to the rim go through the sheet.
        assert_eq!(first, 6);
        // The curve shrinks when the cone goes back down through the sheet, and the sheet
        // up over it: the apex moves down, the sheet's corners up, nothing sideways.
        assert!(x[3].z < start[3].z, "{:?}", x[3]);
        for i in 0..3 {
            assert!(x[i].z > start[i].z, "{:?}", x[i]);
        }
        assert!((x[3].xy() - start[3].xy()).norm() < 1e-12);
        let mut steps = 1;
        while !pull_apart(&topology, &mut x, |_| false, 5e-4).is_empty() {
            steps += 1;
            assert!(steps < 100, "still through after {steps} steps");
        }
        // Out, the apex no higher than the sheet (from there their collision keeps them
        // apart), after closing the 5 mm it was through at the most a step moves each
        // (0.5 mm the apex, 0.5 mm the sheet).
        assert!(
            x[3].z <= x[0].z,
            "{:?}",
            x.iter().map(|p| p.z).collect::<Vec<_>>()
        );
        assert_eq!(steps, 5);
    }

    #[test]
    fn cloth_that_does_not_cross_itself_is_not_moved() {
        let (mesh, mut x) = cone_through_sheet(-0.001, -0.005);
        let topology = Topology::new(&mesh, &[], 0.0);
        let start = x.clone();
        assert_eq!(pull_apart(&topology, &mut x, |_| false, 5e-4).len(), 0);
        assert_eq!(x, start);
    }

    #[test]
    fn fixed_particles_stay() {
        let (mesh, mut x) = cone_through_sheet(0.005, -0.005);
        let topology = Topology::new(&mesh, &[], 0.0);
        let start = x.clone();
        pull_apart(&topology, &mut x, |i| i < 3, 5e-4);
        assert_eq!(&x[..3], &start[..3]);
        assert!(x[3].z < start[3].z);
    }
}
