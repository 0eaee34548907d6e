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

#[test]
fn a_y_up_body_turned_by_the_scene_meets_garmentcodes_patterns() {
    // GarmentCode's body and a design made for it: with up_axis = "y" the body stands in
    // our z-up world facing -y, as the importer puts GarmentCode's panels, so the
    // waistband's panels lie 5 to 17 cm off the waist, all round it. Read as z-up,
    // the body lies on the floor and the band hangs in the air a metre above it.
    let assets = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/garmentcode");
    let scene = |up: &str| {
        let text = format!(
            "[cloth.garment]\npattern = \"patterns/rand_1_001.json\"\nedge_length = 0.03\n\
             [fabric]\npreset = \"cotton_poplin\"\n[[bodies]]\nfile = \"bodies/mean_all.obj\"\n{up}"
        );
        let prepared = SceneFile::from_toml_str(&text, "band.toml")
            .unwrap()
            .prepare("band.toml", &assets)
            .unwrap();
        let cloth::scene_file::PreparedCloth::Garment { garment, .. } = &prepared.cloth else {
            panic!("a garment")
        };
        let distances: Vec<f64> = garment
            .mesh
            .positions()
            .iter()
            .map(|p| prepared.bodies.signed_distance(0.0, p).unwrap().0)
            .collect();
        let (near, far) = distances
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(lo, hi), &d| (lo.min(d), hi.max(d)));
        (near, far, prepared.warnings.len())
    };
    let (near, far, warnings) = scene("up_axis = \"y\"");
    assert!(near > 0.0 && far < 0.2, "{near} to {far} m from the body");
    assert_eq!(warnings, 0);
    let (near, _, _) = scene("");
    assert!(near > 0.5, "z-up: {near} m");
}
