//! The generalized winding number (Jacobson, Kavan & Sorkine-Hornung 2013), evaluated
//! hierarchically (Barill, Dickson, Schmidt, Levin & Jacobson 2018): the inside/outside
//! answer for surfaces that are not watertight.
//!
//! For a closed, outward surface the winding number of a point is 1 inside and 0 outside;
//! a hole lets it fall off gradually near the hole only, a doubled part counts twice, and
//! a flipped triangle spoils only its own share. So "inside" is `w >= 1/2`, and the answer
//! degrades gracefully where pseudonormals (which trust the nearest triangle alone) flip.
//!
//! Far clusters of triangles are replaced by their dipole: the sum of their vector areas
//! `A` placed at their area-weighted centre `c`, whose solid angle is `A . r / |r|^3` with
//! `r = c - p`. A cluster counts as far once `p` is more than [`FAR`] radii from its
//! centre; near ones are summed exactly, triangle by triangle. (The next term of the
//! expansion, tried, made the answer worse at these distances, where the series converges
//! slowly: on a sphere with a hole the largest error went from 0.026 to 0.070.)

use cloth_core::math::Vec3;

/// Clusters this many of their radii away are summed as dipoles. At 2 the error stays
/// under 0.03 of a winding number, far from the 1/2 that decides inside (the tests compare
/// with the exact sum on a sphere with a hole); 3 halves the error for twice the work.
const FAR: f64 = 2.0;
/// Triangles in a leaf.
const LEAF: usize = 8;

/// A bounding hierarchy over triangles with each node's dipole, for fast winding numbers.
#[derive(Debug, Clone)]
pub struct WindingTree {
    nodes: Vec<Node>,
    /// Triangle corners in the tree's order (leaves hold runs of them).
    corners: Vec<[Vec3; 3]>,
}

#[derive(Debug, Clone)]
struct Node {
    /// Area-weighted centre of the node's triangles.
    centre: Vec3,
    /// Largest distance of any of its corners from `centre`.
    radius: f64,
    /// Sum of the triangles' vector areas, half the cross products of their edges.
    area: Vec3,
    /// Leaves: the run `first..first + count` of `corners`. Inner nodes: `count == 0` and
    /// the children are `first` and `first + 1`.
    first: u32,
    count: u32,
}

impl WindingTree {
    /// The tree of `triangles` (indices into `vertices`), taken as they are oriented.
    pub fn new(vertices: &[Vec3], triangles: &[[u32; 3]]) -> Self {
        let mut corners: Vec<[Vec3; 3]> = triangles
            .iter()
            .map(|t| t.map(|i| vertices[i as usize]))
            .collect();
        let mut nodes = vec![Node::empty()];
        // (node, first, count): split until leaves are small, children placed in pairs.
        let mut work = vec![(0usize, 0usize, corners.len())];
        while let Some((node, first, count)) = work.pop() {
            let run = &mut corners[first..first + count];
            nodes[node] = Node::of(run, first);
            if count <= LEAF {
                continue;
            }
            let (lo, hi) = centroid_bounds(run);
            let axis = (hi - lo).imax();
            let middle = count / 2;
            run.select_nth_unstable_by(middle, |a, b| centroid(a)[axis].total_cmp(&centroid(b)[axis]));
            let left = nodes.len();
            nodes.push(Node::empty());
            nodes.push(Node::empty());
            nodes[node].first = left as u32;
            nodes[node].count = 0;
            work.push((left, first, middle));
            work.push((left + 1, first + middle, count - middle));
        }
        Self { nodes, corners }
    }

    /// The winding number of `p`: about 1 inside a closed outward surface, 0 outside.
    pub fn winding_number(&self, p: &Vec3) -> f64 {
        if self.corners.is_empty() {
            return 0.0;
        }
        let mut solid_angle = 0.0;
        // Median splits keep the depth under log2(n / LEAF) + 1, so a depth-first stack
        // holds under 2 + 32 entries for any u32 triangle count: no allocation per query.
        let mut stack = [0u32; 64];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let node = &self.nodes[stack[top] as usize];
            let r = node.centre - p;
            let d2 = r.norm_squared();
            if d2 > (FAR * node.radius).powi(2) {
                solid_angle += node.area.dot(&r) / (d2 * d2.sqrt());
            } else if node.count > 0 {
                let run = node.first as usize..(node.first + node.count) as usize;
                solid_angle += self.corners[run]
                    .iter()
                    .map(|t| triangle_solid_angle(t, p))
                    .sum::<f64>();
            } else {
                stack[top] = node.first;
                stack[top + 1] = node.first + 1;
                top += 2;
            }
        }
        solid_angle / (4.0 * std::f64::consts::PI)
    }

    /// The winding number summed exactly over every triangle: the reference for tests.
    pub fn exact_winding_number(&self, p: &Vec3) -> f64 {
        self.corners
            .iter()
            .map(|t| triangle_solid_angle(t, p))
            .sum::<f64>()
            / (4.0 * std::f64::consts::PI)
    }
}

impl Node {
    fn empty() -> Self {
        Self {
            centre: Vec3::zeros(),
            radius: 0.0,
            area: Vec3::zeros(),
            first: 0,
            count: 0,
        }
    }

    fn of(run: &[[Vec3; 3]], first: usize) -> Self {
        let mut area = Vec3::zeros();
        let (mut weighted, mut total) = (Vec3::zeros(), 0.0);
        for t in run {
            let a = 0.5 * (t[1] - t[0]).cross(&(t[2] - t[0]));
            let size = a.norm();
            area += a;
            weighted += size * centroid(t);
            total += size;
        }
        // Zero-area runs (which a checked surface does not have) fall back to the mean.
        let centre = if total > 0.0 {
            weighted / total
        } else {
            run.iter().map(centroid).sum::<Vec3>() / run.len().max(1) as f64
        };
        let radius = run
            .iter()
            .flatten()
            .map(|c| (c - centre).norm())
            .fold(0.0, f64::max);
        Self {
            centre,
            radius,
            area,
            first: first as u32,
            count: run.len() as u32,
        }
    }
}

fn centroid(t: &[Vec3; 3]) -> Vec3 {
    (t[0] + t[1] + t[2]) / 3.0
}

fn centroid_bounds(run: &[[Vec3; 3]]) -> (Vec3, Vec3) {
    let first = centroid(&run[0]);
    run.iter().fold((first, first), |(lo, hi), t| {
        let c = centroid(t);
        (lo.inf(&c), hi.sup(&c))
    })
}

/// The signed solid angle the triangle subtends at `p` (Van Oosterom & Strackee 1983):
/// positive when `p` sees its back, as a point inside an outward surface does.
fn triangle_solid_angle(t: &[Vec3; 3], p: &Vec3) -> f64 {
    let (a, b, c) = (t[0] - p, t[1] - p, t[2] - p);
    let (la, lb, lc) = (a.norm(), b.norm(), c.norm());
    let numerator = a.dot(&b.cross(&c));
    let denominator = la * lb * lc + a.dot(&b) * lc + b.dot(&c) * la + c.dot(&a) * lb;
    2.0 * numerator.atan2(denominator)
}
