//! Even spacing along polylines: rings around a section, ring heights up the body, ring
//! steps over a cap. Even spacing by length (not by curve parameter) keeps the triangles
//! near the same size where a parameter would bunch them up, e.g. at a superellipse's sides.

/// `n + 1` points at equal lengths along the polyline, both ends included (`n >= 1`,
/// at least two points, not all equal).
pub(crate) fn equal_steps<const D: usize>(points: &[[f64; D]], n: usize) -> Vec<[f64; D]> {
    let lengths = cumulative(points);
    let total = lengths[lengths.len() - 1];
    let mut out = Vec::with_capacity(n + 1);
    let mut segment = 0;
    for i in 0..=n {
        let target = total * i as f64 / n as f64;
        while segment + 2 < lengths.len() && lengths[segment + 1] < target {
            segment += 1;
        }
        let (l0, l1) = (lengths[segment], lengths[segment + 1]);
        let t = if l1 > l0 {
            ((target - l0) / (l1 - l0)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (p, q) = (points[segment], points[segment + 1]);
        out.push(std::array::from_fn(|d| p[d] + t * (q[d] - p[d])));
    }
    // The ends exactly, not up to rounding: neighbouring pieces share them.
    out[0] = points[0];
    out[n] = points[points.len() - 1];
    out
}

/// Length of the polyline from its start to each point.
pub(crate) fn cumulative<const D: usize>(points: &[[f64; D]]) -> Vec<f64> {
    let mut lengths = Vec::with_capacity(points.len());
    let mut total = 0.0;
    lengths.push(0.0);
    for w in points.windows(2) {
        total += (0..D).map(|d| (w[1][d] - w[0][d]).powi(2)).sum::<f64>().sqrt();
        lengths.push(total);
    }
    lengths
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_are_equal_and_ends_kept() {
        let line = [[0.0, 0.0], [1.0, 0.0], [1.0, 3.0]];
        let steps = equal_steps(&line, 4);
        assert_eq!(
            steps,
            vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [1.0, 2.0], [1.0, 3.0]]
        );
    }
}
