//! A garment that comes to rest through itself is smoothed apart where it crosses and
//! draped on; if it still crosses, it is draped again from where it was sewn, loose where
//! it crosses.
//!
//! Smoothed apart (see `smoothing_apart`), the kinks the drape's pull cannot shorten come
//! out, and the drape goes on from there with its collision holding apart what no longer
//! crosses.
//!
//! Through the drape the cloth's collision holds what crosses as it is (a collision that
//! starts crossed keeps it so) while the pull out of itself works on it, and each step
//! undid what the pull had moved: GarmentCode's rand_1_034 and rand_1_099 came to rest
//! with 2 and 4 crossings where a collar meets the shoulder. Draped with the two pieces of
//! each crossing loose round it while the pull goes on (see `Simulation::set_loose_pull`),
//! both came apart. Loose cloth can also slide further through itself as the garment
//! settles (rand_1_091's godet: 8 crossings to 35), and at rest, pulled again loose, the
//! collars did not come apart (the cloth round them no longer moving); so the garment is
//! draped again from where it was sewn, loose, and the drape that crosses less is kept.

use super::smoothing_apart::Smoothing;
use cloth_core::{RestOutcome, StopReason};

/// What was done with a garment at rest through itself.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct UntanglingAtRest {
    /// Edge-triangle crossings of the cloth where the first drape rested.
    pub before: usize,
    /// Smoothed apart there and draped on.
    pub smoothed: SmoothedOn,
    /// Draped again from where it was sewn, loose, if it still crossed.
    pub loose: Option<DrapedAgain>,
}

/// The cloth smoothed apart where it rested through itself, and draped on from there.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SmoothedOn {
    #[serde(flatten)]
    pub smoothing: Smoothing,
    /// Draped on from there, if the smoothing left fewer crossings: where it ended.
    pub draped_on: Option<DrapedAgain>,
}

/// How a drape ended through itself and the bodies: edge-triangle pairs of the cloth, and
/// crossings of the bodies by its edges.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub struct Crossed {
    pub cloth: usize,
    pub body: usize,
}

/// A drape after the first: its crossings where it ended (of itself, and of the bodies),
/// its steps, and whether it was kept: at rest, through itself less than the drape kept
/// before it and through the bodies no more (smoothed apart and draped on, rand_1_009's
/// flounces rested through themselves less, 34 to 75, but 2 edges through a shin).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct DrapedAgain {
    pub after: usize,
    pub body_after: usize,
    pub steps: u64,
    pub kept: bool,
}

impl DrapedAgain {
    /// A drape ended as `outcome`, crossed as `after`, after one kept crossed as `best`.
    pub(super) fn new(best: Crossed, after: Crossed, outcome: &RestOutcome) -> Self {
        Self {
            after: after.cloth,
            body_after: after.body,
            steps: outcome.steps,
            kept: outcome.reason == StopReason::AtRest && after.cloth < best.cloth && after.body <= best.body,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use cloth_core::StepStats;

    fn ended(reason: StopReason) -> RestOutcome {
        RestOutcome {
            reason,
            steps: 120,
            last: StepStats::default(),
        }
    }

    fn crossed(cloth: usize, body: usize) -> Crossed {
        Crossed { cloth, body }
    }

    #[test]
    fn a_drape_after_the_first_is_kept_only_at_rest_and_crossing_less() {
        let at_rest = ended(StopReason::AtRest);
        assert_eq!(
            DrapedAgain::new(crossed(4, 0), crossed(0, 0), &at_rest),
            DrapedAgain {
                after: 0,
                body_after: 0,
                steps: 120,
                kept: true
            }
        );
        assert!(DrapedAgain::new(crossed(8, 3), crossed(7, 3), &at_rest).kept);
        assert!(DrapedAgain::new(crossed(8, 3), crossed(7, 1), &at_rest).kept);
        // Through itself as much or more (rand_1_091: 8, then 35), through the bodies more
        // (rand_1_009: 75 and 0, then 34 and 2), or not at rest (stopped by a time limit,
        // or at the step limit), the one before is kept.
        assert!(!DrapedAgain::new(crossed(8, 0), crossed(8, 0), &at_rest).kept);
        assert!(!DrapedAgain::new(crossed(8, 0), crossed(35, 0), &at_rest).kept);
        assert!(!DrapedAgain::new(crossed(75, 0), crossed(34, 2), &at_rest).kept);
        assert!(!DrapedAgain::new(crossed(4, 0), crossed(0, 0), &ended(StopReason::Stopped)).kept);
        assert!(!DrapedAgain::new(crossed(4, 0), crossed(0, 0), &ended(StopReason::StepLimit)).kept);
    }
}
