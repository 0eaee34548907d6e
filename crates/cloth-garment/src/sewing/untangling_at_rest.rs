//! A garment that comes to rest through itself is smoothed apart where it crosses and
//! draped on, again while that leaves it crossing less; if it still crosses, it is draped
//! again from where it was sewn, loose where it crosses.
//!
//! Smoothed apart (see `smoothing_apart`), the kinks the drape's pull cannot shorten come
//! out, and the drape goes on from there with its collision holding apart what no longer
//! crosses. What the smoothing leaves (godets twisted through their neighbours along a
//! seam, rand_1_015's 85 crossings to 24) the drape on may slide further through (38 at
//! rest): fewer than before, and a kink again, which a second smoothing took out (0 left
//! in 28 rounds, clean at rest 70 steps on).
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
use cloth_core::{math::Vec3, RestOutcome, StopReason};

/// The most times a garment at rest through itself is smoothed apart and draped on. Each
/// drape on kept crosses less than the rest before it; the smoothing then finds fewer
/// kinks, and a drape on costs tens of steps where the loose drape after it costs hundreds.
pub const SMOOTHINGS: usize = 3;

/// What was done with a garment at rest through itself.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct UntanglingAtRest {
    /// Edge-triangle crossings of the cloth where the first drape rested.
    pub before: usize,
    /// Smoothed apart there and draped on, in order: again after each drape on that was
    /// kept and still crossed, up to [`SMOOTHINGS`] times.
    pub smoothed: Vec<SmoothedOn>,
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

/// A garment at rest through itself, as [`smooth_and_drape_on`] works on it.
pub(super) trait AtRest {
    type Error;
    /// Its cloth smoothed apart where it crosses (see `smoothing_apart`): what that did,
    /// and the positions it leaves, not yet set.
    fn smoothed(&self) -> (Smoothing, Vec<Vec3>);
    /// Set at `x`, still, and draped on: how that ended (`Err` loses nothing: the caller
    /// goes back) and where it ended crossed.
    fn drape_on(&mut self, x: &[Vec3]) -> (Result<RestOutcome, Self::Error>, Crossed);
    /// Its positions and velocities, to go back to.
    fn state(&self) -> (Vec<Vec3>, Vec<Vec3>);
    fn set_state(&mut self, state: &(Vec<Vec3>, Vec<Vec3>)) -> Result<(), Self::Error>;
}

/// What [`smooth_and_drape_on`] did: each smoothing and its drape on, the crossings where
/// the garment is left, and how the last drape on kept ended.
pub(super) struct SmoothedApart {
    pub smoothed: Vec<SmoothedOn>,
    pub crossed: Crossed,
    pub last: Option<RestOutcome>,
}

impl SmoothedApart {
    /// The steps of the drapes on that were kept.
    pub fn steps(&self) -> u64 {
        self.smoothed
            .iter()
            .filter_map(|s| s.draped_on)
            .filter(|d| d.kept)
            .map(|d| d.steps)
            .sum()
    }
}

