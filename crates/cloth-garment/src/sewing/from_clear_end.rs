//! Seams the body lies across between clear ends as placed, pulled shut from one end.
//!
//! GarmentCode lays a flounce flat beside its leg, wider than the legs are apart, so the
//! sides of its inner seam reach past the other leg (rand_1_035 on `mean_all`: the left
//! flounce's inner seam, 20 cm, its near end between the legs, its middle across the right
//! leg, its far end beyond it). Pulled straight, the middle pairs press on that leg and the
//! far ones close round it, on the wrong side: the flounce stalled 92 mm open at 1,024
//! times the pull. Sewn by hand, such a seam is closed from the end that is already where
//! it belongs: here its pairs are pulled one after another from an end clear of the body
//! that joins it to another seam (the flounce's corner sewn to its cuff), each once its
//! neighbour towards that end has closed, so the cloth already sewn leads the next pair
//! round the body instead of pressing it on it.

use crate::garment::SeamPairs;
use cloth_core::math::Vec3;
use std::ops::Range;

/// The seams pulled shut from their clear ends, and which of their pairs are pulled yet.
#[derive(Debug, Clone)]
pub(super) struct FromClearEnds {
    /// The garment's pairs, seam after seam (as [`crate::garment::Garment::seam_pairs`]),
    /// and each one's weight once pulled.
    pairs: Vec<[usize; 2]>,
    weights: Vec<f64>,
    /// Each seam pulled from its ends: its index, and its pairs' range in `pairs`.
    seams: Vec<(usize, Range<usize>)>,
    pulled: Vec<bool>,
}

impl FromClearEnds {
    /// The seams of a garment with a pair whose sides have the body between (`across`),
    /// both end pairs clear of it, and
    /// an end pair that shares a particle with another seam; each pulled from such ends,
    /// the pairs clear of the body next to them at once. Every other pair is pulled as
    /// before; `weights` are each pair's when pulled.
    pub(super) fn new(all: &[SeamPairs], weights: Vec<f64>, across: impl Fn([usize; 2]) -> bool) -> Self {
        let pairs: Vec<[usize; 2]> = all.iter().flat_map(|s| s.pairs.iter().copied()).collect();
        let mut pulled = vec![true; pairs.len()];
        let mut seams = Vec::new();
        let mut start = 0;
        for (s, seam) in all.iter().enumerate() {
            let range = start..start + seam.pairs.len();
            start = range.end;
            let blocked: Vec<bool> = seam.pairs.iter().map(|&pair| across(pair)).collect();
            if !blocked.iter().any(|&b| b) {
                continue;
            }
            let joined = |k: usize| {
                let [a, b] = seam.pairs[k];
                all.iter()
                    .enumerate()
                    .any(|(t, other)| t != s && other.pairs.iter().flatten().any(|&p| p == a || p == b))
            };
            // Only a seam clear at both ends has the body between clear runs of pairs: pulled
            // straight it closes on both sides of the body, round it. One whose pairs have
            // the body between as far as an end (a sleeve's seam placed across the arm,
            // GarmentCode's rand_1_088) is pulled straight, the cloth sliding off the body;
            // pulled pair by pair from its other end, 088's sleeves drew a cuff open by
            // 15 mm that its ring could not close.
            let n = seam.pairs.len();
            if blocked[0] || blocked[n - 1] {
                continue;
            }
            let (from_start, from_end) = (joined(0), joined(n - 1));
            if !(from_start || from_end) {
                continue;
            }
            // The clear run at each end it is pulled from.
            let mut now = vec![false; n];
            if from_start {
                for k in (0..n).take_while(|&k| !blocked[k]) {
                    now[k] = true;
                }
            }
            if from_end {
                for k in (0..n).rev().take_while(|&k| !blocked[k]) {
                    now[k] = true;
                }
            }
            pulled[range.clone()].copy_from_slice(&now);
            seams.push((s, range));
        }
        Self {
            pairs,
            weights,
            seams,
            pulled,
        }
    }

    /// Whether no seam is pulled from its ends.
    pub(super) fn is_empty(&self) -> bool {
        self.seams.is_empty()
    }

    /// Whether seam `s` of the garment is pulled from its ends.
    pub(super) fn pulls(&self, s: usize) -> bool {
        self.seams.iter().any(|(t, _)| *t == s)
    }

