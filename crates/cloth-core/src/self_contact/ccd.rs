//! The continuous test: does a particle pass through a triangle, or an edge through an
//! edge, while every particle moves in a straight line over the step (Provot 1997;
//! Bridson, Fedkiw & Anderson 2002)? The four points are coplanar at the roots of a cubic
//! in time; at each root, in order, they are checked for touching. A pair that does not
//! cross but ends the step closer than [`MIN_SEPARATION`] of its contact distance, having
//! closed in, is an impact too: layers keep at least that apart at every step's end.

use crate::math::predicates::{closest_on_segments, closest_on_triangle};
use crate::math::Vec3;

/// Fraction of its contact distance at which a pair that passed through is left: inside
/// the distance, so the next step's repulsion takes hold of it rather than the pair falling
/// onto the same impact step after step.
pub const LANDING: f64 = 0.9;
/// Fraction of its contact distance that a pair closing in is kept apart at least.
pub const MIN_SEPARATION: f64 = 0.6;

/// Where and when two primitives meet during a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Impact {
    pub particles: [u32; 4],
    /// As a contact's (see [`crate::energy::repulsion::ContactFrame`]): `sum w x` is the
    /// gap between the two points.
    pub weights: [f64; 4],
    /// Unit normal at the impact, pointing from the second point's side to the first's as
    /// they were at the start of the step.
    pub normal: Vec3,
    /// Fraction of the step at the impact (1 for a pair ending it too close).
    pub time: f64,
    /// The gap along the normal the pair is to have at the step's end, m: never more than
    /// it had at the start.
    pub target: f64,
}

/// The points of a primitive pair at the start and end of the step.
pub(crate) struct Paths {
    pub start: [Vec3; 4],
    pub end: [Vec3; 4],
}

impl Paths {
    fn at(&self, t: f64) -> [Vec3; 4] {
        std::array::from_fn(|k| self.start[k] + t * (self.end[k] - self.start[k]))
    }
}

/// Coefficients `c0 + c1 t + c2 t^2 + c3 t^3` of `((b - a) x (c - a)) . (d - a)` over the
/// step: six times the signed volume of the four points.
fn volume_cubic(p: &Paths, [a, b, c, d]: [usize; 4]) -> [f64; 4] {
    let rel = |k: usize| {
        (
            p.start[k] - p.start[a],
            (p.end[k] - p.start[k]) - (p.end[a] - p.start[a]),
        )
    };
    let ((u0, du), (v0, dv), (w0, dw)) = (rel(b), rel(c), rel(d));
    let (n0, n1, n2) = (u0.cross(&v0), u0.cross(&dv) + du.cross(&v0), du.cross(&dv));
    [
        n0.dot(&w0),
        n0.dot(&dw) + n1.dot(&w0),
        n1.dot(&dw) + n2.dot(&w0),
        n2.dot(&dw),
    ]
}

fn eval(c: &[f64; 4], t: f64) -> f64 {
    ((c[3] * t + c[2]) * t + c[1]) * t + c[0]
}

/// The times in `[0, 1]` where the cubic changes sign, in increasing order (at most 3):
/// the interval is cut at the derivative's roots into monotone pieces, each bisected where
/// its ends differ in sign. A cubic that vanishes identically (points moving within one
/// plane) has none.
fn roots(c: &[f64; 4]) -> ([f64; 3], usize) {
    if c.iter().all(|&k| k == 0.0) {
        return ([0.0; 3], 0);
    }
    let mut cuts = [0.0, 0.0, 0.0, 1.0];
    let mut count = 1;
    // Derivative 3 c3 t^2 + 2 c2 t + c1.
    let (qa, qb, qc) = (3.0 * c[3], 2.0 * c[2], c[1]);
    let mut critical = [f64::NAN; 2];
    if qa.abs() > 1e-300 {
        let disc = qb * qb - 4.0 * qa * qc;
        if disc > 0.0 {
            let sq = disc.sqrt();
            // The stable pair of quadratic roots.
            let q = -0.5 * (qb + qb.signum() * sq);
            critical = [q / qa, if q != 0.0 { qc / q } else { f64::NAN }];
        }
    } else if qb.abs() > 1e-300 {
        critical[0] = -qc / qb;
    }
    critical.sort_by(f64::total_cmp);
    for t in critical {
        if t > 0.0 && t < 1.0 {
            cuts[count] = t;
            count += 1;
        }
    }
    cuts[count] = 1.0;
    let mut found = ([0.0; 3], 0);
    for k in 0..count {
        let (mut lo, mut hi) = (cuts[k], cuts[k + 1]);
        let (flo, fhi) = (eval(c, lo), eval(c, hi));
        if flo == 0.0 && k == 0 {
            found.0[found.1] = lo;
            found.1 += 1;
            continue;
        }
        if !(flo < 0.0 && fhi >= 0.0 || flo > 0.0 && fhi <= 0.0) {
            continue;
        }
        let rising = fhi > flo;
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if (eval(c, mid) < 0.0) == rising {
                lo = mid;
            } else {
                hi = mid;
            }
            if hi - lo < 1e-13 {
                break;
            }
        }
        if found.1 < 3 {
            found.0[found.1] = hi;
            found.1 += 1;
        }
    }
    found
}

