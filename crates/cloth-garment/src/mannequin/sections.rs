//! Horizontal cross-sections of the torso: smooth convex ovals with a separate front and
//! back, sampled into rings whose polygon perimeter is what a tape measure would read.

use super::arclength::equal_steps;

/// Samples per half oval before resampling by arc length: fine enough that the chords of
/// the resampled ring lie within a micrometre of the curve.
const DENSE: usize = 2048;

/// A cross-section: a superellipse `|x/a|^p + |(y - c)/b|^q = 1` whose `b` and `q` differ in
/// front (-y) and at the back (+y). Both halves meet at the widest points `(+-a, c)` with
/// vertical tangents, so the oval is smooth; with exponents >= 1 it is convex, so a ring
/// never folds and a cap can fan to its centre.
///
/// Exponents near 2 give ellipses; larger side exponents square the sides off (a broad,
/// flat back or chest), a larger front exponent fills the front out across the bust.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Section {
    pub half_width: f64,
    /// Distance from the centre to the front, towards -y.
    pub front: f64,
    /// Distance from the centre to the back, towards +y.
    pub back: f64,
    /// y of the widest points: sections sit further back at the seat and the neck.
    pub centre_y: f64,
    pub side_exponent: f64,
    pub front_exponent: f64,
    pub back_exponent: f64,
}

/// Number of interpolated parameters of a [`Section`].
pub(crate) const PARAMETERS: usize = 7;

impl Section {
    pub fn to_array(self) -> [f64; PARAMETERS] {
        [
            self.half_width,
            self.front,
            self.back,
            self.centre_y,
            self.side_exponent,
            self.front_exponent,
            self.back_exponent,
        ]
    }

    pub fn from_array(p: [f64; PARAMETERS]) -> Self {
        Self {
            half_width: p[0],
            front: p[1],
            back: p[2],
            centre_y: p[3],
            side_exponent: p[4],
            front_exponent: p[5],
            back_exponent: p[6],
        }
    }

    /// The section scaled about the body's centre line; the ring scales with it, because
    /// resampling by relative arc length does not depend on size.
    pub fn scaled(self, k: f64) -> Self {
        Self {
            half_width: k * self.half_width,
            front: k * self.front,
            back: k * self.back,
            centre_y: k * self.centre_y,
            ..self
        }
    }

    /// The section made deeper or shallower (front and back together), width kept.
    pub fn deepened(self, k: f64) -> Self {
        Self {
            front: k * self.front,
            back: k * self.back,
            ..self
        }
    }

    pub fn depth(&self) -> f64 {
        self.front + self.back
    }

    /// y of the front-most and back-most points.
    pub fn front_y(&self) -> f64 {
        self.centre_y - self.front
    }
    pub fn back_y(&self) -> f64 {
        self.centre_y + self.back
    }

    /// `segments` points (a multiple of 4), counter-clockwise seen from above, starting at
    /// the +x side: index 0 and `segments / 2` are the sides, `segments / 4` the centre
    /// back and `3 segments / 4` the centre front. Each half is spaced evenly by arc length
    /// on its own, so the ring is mirror-symmetric in x even when front and back differ,
    /// and a given index sits at the same place around the body on every ring (no twist
    /// between rings).
    pub fn ring(&self, segments: usize) -> Vec<[f64; 2]> {
        let half = segments / 2;
        let back = self.half_curve(1.0, self.back, self.back_exponent);
        let front = self.half_curve(-1.0, self.front, self.front_exponent);
        let mut ring = Vec::with_capacity(segments);
        for curve in [back, front] {
            let mut points = equal_steps(&curve, half);
            points.pop(); // the next half starts there
            ring.extend(points);
        }
        ring
    }