    /// The seams pulled from their ends, by index.
    pub(super) fn seams(&self) -> impl Iterator<Item = usize> + '_ {
        self.seams.iter().map(|(s, _)| *s)
    }

    /// Each pair's weight now: its own once pulled, zero before.
    pub(super) fn weights(&self) -> Vec<f64> {
        self.weights
            .iter()
            .zip(&self.pulled)
            .map(|(&w, &on)| if on { w } else { 0.0 })
            .collect()
    }

    /// Pulls each pair not pulled yet whose neighbour along its seam is pulled and has
    /// closed to `within` at `x` (m); whether any was. A pair that has closed already
    /// passes the pull on at once.
    pub(super) fn advance(&mut self, x: &[Vec3], within: f64) -> bool {
        let closed = |pairs: &[[usize; 2]], k: usize| {
            let [a, b] = pairs[k];
            (x[a] - x[b]).norm() <= within
        };
        let mut any = false;
        for (_, range) in &self.seams {
            for k in range.start + 1..range.end {
                if !self.pulled[k] && self.pulled[k - 1] && closed(&self.pairs, k - 1) {
                    self.pulled[k] = true;
                    any = true;
                }
            }
            for k in (range.start..range.end - 1).rev() {
                if !self.pulled[k] && self.pulled[k + 1] && closed(&self.pairs, k + 1) {
                    self.pulled[k] = true;
                    any = true;
                }
            }
        }
        any
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Particle `k` of a row of them 1 cm apart along x, side `side` of a seam 3 cm wide in y.
    fn at(k: usize, side: usize) -> Vec3 {
        Vec3::new(0.01 * k as f64, 0.03 * side as f64, 0.0)
    }

    /// A seam of ten pairs (particles 0-9 to 10-19) whose pairs 3 to 6 have the body
    /// between; its first particle is on a second seam (0 to 20) when `joined` is, or its
    /// last (9 to 20) when not.
    fn flounce(joined_at_start: bool) -> (Vec<SeamPairs>, Vec<Vec3>) {
        let seam = SeamPairs {
            name: "inner".into(),
            pairs: (0..10).map(|k| [k, 10 + k]).collect(),
        };
        let other = SeamPairs {
            name: "cuff".into(),
            pairs: vec![[if joined_at_start { 0 } else { 9 }, 20]],
        };
        let mut x: Vec<Vec3> = (0..10)
            .map(|k| at(k, 0))
            .chain((0..10).map(|k| at(k, 1)))
            .collect();
        x.push(at(0, 2));
        (vec![seam, other], x)
    }

    /// Pairs 3 to 6 of the flounce's seam (particles 0-9 to 10-19) have the body between.
    fn across([a, b]: [usize; 2]) -> bool {
        b == 10 + a && (3..=6).contains(&a)
    }

    fn close(x: &mut [Vec3], k: usize) {
        x[10 + k] = x[k];
    }

    #[test]
    fn a_seam_the_body_lies_across_is_pulled_from_its_clear_joined_end_a_pair_at_a_time() {
        let (seams, mut x) = flounce(true);
        let mut ends = FromClearEnds::new(&seams, vec![2.0; 11], across);
        assert!(ends.pulls(0) && !ends.pulls(1) && !ends.is_empty());
        assert_eq!(ends.seams().collect::<Vec<_>>(), vec![0]);
        // The clear run at the joined end is pulled; the pairs across the body, and the
        // clear ones beyond them at the free end, are not; the other seam is as before.
        let pulled = |ends: &FromClearEnds| ends.weights().iter().map(|&w| w > 0.0).collect::<Vec<_>>();
        let mut expect = vec![
            true, true, true, false, false, false, false, false, false, false, true,
        ];
        assert_eq!(pulled(&ends), expect);
        assert_eq!(ends.weights()[0], 2.0);
        // Nothing closed: nothing more pulled.
        assert!(!ends.advance(&x, 0.005));
        // The last pulled pair closing passes the pull on to the next, one at a time.
        close(&mut x, 0);
        close(&mut x, 1);
        assert!(!ends.advance(&x, 0.005));
        close(&mut x, 2);
        assert!(ends.advance(&x, 0.005));
        expect[3] = true;
        assert_eq!(pulled(&ends), expect);
        assert!(!ends.advance(&x, 0.005));
        // Pairs already closed pass it on at once, as far as the first open one.
        for k in 3..6 {
            close(&mut x, k);
        }
        assert!(ends.advance(&x, 0.005));
        for e in &mut expect[4..=6] {
            *e = true;
        }
        assert_eq!(pulled(&ends), expect);
        // Within `within` counts as closed.
        x[16] = x[6] + Vec3::new(0.0, 0.004, 0.0);
        assert!(ends.advance(&x, 0.005));
        assert!(pulled(&ends)[7]);
    }

    #[test]
    fn a_seam_is_pulled_from_either_end_that_is_clear_and_joined_and_else_as_before() {
        // Joined at its last pair instead: pulled from there.
        let (seams, _) = flounce(false);
        let ends = FromClearEnds::new(&seams, vec![1.0; 11], across);
        let on: Vec<bool> = ends.weights().iter().map(|&w| w > 0.0).collect();
        assert_eq!(
            on[..10],
            [false, false, false, false, false, false, false, true, true, true]
        );
        // The body between as far as either end, the joined one or the free one: pulled
        // straight, as before.
        for blocked in [3..=9, 0..=6] {
            let ends = FromClearEnds::new(&seams, vec![1.0; 11], |[a, b]| {
                b == 10 + a && blocked.contains(&a)
            });
            assert!(ends.is_empty() && !ends.pulls(0));
            assert_eq!(ends.weights(), vec![1.0; 11]);
        }
        // Clear at both ends but joined at neither: pulled as before.
        let free = vec![seams[0].clone()];
        assert!(FromClearEnds::new(&free, vec![1.0; 10], across).is_empty());
        // Clear of the body: pulled as before.
        let ends = FromClearEnds::new(&seams, vec![1.0; 11], |_| false);
        assert!(ends.is_empty());
        // Both ends clear and joined: pulled from both, and the middle from either side.
        let (mut seams, mut x) = flounce(true);
        seams[1].pairs.push([9, 20]);
        let mut ends = FromClearEnds::new(&seams, vec![1.0; 12], across);
        let on: Vec<bool> = ends.weights().iter().map(|&w| w > 0.0).collect();
        assert_eq!(
            on[..10],
            [true, true, true, false, false, false, false, true, true, true]
        );
        close(&mut x, 7);
        assert!(ends.advance(&x, 0.005));
        assert!(ends.weights()[6] > 0.0 && ends.weights()[3] == 0.0);
    }
}
