//! Volino & Magnenat-Thalmann's contour test, in the star form of Schvartzman, Pérez &
//! Otaduy (2010). A connected patch whose normals lie within a right angle of an axis is
//! a one-to-one picture of its projection on the plane across the axis only if its contour
//! (its boundary, projected) does not cross itself: a pleat folded flat, or a ramp
//! winding round, has normals in a narrow cone and still overlaps itself. A contour is
//! surely simple if it winds once round a centre with every edge turning forwards about
//! it (star-shaped): then the patch cannot touch itself, and the search skips it. Over a
//! step, with every point moving straight, the test holds at every instant of it.

use super::topology::Topology;
use crate::math::Vec3;
use crate::spatial::Bvh;
use std::f64::consts::TAU;

/// The positions at the start and the end of a step (the same for one instant).
#[derive(Clone, Copy)]
pub(crate) struct Motion<'a> {
    pub start: &'a [Vec3],
    pub end: &'a [Vec3],
}

/// Candidate centres tried per patch when the contours are made.
const CANDIDATES: usize = 16;

/// The contour of every node of a triangles' hierarchy, and of every two neighbouring
/// leaves together: the edges of its triangles with no triangle of it across them, each
/// directed as its triangle winds (so a contour runs counter-clockwise seen from the side
/// the normals point to), and the triangle whose centroid is its star centre, chosen where
/// the cloth starts as the one the contour turns round most surely. Fixed with the mesh.
#[derive(Debug, Clone, Default)]
pub(crate) struct Contours {
    start: Vec<u32>,
    edges: Vec<[u32; 2]>,
    centre: Vec<u32>,
    /// Per leaf, its neighbouring leaves and their joint contour's centre, in rows.
    pair_start: Vec<u32>,
    pairs: Vec<(u32, u32)>,
}

impl Contours {
    pub fn new(bvh: &Bvh, topology: &Topology, x: &[Vec3]) -> Self {
        let root = bvh.subtree(0);
        let mut place = vec![0usize; topology.triangles.len()];
        let mut leaf_of = vec![0u32; topology.triangles.len()];
        for (k, &t) in root.iter().enumerate() {
            place[t as usize] = k;
        }
        let mut out = Self {
            start: vec![0],
            pair_start: vec![0; bvh.node_count() + 1],
            ..Self::default()
        };
        for k in 0..bvh.node_count() {
            let span = bvh.span(k);
            let from = out.edges.len();
            for &t in bvh.subtree(k) {
                if bvh.is_leaf(k) {
                    leaf_of[t as usize] = k as u32;
                }
                let tri = topology.triangles[t as usize];
                for c in 0..3 {
                    let inside = topology
                        .across(t as usize, c)
                        .is_some_and(|s| span.contains(&place[s]));
                    if !inside {
                        out.edges.push([tri[(c + 1) % 3], tri[(c + 2) % 3]]);
                    }
                }
            }
            out.start.push(out.edges.len() as u32);
            let centre = best_centre(bvh.subtree(k), &out.edges[from..], topology, x);
            out.centre.push(centre);
        }
        for a in 0..bvh.node_count() {
            if bvh.is_leaf(a) {
                let mut seen: Vec<u32> = Vec::new();
                for &t in bvh.subtree(a) {
                    for c in 0..3 {
                        let Some(s) = topology.across(t as usize, c) else {
                            continue;
                        };
                        let b = leaf_of[s];
                        if b as usize != a && !seen.contains(&b) {
                            seen.push(b);
                        }
                    }
                }
                for b in seen {
                    let (ca, cb) = (out.of(a), out.of(b as usize));
                    let joint: Vec<[u32; 2]> = outer(ca, cb).chain(outer(cb, ca)).collect();
                    let both: Vec<u32> = bvh
                        .subtree(a)
                        .iter()
                        .chain(bvh.subtree(b as usize))
                        .copied()
                        .collect();
                    let centre = best_centre(&both, &joint, topology, x);
                    out.pairs.push((b, centre));
                }
            }
            out.pair_start[a + 1] = out.pairs.len() as u32;
        }
        out
    }

