//! Distances and intersections of points, segments and triangles: what self-contact's
//! proximity, its continuous test and the intersection counts (of the cloth with itself and
//! with a body) are made of.

use crate::math::Vec3;

/// Barycentric weights of the point of triangle `(a, b, c)` nearest to `p` (non-negative,
/// summing to one), found by the Voronoi region of `p` (vertex, edge or face).
pub fn closest_on_triangle(p: &Vec3, a: &Vec3, b: &Vec3, c: &Vec3) -> [f64; 3] {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(&ap), ac.dot(&ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return [1.0, 0.0, 0.0];
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(&bp), ac.dot(&bp));
    if d3 >= 0.0 && d4 <= d3 {
        return [0.0, 1.0, 0.0];
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let s = d1 / (d1 - d3);
        return [1.0 - s, s, 0.0];
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(&cp), ac.dot(&cp));
    if d6 >= 0.0 && d5 <= d6 {
        return [0.0, 0.0, 1.0];
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let s = d2 / (d2 - d6);
        return [1.0 - s, 0.0, s];
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        let s = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return [0.0, 1.0 - s, s];
    }
    let sum = va + vb + vc;
    if !(sum > 0.0) {
        // A degenerate (needle or point) triangle: its nearest vertex.
        let d = [ap.norm_squared(), bp.norm_squared(), cp.norm_squared()];
        let k = (0..3).min_by(|&i, &j| d[i].total_cmp(&d[j])).unwrap_or(0);
        let mut w = [0.0; 3];
        w[k] = 1.0;
        return w;
    }
    [va / sum, vb / sum, vc / sum]
}