/// Smooths `garment`, at rest crossed as `crossed`, apart and drapes it on, again while
/// each drape on is kept and still crosses, at most [`SMOOTHINGS`] times; stops when a
/// smoothing leaves no fewer crossings than the rest it started from (nothing draped on),
/// or a drape on is not kept (the garment then goes back to the last rest kept).
pub(super) fn smooth_and_drape_on<A: AtRest>(
    garment: &mut A,
    crossed: Crossed,
) -> Result<SmoothedApart, A::Error> {
    let mut done = SmoothedApart {
        smoothed: Vec::new(),
        crossed,
        last: None,
    };
    let mut kept = garment.state();
    while done.crossed.cloth > 0 && done.smoothed.len() < SMOOTHINGS {
        let (smoothing, x) = garment.smoothed();
        if smoothing.left >= done.crossed.cloth {
            done.smoothed.push(SmoothedOn {
                smoothing,
                draped_on: None,
            });
            break;
        }
        let (on, after) = garment.drape_on(&x);
        let report = on
            .as_ref()
            .ok()
            .map(|on| DrapedAgain::new(done.crossed, after, on));
        done.smoothed.push(SmoothedOn {
            smoothing,
            draped_on: report,
        });
        match (on, report) {
            (Ok(on), Some(report)) if report.kept => {
                done.last = Some(on);
                done.crossed = after;
                kept = garment.state();
            }
            _ => {
                garment.set_state(&kept)?;
                break;
            }
        }
    }
    Ok(done)
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

    /// A garment whose smoothings and drapes on end as scripted: smoothing `k` leaves
    /// `left[k]` crossings; drape on `k` ends crossed as `after[k]`, at rest or not. Its
    /// state is a marker of which rest it is at (0 the first, `k + 1` after drape on `k`).
    struct Scripted {
        left: Vec<usize>,
        after: Vec<(Crossed, StopReason)>,
        smoothings: usize,
        drapes: usize,
        at: f64,
    }

    impl Scripted {
        fn new(left: &[usize], after: &[(usize, usize, StopReason)]) -> Self {
            Self {
                left: left.to_vec(),
                after: after.iter().map(|&(c, b, r)| (crossed(c, b), r)).collect(),
                smoothings: 0,
                drapes: 0,
                at: 0.0,
            }
        }
    }

    impl AtRest for Scripted {
        type Error = ();

        fn smoothed(&self) -> (Smoothing, Vec<Vec3>) {
            let k = self.smoothings.min(self.left.len() - 1);
            let smoothing = Smoothing {
                left: self.left[k],
                ..Smoothing::default()
            };
            (smoothing, vec![Vec3::repeat(-1.0)])
        }

        fn drape_on(&mut self, x: &[Vec3]) -> (Result<RestOutcome, ()>, Crossed) {
            assert_eq!(x, [Vec3::repeat(-1.0)], "draped on from the smoothed positions");
            let (after, reason) = self.after[self.drapes];
            self.smoothings += 1;
            self.drapes += 1;
            self.at = self.drapes as f64;
            (Ok(ended(reason)), after)
        }

        fn state(&self) -> (Vec<Vec3>, Vec<Vec3>) {
            (vec![Vec3::repeat(self.at)], Vec::new())
        }

        fn set_state(&mut self, state: &(Vec<Vec3>, Vec<Vec3>)) -> Result<(), ()> {
            self.at = state.0[0].x;
            Ok(())
        }
    }

    #[test]
    fn smoothed_and_draped_on_again_while_each_drape_on_is_kept_and_still_crosses() {
        let at_rest = StopReason::AtRest;
        // rand_1_015's case: 85 crossings, 24 left by the smoothing, 38 at rest after the
        // drape on (kept: fewer than 85); smoothed again from there, 5 left, 0 at rest.
        let mut garment = Scripted::new(&[24, 5], &[(38, 0, at_rest), (0, 0, at_rest)]);
        let done = smooth_and_drape_on(&mut garment, crossed(85, 0)).unwrap();
        assert_eq!(done.smoothed.len(), 2);
        assert_eq!(done.crossed, crossed(0, 0));
        assert_eq!(done.steps(), 240);
        assert_eq!(garment.at, 2.0, "left where the second drape on rested");
        assert!(done.smoothed.iter().all(|s| s.draped_on.is_some_and(|d| d.kept)));
        // No more than SMOOTHINGS times, each kept.
        let left = [50, 40, 30, 20, 10];
        let after: Vec<_> = [60, 50, 40, 30, 20].iter().map(|&c| (c, 0, at_rest)).collect();
        let mut garment = Scripted::new(&left, &after);
        let done = smooth_and_drape_on(&mut garment, crossed(70, 0)).unwrap();
        assert_eq!(done.smoothed.len(), SMOOTHINGS);
        assert_eq!(done.crossed.cloth, [60, 50, 40][SMOOTHINGS - 1]);
        assert_eq!(garment.at, SMOOTHINGS as f64);
    }

    #[test]
    fn a_drape_on_not_kept_goes_back_to_the_last_rest_kept_and_ends_the_smoothing() {
        let at_rest = StopReason::AtRest;
        // The second drape on rests through itself more than the first kept (20 to 30):
        // back to where the first rested, no third smoothing.
        let mut garment = Scripted::new(
            &[10, 5, 1],
            &[(20, 0, at_rest), (30, 0, at_rest), (0, 0, at_rest)],
        );
        let done = smooth_and_drape_on(&mut garment, crossed(40, 0)).unwrap();
        assert_eq!(done.smoothed.len(), 2);
        assert_eq!(done.crossed, crossed(20, 0));
        assert_eq!(done.steps(), 120, "the steps of the drape kept only");
        assert_eq!(garment.at, 1.0);
        assert!(!done.smoothed[1].draped_on.unwrap().kept);
        // Through the body more, or stopped before rest: back to the first rest.
        for (after, reason) in [((0, 2), at_rest), ((0, 0), StopReason::Stopped)] {
            let mut garment = Scripted::new(&[0], &[(after.0, after.1, reason)]);
            let done = smooth_and_drape_on(&mut garment, crossed(75, 0)).unwrap();
            assert_eq!(
                (done.smoothed.len(), done.crossed, done.last),
                (1, crossed(75, 0), None)
            );
            assert_eq!(garment.at, 0.0);
        }
    }

    #[test]
    fn a_smoothing_that_leaves_no_fewer_crossings_is_not_draped_on() {
        let mut garment = Scripted::new(&[12], &[]);
        let done = smooth_and_drape_on(&mut garment, crossed(12, 0)).unwrap();
        assert_eq!(done.smoothed.len(), 1);
        assert_eq!(done.smoothed[0].draped_on, None);
        assert_eq!(
            (done.crossed, done.steps(), garment.drapes),
            (crossed(12, 0), 0, 0)
        );
        // Clear at rest: nothing to smooth.
        let done = smooth_and_drape_on(&mut garment, crossed(0, 0)).unwrap();
        assert!(done.smoothed.is_empty());
    }
}