    /// Node `k`'s contour and the triangle at its centre.
    pub fn of(&self, k: usize) -> &[[u32; 2]] {
        &self.edges[self.start[k] as usize..self.start[k + 1] as usize]
    }

    pub fn centre(&self, k: usize) -> u32 {
        self.centre[k]
    }

    /// The centre of neighbouring leaves `a` and `b` together, if they are neighbours.
    pub fn pair_centre(&self, a: usize, b: usize) -> Option<u32> {
        self.pairs[self.pair_start[a] as usize..self.pair_start[a + 1] as usize]
            .iter()
            .find(|p| p.0 as usize == b)
            .map(|p| p.1)
    }
}

/// The edges of contour `own` that are not edges of contour `other` run backwards: with
/// `other`'s, the contour of the two patches together.
pub(crate) fn outer<'a>(
    own: &'a [[u32; 2]],
    other: &'a [[u32; 2]],
) -> impl Iterator<Item = [u32; 2]> + Clone + 'a {
    own.iter()
        .filter(move |e| !other.iter().any(|f| f[0] == e[1] && f[1] == e[0]))
        .copied()
}

/// Of the patch's triangles nearest its middle, the one whose centroid the contour turns
/// round with the widest margin at `x` (the nearest if none does).
fn best_centre(triangles: &[u32], contour: &[[u32; 2]], topology: &Topology, x: &[Vec3]) -> u32 {
    let centroid = |t: u32| {
        topology.triangles[t as usize]
            .iter()
            .map(|&i| x[i as usize])
            .sum::<Vec3>()
            / 3.0
    };
    let area = |t: u32| {
        let [a, b, c] = topology.triangles[t as usize].map(|i| x[i as usize]);
        (b - a).cross(&(c - a))
    };
    let normal: Vec3 = triangles.iter().map(|&t| area(t)).sum();
    let middle: Vec3 = triangles.iter().map(|&t| centroid(t)).sum::<Vec3>() / triangles.len() as f64;
    let mut near: Vec<(f64, u32)> = triangles
        .iter()
        .map(|&t| ((centroid(t) - middle).norm_squared(), t))
        .collect();
    near.sort_by(|p, q| p.0.total_cmp(&q.0).then(p.1.cmp(&q.1)));
    let Some(axis) = normal.try_normalize(0.0) else {
        return near[0].1;
    };
    let margin = |t: u32| {
        let c = centroid(t);
        contour
            .iter()
            .map(|&[a, b]| {
                let (p, q) = (x[a as usize] - c, x[b as usize] - c);
                axis.dot(&p.cross(&q)) / (p.norm() * q.norm()).max(f64::MIN_POSITIVE)
            })
            .fold(f64::INFINITY, f64::min)
    };
    near.iter()
        .take(CANDIDATES)
        .map(|&(_, t)| (margin(t), t))
        .fold((f64::NEG_INFINITY, near[0].1), |best, m| {
            if m.0 > best.0 {
                m
            } else {
                best
            }
        })
        .1
}

