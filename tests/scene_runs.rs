//! Scene files run through the library: an observer that stops a garment's run mid-sewing
//! gets the state reached, and the report says where it stopped.

use cloth::scene_file::{RunObserver, RunOutcome, SceneFile};
use cloth::{Simulation, StepStats};
use std::ops::ControlFlow;
use std::path::Path;

/// Stops the run after `at` steps of `stage`; counts the stages begun.
struct StopAt {
    stage: &'static str,
    at: u64,
    begun: Vec<(&'static str, u64)>,
}

impl RunObserver for StopAt {
    fn stage(&mut self, stage: &'static str, max_steps: u64) {
        self.begun.push((stage, max_steps));
    }

    fn step(&mut self, stage: &'static str, _: &Simulation, stats: &StepStats) -> ControlFlow<()> {
        if stage == self.stage && stats.step == self.at {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    }
}

#[test]
fn a_garment_stopped_while_sewing_keeps_its_unwelded_state() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/skirt.toml");
    let (mut scene, dir) = SceneFile::from_path(&path).unwrap();
    if let cloth::scene_file::ClothSpec::Garment { edge_length, .. } = &mut scene.cloth {
        *edge_length = 0.03; // quick
    }
    let prepared = scene.prepare("skirt.toml", &dir).unwrap();
    let unwelded = match &prepared.cloth {
        cloth::scene_file::PreparedCloth::Garment { garment, .. } => garment.mesh.vertex_count(),
        _ => panic!("the skirt is a garment"),
    };
    let mut observer = StopAt {
        stage: "sewing",
        at: 3,
        begun: Vec::new(),
    };
    let result = prepared.run(&scene, None, &mut observer).unwrap();
    assert_eq!(observer.begun, [("sewing", scene.sewing.max_steps)]);
    assert_eq!(
        result.report.outcome,
        RunOutcome::Interrupted {
            stage: "sewing",
            step: 3
        }
    );
    assert!(!result.finished());
    assert_eq!(result.positions.len(), unwelded);
    assert_eq!(result.report.stages.len(), 1);
    assert_eq!(result.report.stages[0].ended, "interrupted");
    // Three steps do not close the seams: the gap reported is the one reached.
    let gap = result.report.largest_seam_gap.unwrap();
    assert!(gap > scene.sewing.gap_tolerance, "{gap}");
}