/// Parameters `(s, t)` in `[0, 1]` of the nearest points `p0 + s (p1 - p0)` and
/// `q0 + t (q1 - q0)` of two segments. For parallel segments, one of the nearest pairs.
pub fn closest_on_segments(p0: &Vec3, p1: &Vec3, q0: &Vec3, q1: &Vec3) -> (f64, f64) {
    let (d1, d2, r) = (p1 - p0, q1 - q0, p0 - q0);
    let (a, e, f) = (d1.norm_squared(), d2.norm_squared(), d2.dot(&r));
    let tiny = 1e-300;
    if a <= tiny && e <= tiny {
        return (0.0, 0.0);
    }
    if a <= tiny {
        return (0.0, (f / e).clamp(0.0, 1.0));
    }
    let c = d1.dot(&r);
    if e <= tiny {
        return ((-c / a).clamp(0.0, 1.0), 0.0);
    }
    let b = d1.dot(&d2);
    let denom = a * e - b * b;
    // Parallel (to rounding): any s will do; the one at p0 is as near as any.
    let mut s = if denom > 1e-14 * a * e {
        ((b * f - c * e) / denom).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let mut t = (b * s + f) / e;
    if t < 0.0 {
        t = 0.0;
        s = (-c / a).clamp(0.0, 1.0);
    } else if t > 1.0 {
        t = 1.0;
        s = ((b - c) / a).clamp(0.0, 1.0);
    }
    (s, t)
}

/// Six times the signed volume of the tetrahedron `(a, b, c, d)`: positive when `d` is on
/// the side of `(a, b, c)` its right-handed normal points to.
pub fn orient(a: &Vec3, b: &Vec3, c: &Vec3, d: &Vec3) -> f64 {
    (b - a).cross(&(c - a)).dot(&(d - a))
}

/// Whether the segment `p q` passes through the triangle `t`: its ends strictly on either
/// side of the triangle's plane, and the crossing point inside the triangle or on its
/// boundary. A segment lying in the plane does not cross (a flat sheet is not
/// intersecting itself), nor does one that only touches it with an end.
pub fn segment_crosses_triangle(p: &Vec3, q: &Vec3, t: &[Vec3; 3]) -> bool {
    let (sp, sq) = (orient(&t[0], &t[1], &t[2], p), orient(&t[0], &t[1], &t[2], q));
    if !((sp > 0.0 && sq < 0.0) || (sp < 0.0 && sq > 0.0)) {
        return false;
    }
    // The line through p q passes inside when it turns the same way round every edge.
    let e0 = orient(p, q, &t[0], &t[1]);
    let e1 = orient(p, q, &t[1], &t[2]);
    let e2 = orient(p, q, &t[2], &t[0]);
    (e0 >= 0.0 && e1 >= 0.0 && e2 >= 0.0) || (e0 <= 0.0 && e1 <= 0.0 && e2 <= 0.0)
}

/// Unit normal of triangle `(a, b, c)` (right-handed), or `None` for a degenerate one.
pub fn triangle_normal(a: &Vec3, b: &Vec3, c: &Vec3) -> Option<Vec3> {
    let n = (b - a).cross(&(c - a));
    let len = n.norm();
    (len > 0.0 && len.is_finite()).then(|| n / len)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn brute_triangle(p: &Vec3, a: &Vec3, b: &Vec3, c: &Vec3) -> f64 {
        let mut best = f64::INFINITY;
        let n = 400;
        for i in 0..=n {
            for j in 0..=(n - i) {
                let (u, v) = (i as f64 / n as f64, j as f64 / n as f64);
                let q = a + u * (b - a) + v * (c - a);
                best = best.min((p - q).norm());
            }
        }
        best
    }

    #[test]
    fn nearest_triangle_point_matches_a_dense_search_in_every_region() {
        let (a, b, c) = (
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.1, 0.0),
            Vec3::new(0.3, 0.9, 0.2),
        );
        let points = [
            Vec3::new(0.3, 0.3, 0.5),   // face
            Vec3::new(-0.5, -0.4, 0.1), // vertex a
            Vec3::new(1.6, 0.0, -0.3),  // vertex b
            Vec3::new(0.3, 1.5, 0.4),   // vertex c
            Vec3::new(0.5, -0.5, 0.2),  // edge ab
            Vec3::new(-0.4, 0.5, 0.0),  // edge ac
            Vec3::new(0.9, 0.8, 0.1),   // edge bc
        ];
        for p in points {
            let w = closest_on_triangle(&p, &a, &b, &c);
            assert!(w.iter().all(|&x| x >= 0.0) && (w.iter().sum::<f64>() - 1.0).abs() < 1e-12);
            let q = w[0] * a + w[1] * b + w[2] * c;
            let d = (p - q).norm();
            let reference = brute_triangle(&p, &a, &b, &c);
            // The dense search can only be farther, by at most its spacing.
            assert!(
                d <= reference + 1e-12 && reference - d < 4e-3,
                "{p}: {d} vs {reference}"
            );
        }
    }

    #[test]
    fn nearest_segment_points_match_a_dense_search() {
        let cases = [
            [
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(0.5, -1.0, 0.3),
                Vec3::new(0.5, 1.0, 0.3),
            ],
            [
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(1.5, 0.2, 0.0),
                Vec3::new(2.5, 1.0, 0.0),
            ],
            // Parallel.
            [
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(0.5, 0.2, 0.0),
                Vec3::new(1.5, 0.2, 0.0),
            ],
        ];
        for [p0, p1, q0, q1] in cases {
            let (s, t) = closest_on_segments(&p0, &p1, &q0, &q1);
            let d = (p0 + s * (p1 - p0) - q0 - t * (q1 - q0)).norm();
            let mut reference = f64::INFINITY;
            for i in 0..=500 {
                for j in 0..=500 {
                    let (u, v) = (i as f64 / 500.0, j as f64 / 500.0);
                    reference = reference.min((p0 + u * (p1 - p0) - q0 - v * (q1 - q0)).norm());
                }
            }
            assert!(
                d <= reference + 1e-12 && reference - d < 1e-5,
                "{d} vs {reference}"
            );
        }
    }

    #[test]
    fn segments_cross_triangles_only_through_them() {
        let t = [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ];
        let up = Vec3::new(0.0, 0.0, 1.0);
        let through = Vec3::new(0.2, 0.2, 0.0);
        assert!(segment_crosses_triangle(&(through + up), &(through - up), &t));
        assert!(segment_crosses_triangle(
            &(through - up),
            &(through + 0.1 * up),
            &t
        ));
        let beside = Vec3::new(0.8, 0.8, 0.0);
        assert!(!segment_crosses_triangle(&(beside + up), &(beside - up), &t));
        // Ends on one side, or one end in the plane, or lying in the plane: no crossing.
        assert!(!segment_crosses_triangle(
            &(through + up),
            &(through + 0.5 * up),
            &t
        ));
        assert!(!segment_crosses_triangle(&(through + up), &through, &t));
        assert!(!segment_crosses_triangle(
            &Vec3::new(-0.5, 0.2, 0.0),
            &Vec3::new(0.5, 0.2, 0.0),
            &t
        ));
        // Through an edge counts.
        let edge = Vec3::new(0.5, 0.0, 0.0);
        assert!(segment_crosses_triangle(&(edge + up), &(edge - up), &t));
    }
}
