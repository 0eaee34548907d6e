//! A garment that comes to rest through itself is draped again, loose where it crosses.
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

use cloth_core::{RestOutcome, StopReason};

/// What draping again loose did.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct UntanglingAtRest {
    /// Edge-triangle crossings of the cloth where the first drape rested.
    pub before: usize,
    /// ... and where the second ended.
    pub after: usize,
    /// The second drape's steps.
    pub steps: u64,
    /// Whether the second was kept: at rest, crossing less.
    pub kept: bool,
}

impl UntanglingAtRest {
    /// The second drape, ended as `outcome` crossing `after` times, of a garment that
    /// first rested crossing `before` times.
    pub(super) fn new(before: usize, after: usize, outcome: &RestOutcome) -> Self {
        Self {
            before,
            after,
            steps: outcome.steps,
            kept: outcome.reason == StopReason::AtRest && after < before,
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

    #[test]
    fn the_second_drape_is_kept_only_at_rest_and_crossing_less() {
        let at_rest = ended(StopReason::AtRest);
        assert_eq!(
            UntanglingAtRest::new(4, 0, &at_rest),
            UntanglingAtRest {
                before: 4,
                after: 0,
                steps: 120,
                kept: true
            }
        );
        assert!(UntanglingAtRest::new(8, 7, &at_rest).kept);
        // Crossing as much or more (rand_1_091: 8, then 35), or not at rest (stopped by a
        // time limit, or at the step limit), the first is kept.
        assert!(!UntanglingAtRest::new(8, 8, &at_rest).kept);
        assert!(!UntanglingAtRest::new(8, 35, &at_rest).kept);
        assert!(!UntanglingAtRest::new(4, 0, &ended(StopReason::Stopped)).kept);
        assert!(!UntanglingAtRest::new(4, 0, &ended(StopReason::StepLimit)).kept);
    }
}
