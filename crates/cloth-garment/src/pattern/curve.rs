//! The shape of an edge between its two end points.

use super::Point2;

/// Polyline segments per unit parameter used to measure a Bezier curve's arc length:
/// the relative length error of a polyline falls as the square of its segment count, so
/// 512 segments are within a part in a million on any curve a pattern draws.
const LENGTH_SEGMENTS: usize = 512;

/// An edge's shape from `start` to `end`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Curve {
    Line,
    /// Quadratic Bezier with one control point.
    Quadratic {
        control: Point2,
    },
    /// Cubic Bezier with two control points.
    Cubic {
        control: [Point2; 2],
    },
    /// Circular arc of `radius` (at least half the chord). `large` picks the longer of the
    /// two arcs through the ends; `ccw` says it turns counter-clockwise from start to end.
    Arc {
        radius: f64,
        large: bool,
        ccw: bool,
    },
}

impl Curve {
    /// The point at parameter `t` in [0, 1] (uniform in angle for arcs).
    pub fn point(&self, a: Point2, b: Point2, t: f64) -> Point2 {
        let s = 1.0 - t;
        match *self {
            Curve::Line => a + (b - a) * t,
            Curve::Quadratic { control } => a * (s * s) + control * (2.0 * s * t) + b * (t * t),
            Curve::Cubic { control: [c, d] } => {
                a * (s * s * s) + c * (3.0 * s * s * t) + d * (3.0 * s * t * t) + b * (t * t * t)
            }
            Curve::Arc { .. } => match self.arc(a, b) {
                Some((centre, r, a0, sweep)) => {
                    let angle = a0 + sweep * t;
                    centre + Point2::new(angle.cos(), angle.sin()) * r
                }
                None => a + (b - a) * t,
            },
        }
    }

    /// Centre, radius, start angle and signed sweep of an arc; `None` for other curves
    /// and for an arc whose radius is under half its chord (see [`Curve::check`]).
    fn arc(&self, a: Point2, b: Point2) -> Option<(Point2, f64, f64, f64)> {
        let Curve::Arc { radius, large, ccw } = *self else {
            return None;
        };
        let chord = b - a;
        let d = chord.norm();
        if !(d > 0.0) || !(radius >= 0.5 * d * (1.0 - 1e-9)) {
            return None;
        }
        let offset = (radius * radius - 0.25 * d * d).max(0.0).sqrt();
        let left = Point2::new(-chord.y, chord.x) / d;
        // Travelling counter-clockwise, the centre is on the left of the chord for the
        // minor arc and on the right for the major one.
        let side = if ccw != large { 1.0 } else { -1.0 };
        let centre = (a + b) * 0.5 + left * (side * offset);
        let angle = |p: Point2| (p.y - centre.y).atan2(p.x - centre.x);
        let (a0, a1) = (angle(a), angle(b));
        let tau = std::f64::consts::TAU;
        let mut sweep = (a1 - a0).rem_euclid(tau);
        if !ccw {
            sweep -= tau;
        }
        Some((centre, radius, a0, sweep))
    }

    /// Why the curve cannot join `a` to `b`, if it cannot.
    pub fn check(&self, a: Point2, b: Point2) -> Result<(), String> {
        let finite = |p: &Point2| p.iter().all(|c| c.is_finite());
        match *self {
            Curve::Line => Ok(()),
            Curve::Quadratic { control } if !finite(&control) => Err("control point is not finite".into()),
            Curve::Cubic { control } if !control.iter().all(finite) => {
                Err("control points are not finite".into())
            }
            Curve::Arc { radius, .. } if !(radius.is_finite() && radius > 0.0) => {
                Err(format!("arc radius {radius} must be positive and finite"))
            }
            Curve::Arc { radius, .. } if self.arc(a, b).is_none() => Err(format!(
                "arc radius {radius} is under half the chord {}",
                0.5 * (b - a).norm()
            )),
            _ => Ok(()),
        }
    }

    /// Arc length from `a` to `b`.
    pub fn length(&self, a: Point2, b: Point2) -> f64 {
        match *self {
            Curve::Line => (b - a).norm(),
            Curve::Arc { .. } => match self.arc(a, b) {
                Some((_, r, _, sweep)) => r * sweep.abs(),
                None => (b - a).norm(),
            },
            _ => *self.cumulative(a, b).last().expect("segments"),
        }
    }

    /// How far the curve's direction turns from `a` to `b`, radians (summed, so an S
    /// counts both bends).
    pub fn turning(&self, a: Point2, b: Point2) -> f64 {
        match *self {
            Curve::Line => 0.0,
            Curve::Arc { .. } => self.arc(a, b).map_or(0.0, |(_, _, _, sweep)| sweep.abs()),
            _ => {
                let p: Vec<Point2> = (0..=LENGTH_SEGMENTS)
                    .map(|k| self.point(a, b, k as f64 / LENGTH_SEGMENTS as f64))
                    .collect();
                p.windows(3)
                    .map(|w| {
                        let (u, v) = (w[1] - w[0], w[2] - w[1]);
                        u.perp(&v).atan2(u.dot(&v)).abs()
                    })
                    .sum()
            }
        }
    }