    /// The back (`side = 1`) or front (`side = -1`) half, from one widest point to the
    /// other, counter-clockwise.
    fn half_curve(&self, side: f64, extent: f64, exponent: f64) -> Vec<[f64; 2]> {
        (0..=DENSE)
            .map(|i| {
                let theta = std::f64::consts::PI * i as f64 / DENSE as f64;
                let (s, c) = theta.sin_cos();
                let x = self.half_width * signed_power(c, 2.0 / self.side_exponent);
                let y = self.centre_y + side * extent * s.abs().powf(2.0 / exponent);
                [side * x, y]
            })
            .collect()
    }
}

fn signed_power(v: f64, e: f64) -> f64 {
    v.signum() * v.abs().powf(e)
}

/// Perimeter of a closed polygon.
pub(crate) fn perimeter(ring: &[[f64; 2]]) -> f64 {
    ring.iter()
        .zip(ring.iter().cycle().skip(1))
        .map(|(p, q)| (q[0] - p[0]).hypot(q[1] - p[1]))
        .sum()
}

/// The section scaled so its `segments`-gon has exactly `girth` as perimeter: the girth a
/// tape would read around the meshed body, not around the ideal curve.
pub(crate) fn with_girth(shape: Section, girth: f64, segments: usize) -> Section {
    shape.scaled(girth / perimeter(&shape.ring(segments)))
}

/// The section made deeper or shallower, its width kept, so its `segments`-gon has `girth`
/// as perimeter. The perimeter grows monotonically with depth, from twice the width (a
/// flat section) upward, so bisection finds it; a girth under twice the width cannot be
/// reached and gives the flattest section tried.
pub(crate) fn with_girth_at_width(shape: Section, girth: f64, segments: usize) -> Section {
    let girth_of = |k: f64| perimeter(&shape.deepened(k).ring(segments));
    let (mut lo, mut hi) = (1e-3, 1.0);
    while girth_of(hi) < girth {
        hi *= 2.0;
    }
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if girth_of(mid) < girth {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    shape.deepened(0.5 * (lo + hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ellipse(a: f64, b: f64) -> Section {
        Section {
            half_width: a,
            front: b,
            back: b,
            centre_y: 0.0,
            side_exponent: 2.0,
            front_exponent: 2.0,
            back_exponent: 2.0,
        }
    }

    #[test]
    fn circle_ring_is_a_regular_polygon() {
        let ring = ellipse(1.0, 1.0).ring(64);
        assert_eq!(ring.len(), 64);
        let expected = 64.0 * 2.0 * (std::f64::consts::PI / 64.0).sin();
        assert!((perimeter(&ring) - expected).abs() < 1e-5, "{}", perimeter(&ring));
        for (k, p) in ring.iter().enumerate() {
            let angle = std::f64::consts::TAU * k as f64 / 64.0;
            assert!((p[0] - angle.cos()).abs() < 1e-5 && (p[1] - angle.sin()).abs() < 1e-5);
        }
    }

    #[test]
    fn girth_fits_exactly_and_ring_is_mirror_symmetric() {
        let shape = Section {
            front: 0.7,
            back: 0.4,
            centre_y: 0.1,
            side_exponent: 3.0,
            front_exponent: 2.4,
            ..ellipse(1.0, 1.0)
        };
        let fitted = with_girth(shape, 0.9, 64);
        let ring = fitted.ring(64);
        assert!((perimeter(&ring) - 0.9).abs() < 1e-12);
        // Mirroring across x = 0 maps index k to n/2 - k, modulo n, on both halves.
        for (k, p) in ring.iter().enumerate() {
            let q = ring[(32 + 64 - k) % 64];
            assert!(
                (p[0] + q[0]).abs() < 1e-12 && (p[1] - q[1]).abs() < 1e-12,
                "{k}: {p:?} {q:?}"
            );
        }
        let deep = with_girth_at_width(shape, 5.0, 64);
        assert_eq!(deep.half_width, shape.half_width);
        assert!((perimeter(&deep.ring(64)) - 5.0).abs() < 1e-9);
    }
}