/// Orients `n` to point from the second point to the first as they stood at the start
/// (or, if they started level, against their approach).
fn oriented(n: Vec3, weights: &[f64; 4], p: &Paths) -> Vec3 {
    let start: Vec3 = (0..4).map(|k| weights[k] * p.start[k]).sum();
    let side = n.dot(&start);
    let side = if side != 0.0 {
        side
    } else {
        -n.dot(&(0..4).map(|k| weights[k] * (p.end[k] - p.start[k])).sum::<Vec3>())
    };
    if side < 0.0 {
        -n
    } else {
        n
    }
}

/// The impact of particle 0 of `p` on the triangle of particles 1, 2, 3: the first time
/// they pass through one plane within `touch` of each other, or else their nearest points
/// at the end if closer than [`MIN_SEPARATION`] of their contact distance and closer than
/// at the start. `distance(weights)` is the pair's contact distance; without it only
/// passing through counts, and the pair is left on its side, however close.
pub(crate) fn particle_triangle(
    particles: [u32; 4],
    p: &Paths,
    touch: f64,
    distance: Option<impl Fn(&[f64; 4]) -> f64>,
) -> Option<Impact> {
    let nearest = |[x, a, b, c]: [Vec3; 4]| {
        let w = closest_on_triangle(&x, &a, &b, &c);
        ([1.0, -w[0], -w[1], -w[2]], x - (w[0] * a + w[1] * b + w[2] * c))
    };
    let cubic = volume_cubic(p, [1, 2, 3, 0]);
    let (times, count) = roots(&cubic);
    for &t in &times[..count] {
        let at = p.at(t);
        let (weights, gap) = nearest(at);
        if gap.norm() > touch {
            continue;
        }
        let [_, a, b, c] = at;
        let face = (b - a).cross(&(c - a));
        let n = if face.norm() > 0.0 {
            face.normalize()
        } else if gap.norm() > 0.0 {
            gap.normalize()
        } else {
            continue;
        };
        return Some(impact(particles, weights, n, t, landing(&distance, &weights), p));
    }
    let (weights, gap) = nearest(p.end);
    closing(particles, weights, gap, p, distance.as_ref()?)
}

/// The impact of the edge of particles 0, 1 of `p` on the edge of particles 2, 3, as
/// [`particle_triangle`]'s; ending close counts only between the edges' insides (near an
/// end it is a particle's, which the particle-triangle test has).
pub(crate) fn edge_edge(
    particles: [u32; 4],
    p: &Paths,
    touch: f64,
    distance: Option<impl Fn(&[f64; 4]) -> f64>,
) -> Option<Impact> {
    let nearest = |[p0, p1, q0, q1]: [Vec3; 4]| {
        let (s, u) = closest_on_segments(&p0, &p1, &q0, &q1);
        (
            [1.0 - s, s, u - 1.0, -u],
            (p0 + s * (p1 - p0)) - (q0 + u * (q1 - q0)),
        )
    };
    let cubic = volume_cubic(p, [0, 1, 2, 3]);
    let (times, count) = roots(&cubic);
    for &t in &times[..count] {
        let at = p.at(t);
        let (weights, gap) = nearest(at);
        if gap.norm() > touch {
            continue;
        }
        let [p0, p1, q0, q1] = at;
        let cross = (p1 - p0).cross(&(q1 - q0));
        let n = if cross.norm() > 1e-12 * (p1 - p0).norm() * (q1 - q0).norm() {
            cross.normalize()
        } else {
            // Parallel edges: across them, along their gap at the start.
            let start: Vec3 = (0..4).map(|k| weights[k] * p.start[k]).sum();
            if start.norm() > 0.0 {
                start.normalize()
            } else {
                continue;
            }
        };
        return Some(impact(particles, weights, n, t, landing(&distance, &weights), p));
    }
    let (weights, gap) = nearest(p.end);
    if !(weights[1] > 0.0 && weights[1] < 1.0 && weights[3] < 0.0 && weights[3] > -1.0) {
        return None;
    }
    closing(particles, weights, gap, p, distance.as_ref()?)
}

/// The gap a pair that passed through is left at: [`LANDING`] of its contact distance, or
/// (not knowing it) nothing but its own side.
fn landing(distance: &Option<impl Fn(&[f64; 4]) -> f64>, weights: &[f64; 4]) -> f64 {
    distance.as_ref().map_or(0.0, |d| LANDING * d(weights))
}

/// An impact at `time` along `n` (oriented), to be left at `gap` along it at most.
fn impact(particles: [u32; 4], weights: [f64; 4], n: Vec3, time: f64, gap: f64, p: &Paths) -> Impact {
    let normal = oriented(n, &weights, p);
    let start = normal.dot(&(0..4).map(|k| weights[k] * p.start[k]).sum::<Vec3>());
    Impact {
        particles,
        weights,
        normal,
        time,
        target: gap.min(start.max(0.0)),
    }
}

