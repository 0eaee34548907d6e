//! Monotone cubic interpolation between the key sections.
//!
//! A plain cubic spline overshoots: between a narrow waist and a wide hip it would bulge
//! past the hip, and the girth at the hip would no longer be the largest. The monotone
//! (Fritsch-Carlson) Hermite cubic never leaves the range of its neighbouring knots and
//! has a flat tangent at every local extreme, so the hip, the bust and the shoulder stay
//! the widest places, smoothly.

/// A monotone piecewise cubic through `(x, y)` knots (x strictly increasing).
#[derive(Debug, Clone)]
pub(crate) struct MonotoneCubic {
    xs: Vec<f64>,
    ys: Vec<f64>,
    slopes: Vec<f64>,
}

impl MonotoneCubic {
    /// Knot slopes by the weighted harmonic mean of Fritsch and Butland (1984), as in
    /// MATLAB's `pchip`; the end slopes by the shape-preserving three-point rule.
    ///
    /// The caller guarantees at least two knots with strictly increasing `xs`.
    pub fn new(xs: Vec<f64>, ys: Vec<f64>) -> Self {
        debug_assert!(xs.len() >= 2 && xs.len() == ys.len());
        debug_assert!(xs.windows(2).all(|w| w[1] > w[0]));
        let n = xs.len();
        let h: Vec<f64> = xs.windows(2).map(|w| w[1] - w[0]).collect();
        let delta: Vec<f64> = (0..n - 1).map(|k| (ys[k + 1] - ys[k]) / h[k]).collect();
        let mut slopes = vec![0.0; n];
        if n == 2 {
            slopes = vec![delta[0]; 2];
        } else {
            for k in 1..n - 1 {
                if delta[k - 1] * delta[k] > 0.0 {
                    let w1 = 2.0 * h[k] + h[k - 1];
                    let w2 = h[k] + 2.0 * h[k - 1];
                    slopes[k] = (w1 + w2) / (w1 / delta[k - 1] + w2 / delta[k]);
                }
            }
            slopes[0] = end_slope(h[0], h[1], delta[0], delta[1]);
            slopes[n - 1] = end_slope(h[n - 2], h[n - 3], delta[n - 2], delta[n - 3]);
        }
        Self { xs, ys, slopes }
    }

    /// The value at `x`; outside the knots, the end values (the shape does not extrapolate).
    pub fn at(&self, x: f64) -> f64 {
        let n = self.xs.len();
        if x <= self.xs[0] {
            return self.ys[0];
        }
        if x >= self.xs[n - 1] {
            return self.ys[n - 1];
        }
        let k = self.xs.partition_point(|&knot| knot <= x) - 1;
        let h = self.xs[k + 1] - self.xs[k];
        let t = (x - self.xs[k]) / h;
        let (t2, t3) = (t * t, t * t * t);
        let h00 = 2.0 * t3 - 3.0 * t2 + 1.0;
        let h10 = t3 - 2.0 * t2 + t;
        let h01 = -2.0 * t3 + 3.0 * t2;
        let h11 = t3 - t2;
        h00 * self.ys[k] + h10 * h * self.slopes[k] + h01 * self.ys[k + 1] + h11 * h * self.slopes[k + 1]
    }
}

/// One-sided three-point slope, clipped so the end interval stays monotone.
fn end_slope(h0: f64, h1: f64, d0: f64, d1: f64) -> f64 {
    let slope = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
    if slope * d0 <= 0.0 {
        0.0
    } else if d0 * d1 < 0.0 && slope.abs() > 3.0 * d0.abs() {
        3.0 * d0
    } else {
        slope
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn passes_through_knots_and_stays_within_neighbours() {
        let xs = vec![0.0, 1.0, 1.5, 3.0, 4.0];
        let ys = vec![2.0, 1.0, 3.0, 3.2, 0.5];
        let spline = MonotoneCubic::new(xs.clone(), ys.clone());
        for (x, y) in xs.iter().zip(&ys) {
            assert!((spline.at(*x) - y).abs() < 1e-12);
        }
        for k in 0..4 {
            let (lo, hi) = (ys[k].min(ys[k + 1]), ys[k].max(ys[k + 1]));
            for i in 0..=100 {
                let x = xs[k] + (xs[k + 1] - xs[k]) * i as f64 / 100.0;
                let y = spline.at(x);
                assert!(y >= lo - 1e-12 && y <= hi + 1e-12, "overshoot at {x}: {y}");
            }
        }
    }
}
