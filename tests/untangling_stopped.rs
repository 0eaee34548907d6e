//! A garment at rest through itself is smoothed apart and draped on; a caller that stops
//! that drape on (a time limit, Ctrl-C, an observer) gets the run reported as stopped,
//! with the rest kept before it, not as finished.

mod common;

use cloth::scene_file::{RunObserver, RunOutcome, SceneFile};
use cloth::{Simulation, StepStats};
use std::ops::ControlFlow;

/// The test tube (assets/patterns/tube.toml) with its front panel tilted through the
/// back one: sewn, it rests crossing itself, and is smoothed apart and draped on.
fn crossed_tube() -> (SceneFile, cloth::scene_file::Prepared, tempfile::TempDir) {
    let dir = tempfile::tempdir().unwrap();
    let tube =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/patterns/tube.toml")).unwrap();
    let front = "placement = { rotation = [90, 0, 0], translation = [0, -1.5, 50] }";
    assert!(tube.contains(front));
    let tilted = tube.replacen(
        front,
        "placement = { rotation = [60, 0, 0], translation = [0, 0, 50] }",
        1,
    );
    std::fs::write(dir.path().join("crossed.toml"), tilted).unwrap();
    let text = "[cloth.garment]\npattern = \"crossed.toml\"\nedge_length = 0.02\n\
                pins = [{ panel = \"back\", edge = \"top\" }]\n[fabric]\npreset = \"cotton_poplin\"\n";
    let scene = SceneFile::from_toml_str(text, "scene.toml").unwrap();
    let prepared = scene.prepare("scene.toml", dir.path()).unwrap();
    (scene, prepared, dir)
}

/// Stops the run after `at` draping steps (never, for `u64::MAX`).
struct StopDraping {
    at: u64,
    steps: u64,
}

impl RunObserver for StopDraping {
    fn step(&mut self, stage: &'static str, _: &Simulation, _: &StepStats) -> ControlFlow<()> {
        if stage != "draping" {
            return ControlFlow::Continue(());
        }
        self.steps += 1;
        if self.steps >= self.at {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    }
}

#[test]
fn a_drape_on_stopped_by_the_caller_is_reported_stopped() {
    common::on_threads(1, || {
        let (scene, prepared, _dir) = crossed_tube();
        let mut whole = StopDraping {
            at: u64::MAX,
            steps: 0,
        };
        let done = prepared.run(&scene, None, &mut whole).unwrap();
        let untangled = done
            .report
            .untangling_at_rest
            .clone()
            .expect("rests through itself");
        let on = untangled.smoothed[0]
            .draped_on
            .expect("smoothed apart and draped on");
        assert!(on.kept && on.steps > 10, "{untangled:?}");
        assert_eq!(done.report.outcome, RunOutcome::Finished);
        // Stopped half way through the drape on: the first drape's rest, not finished.
        let first = whole.steps - on.steps;
        let (scene, prepared, _dir) = crossed_tube();
        let mut observer = StopDraping {
            at: first + on.steps / 2,
            steps: 0,
        };
        let stopped = prepared.run(&scene, None, &mut observer).unwrap();
        let untangling = stopped
            .report
            .untangling_at_rest
            .expect("stopped while untangling");
        assert!(!untangling.smoothed[0].draped_on.expect("draped on").kept);
        assert!(
            matches!(
                stopped.report.outcome,
                RunOutcome::Interrupted { stage: "draping", .. }
            ),
            "{:?}",
            stopped.report.outcome
        );
        assert_eq!(stopped.report.stages.last().unwrap().ended, "interrupted");
    });
}