/// Whether the contour `edges`, projected along `axis`, winds once round `centre` (a point
/// moving with the cloth, the centroid of three particles) with every edge turning forwards
/// (counter-clockwise about `axis`) throughout the motion.
pub(crate) fn star_shaped(
    edges: impl Iterator<Item = [u32; 2]>,
    centre: [u32; 3],
    axis: &Vec3,
    motion: &Motion<'_>,
) -> bool {
    let at = |x: &[Vec3]| centre.iter().map(|&i| x[i as usize]).sum::<Vec3>() / 3.0;
    let (c0, c1) = (at(motion.start), at(motion.end));
    let mut turn = 0.0;
    for [a, b] in edges {
        let (a0, b0) = (motion.start[a as usize] - c0, motion.start[b as usize] - c0);
        let (da, db) = (motion.end[a as usize] - c1 - a0, motion.end[b as usize] - c1 - b0);
        // The edge's turn about the centre, axis . (a x b), is quadratic in time.
        let k0 = axis.dot(&a0.cross(&b0));
        let k1 = axis.dot(&(a0.cross(&db) + da.cross(&b0)));
        let k2 = axis.dot(&da.cross(&db));
        if !(k0 > 0.0 && k0 + k1 + k2 > 0.0) {
            return false;
        }
        if k2 > 0.0 {
            let t = -k1 / (2.0 * k2);
            if t > 0.0 && t < 1.0 && k0 + t * (k1 + t * k2) <= 0.0 {
                return false;
            }
        }
        let along = a0.dot(&b0) - axis.dot(&a0) * axis.dot(&b0);
        turn += k0.atan2(along);
    }
    // Each turn is forwards, so the total is a whole number of rounds.
    (turn - TAU).abs() < 1.0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `points` with the centre last.
    fn run(points: &[Vec3], edges: &[[u32; 2]]) -> bool {
        let motion = Motion {
            start: points,
            end: points,
        };
        let c = points.len() as u32 - 1;
        star_shaped(edges.iter().copied(), [c; 3], &Vec3::z(), &motion)
    }

    /// `n` points round a circle, then its centre.
    fn ring(n: usize, radius: f64) -> Vec<Vec3> {
        (0..n)
            .map(|k| {
                let a = TAU * k as f64 / n as f64;
                Vec3::new(radius * a.cos(), radius * a.sin(), 0.1 * a.sin())
            })
            .chain([Vec3::zeros()])
            .collect()
    }

    #[test]
    fn a_convex_loop_is_star_shaped_and_reversed_or_doubled_it_is_not() {
        let p = ring(8, 1.0);
        let forwards: Vec<[u32; 2]> = (0..8).map(|k| [k, (k + 1) % 8]).collect();
        assert!(run(&p, &forwards));
        let backwards: Vec<[u32; 2]> = forwards.iter().map(|&[a, b]| [b, a]).collect();
        assert!(!run(&p, &backwards));
        // Two loops round one centre (a ramp winding over itself): twice the turn.
        let p = ring(16, 1.0);
        let evens: Vec<[u32; 2]> = (0..8).map(|k| [2 * k, (2 * k + 2) % 16]).collect();
        assert!(run(&p, &evens));
        let odds = (0..8).map(|k| [2 * k + 1, (2 * k + 3) % 16]);
        let twice: Vec<[u32; 2]> = evens.iter().copied().chain(odds).collect();
        assert!(!run(&p, &twice));
    }

    #[test]
    fn a_contour_crossing_itself_fails_and_a_motion_through_the_centre_is_caught() {
        // A bow tie, crossing itself at the centre: one loop turns backwards.
        let p = vec![
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(1.0, -1.0, 0.0),
            Vec3::new(-1.0, 1.0, 0.0),
            Vec3::new(-1.0, -1.0, 0.0),
            Vec3::new(0.0, 0.0, 0.0),
        ];
        let eight = [[0, 1], [1, 2], [2, 3], [3, 0]];
        assert!(!run(&p, &eight));
        // A square turned half round over the step, every corner moving straight to the
        // opposite one: the same square at both ends, collapsed onto its centre halfway.
        let start = ring(4, 1.0);
        let end: Vec<Vec3> = start.iter().map(|p| Vec3::new(-p.x, -p.y, p.z)).collect();
        let square = [[0, 1], [1, 2], [2, 3], [3, 0]];
        let test = |start: &[Vec3], end: &[Vec3]| {
            let motion = Motion { start, end };
            star_shaped(square.iter().copied(), [4; 3], &Vec3::z(), &motion)
        };
        assert!(test(&start, &start));
        assert!(test(&end, &end));
        assert!(!test(&start, &end));
    }
}