    /// Cumulative polyline length at `t = k / LENGTH_SEGMENTS`.
    fn cumulative(&self, a: Point2, b: Point2) -> Vec<f64> {
        let mut acc = vec![0.0; LENGTH_SEGMENTS + 1];
        let mut prev = a;
        for k in 1..=LENGTH_SEGMENTS {
            let p = self.point(a, b, k as f64 / LENGTH_SEGMENTS as f64);
            acc[k] = acc[k - 1] + (p - prev).norm();
            prev = p;
        }
        acc
    }

    /// `pieces + 1` points at equal arc-length spacing from `a` to `b`, the ends exact.
    pub fn resample(&self, a: Point2, b: Point2, pieces: usize) -> Vec<Point2> {
        let pieces = pieces.max(1);
        let t_of: Box<dyn Fn(f64) -> f64> = match self {
            Curve::Line | Curve::Arc { .. } => Box::new(|f| f),
            _ => {
                let acc = self.cumulative(a, b);
                let total = acc[LENGTH_SEGMENTS];
                Box::new(move |f: f64| {
                    let target = f * total;
                    let k = acc.partition_point(|&s| s < target).clamp(1, LENGTH_SEGMENTS);
                    let span = acc[k] - acc[k - 1];
                    let within = if span > 0.0 {
                        (target - acc[k - 1]) / span
                    } else {
                        0.0
                    };
                    (k as f64 - 1.0 + within) / LENGTH_SEGMENTS as f64
                })
            }
        };
        let mut points: Vec<Point2> = (0..=pieces)
            .map(|k| self.point(a, b, t_of(k as f64 / pieces as f64)))
            .collect();
        points[0] = a;
        points[pieces] = b;
        points
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn p(x: f64, y: f64) -> Point2 {
        Point2::new(x, y)
    }

    #[test]
    fn arcs_go_the_way_their_flags_say() {
        let (a, b) = (p(1.0, 0.0), p(-1.0, 0.0));
        // A half circle: both arcs are half, ccw passes through +y.
        let ccw = Curve::Arc {
            radius: 1.0,
            large: false,
            ccw: true,
        };
        assert!((ccw.point(a, b, 0.5) - p(0.0, 1.0)).norm() < 1e-12);
        assert!((ccw.length(a, b) - PI).abs() < 1e-12);
        let cw = Curve::Arc {
            radius: 1.0,
            large: false,
            ccw: false,
        };
        assert!((cw.point(a, b, 0.5) - p(0.0, -1.0)).norm() < 1e-12);
        // A quarter circle's minor and major arcs.
        let (a, b) = (p(1.0, 0.0), p(0.0, 1.0));
        let minor = Curve::Arc {
            radius: 1.0,
            large: false,
            ccw: true,
        };
        assert!((minor.length(a, b) - PI / 2.0).abs() < 1e-12);
        let major = Curve::Arc {
            radius: 1.0,
            large: true,
            ccw: true,
        };
        assert!((major.length(a, b) - 3.0 * PI / 2.0).abs() < 1e-12);
        assert!((major.turning(a, b) - 3.0 * PI / 2.0).abs() < 1e-12);
        // Its centre is (1, 1): the major arc bulges away from the origin.
        let h = std::f64::consts::FRAC_1_SQRT_2;
        assert!((major.point(a, b, 0.5) - p(1.0 + h, 1.0 + h)).norm() < 1e-12);
        assert!(Curve::Arc {
            radius: 0.4,
            large: false,
            ccw: true
        }
        .check(p(0.0, 0.0), p(1.0, 0.0))
        .is_err());
    }

    #[test]
    fn bezier_lengths_and_resampling() {
        // A quadratic Bezier degenerate to a line is that line at uneven speed.
        let (a, b) = (p(0.0, 0.0), p(2.0, 0.0));
        let q = Curve::Quadratic { control: p(1.9, 0.0) };
        assert!((q.length(a, b) - 2.0).abs() < 1e-9);
        let pts = q.resample(a, b, 4);
        for (k, pt) in pts.iter().enumerate() {
            assert!((pt.x - 0.5 * k as f64).abs() < 1e-5, "{k}: {pt:?}");
        }
        // A cubic approximating a quarter circle (control distance 0.5523) has length
        // within 0.03% of pi/2.
        let k = 0.552_284_749_8;
        let c = Curve::Cubic {
            control: [p(1.0, k), p(k, 1.0)],
        };
        let len = c.length(p(1.0, 0.0), p(0.0, 1.0));
        assert!((len / (PI / 2.0) - 1.0).abs() < 3e-4, "{len}");
        // The polyline's turning misses half a segment's worth at each end.
        let turn = c.turning(p(1.0, 0.0), p(0.0, 1.0));
        assert!((turn - PI / 2.0).abs() < 2.0 * PI / 2.0 / 512.0, "{turn}");
        let pts = c.resample(p(1.0, 0.0), p(0.0, 1.0), 8);
        let gaps: Vec<f64> = pts.windows(2).map(|w| (w[1] - w[0]).norm()).collect();
        let spread = gaps.iter().cloned().fold(0.0, f64::max) / gaps.iter().cloned().fold(1.0, f64::min);
        assert!(spread < 1.001, "{gaps:?}");
    }
}