/// The pair's nearest points at the end, `gap` apart, as an impact if they are closer
/// than [`MIN_SEPARATION`] of their contact distance and closed in over the step.
fn closing(
    particles: [u32; 4],
    weights: [f64; 4],
    gap: Vec3,
    p: &Paths,
    distance: &impl Fn(&[f64; 4]) -> f64,
) -> Option<Impact> {
    let (end, keep) = (gap.norm(), MIN_SEPARATION * distance(&weights));
    let start = (0..4).map(|k| weights[k] * p.start[k]).sum::<Vec3>().norm();
    // Closing in by more than rounding: a pair moved as one (an impact zone) does not.
    if !(end < keep && end < start - 1e-6 * keep) || end == 0.0 {
        return None;
    }
    Some(impact(particles, weights, gap / end, 1.0, keep, p))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn paths(start: [Vec3; 4], motion: [Vec3; 4]) -> Paths {
        Paths {
            start,
            end: std::array::from_fn(|k| start[k] + motion[k]),
        }
    }

    #[test]
    fn cubic_roots_are_found_where_the_sign_changes() {
        // (t - 0.2)(t - 0.5)(t - 0.9)
        let c = [-0.09, 0.73, -1.6, 1.0];
        let (t, n) = roots(&c);
        assert_eq!(n, 3);
        for (got, want) in t.iter().zip([0.2, 0.5, 0.9]) {
            assert!((got - want).abs() < 1e-10, "{t:?}");
        }
        // Touching zero without crossing (double root at 0.5): not an impact.
        let c = [0.25 + 0.01, -1.0, 1.0, 0.0];
        assert_eq!(roots(&c).1, 0);
        assert_eq!(roots(&[0.0; 4]).1, 0);
    }

    #[test]
    fn a_particle_falling_through_a_triangle_is_caught_and_one_passing_beside_is_not() {
        let tri = [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ];
        let fall = Vec3::new(0.0, 0.0, -1.0);
        let p = paths(
            [Vec3::new(0.25, 0.25, 0.2), tri[0], tri[1], tri[2]],
            [fall, Vec3::zeros(), Vec3::zeros(), Vec3::zeros()],
        );
        let hit = particle_triangle([0, 1, 2, 3], &p, 1e-6, Some(|_: &[f64; 4]| 1e-3)).expect("caught");
        assert!((hit.time - 0.2).abs() < 1e-9);
        assert!((hit.normal - Vec3::z()).norm() < 1e-12, "{}", hit.normal);
        assert!((hit.weights[1] + 0.5).abs() < 1e-9);
        let beside = paths(
            [Vec3::new(0.8, 0.8, 0.2), tri[0], tri[1], tri[2]],
            [fall, Vec3::zeros(), Vec3::zeros(), Vec3::zeros()],
        );
        assert!(particle_triangle([0, 1, 2, 3], &beside, 1e-6, Some(|_: &[f64; 4]| 1e-3)).is_none());
        // The triangle rising through the particle, which also moves: caught.
        let up = Vec3::new(0.0, 0.0, 0.5);
        let p = paths(
            [Vec3::new(0.25, 0.25, 0.2), tri[0], tri[1], tri[2]],
            [Vec3::new(0.1, 0.0, 0.0), up, up, up],
        );
        let hit = particle_triangle([0, 1, 2, 3], &p, 1e-6, Some(|_: &[f64; 4]| 1e-3)).expect("caught");
        assert!((hit.time - 0.4).abs() < 1e-9);
    }

    #[test]
    fn crossing_edges_are_caught_and_a_rotating_pair_is_found_at_its_first_crossing() {
        let p = paths(
            [
                Vec3::new(0.0, 0.0, 0.1),
                Vec3::new(1.0, 0.0, 0.1),
                Vec3::new(0.5, -0.5, 0.0),
                Vec3::new(0.5, 0.5, 0.0),
            ],
            [
                Vec3::new(0.0, 0.0, -0.4),
                Vec3::new(0.0, 0.0, -0.4),
                Vec3::zeros(),
                Vec3::zeros(),
            ],
        );
        let hit = edge_edge([0, 1, 2, 3], &p, 1e-6, Some(|_: &[f64; 4]| 1e-3)).expect("caught");
        assert!((hit.time - 0.25).abs() < 1e-9);
        assert!((hit.weights[0] - 0.5).abs() < 1e-9 && (hit.weights[3] + 0.5).abs() < 1e-9);
        assert!(hit.normal.z > 0.99, "{}", hit.normal);
        // Passing above the other edge's end: no impact.
        let miss = paths(
            [
                Vec3::new(0.0, 0.8, 0.1),
                Vec3::new(1.0, 0.8, 0.1),
                Vec3::new(0.5, -0.5, 0.0),
                Vec3::new(0.5, 0.5, 0.0),
            ],
            [
                Vec3::new(0.0, 0.0, -0.4),
                Vec3::new(0.0, 0.0, -0.4),
                Vec3::zeros(),
                Vec3::zeros(),
            ],
        );
        assert!(edge_edge([0, 1, 2, 3], &miss, 1e-6, Some(|_: &[f64; 4]| 1e-3)).is_none());
    }
}
