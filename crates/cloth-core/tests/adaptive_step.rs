//! Steps that fail are taken again in shorter substeps: a run on valid input does not end
//! for numerical reasons above the floor of `time_step / 2^max_halvings`.

use cloth_core::{
    math::Vec3, DivergenceReason, Fabric, GridBuilder, Pin, RestCriteria, SimError, Simulation,
    SimulationBuilder, SolverSettings, StopReason,
};
use std::ops::ControlFlow;

/// A 20 x 20 sheet, 0.5 m wide, along `across` and `down` from its first row, held at
/// `pins`, its implicit solves cut at `iterations`.
fn sheet(across: Vec3, down: Vec3, pins: Vec<Pin>, iterations: usize, max_halvings: u32) -> Simulation {
    let mesh = GridBuilder::new(20, 20)
        .size(0.5, 0.5)
        .axes(across, down)
        .build()
        .unwrap();
    let mut settings = SolverSettings {
        time_step: 1.0 / 30.0,
        max_halvings,
        parallel: false,
        ..SolverSettings::default()
    };
    settings.pcg.max_iterations = iterations;
    SimulationBuilder::new(mesh, Fabric::cotton_like())
        .settings(settings)
        .pins(pins)
        .build()
        .unwrap()
}

/// The sheet hanging from two corners.
fn hanging_sheet(iterations: usize, max_halvings: u32) -> Simulation {
    sheet(
        Vec3::x(),
        -Vec3::z(),
        vec![Pin::fixed(0), Pin::fixed(19)],
        iterations,
        max_halvings,
    )
}

#[test]
fn a_solve_that_does_not_converge_is_taken_again_in_substeps() {
    // The whole step's system is too stiff to solve in so few iterations; a shorter
    // step's, nearer the mass matrix, is not.
    let iterations = 12;
    let mut fixed = hanging_sheet(iterations, 0);
    let unconverged = (0..30).filter(|_| !fixed.step().unwrap().cg_converged).count();
    assert!(unconverged > 0);

    let mut adaptive = hanging_sheet(iterations, 6);
    let (mut retries, mut most, mut last) = (0, 0, None);
    for k in 1..=90u64 {
        let stats = adaptive.step().unwrap_or_else(|e| panic!("step {k}: {e}"));
        assert!(stats.cg_converged, "step {k}");
        assert_eq!(stats.step, k);
        retries += stats.retries;
        most = most.max(stats.substeps);
        last = Some(stats);
    }
    assert!(retries > 0 && most > 1, "retries {retries}, most substeps {most}");
    // Whole steps of h, however they were cut.
    assert!((adaptive.time() - 3.0).abs() < 1e-12, "{}", adaptive.time());
    // Swinging slower, the sheet is back to longer substeps.
    let last = last.unwrap();
    assert!(last.substeps < most, "{} of {most}", last.substeps);
}

#[test]
fn below_the_floor_the_step_fails_and_keeps_the_last_whole_step() {
    // Free fall reaches the speed limit whatever the step: every substep fails.
    let mesh = GridBuilder::new(6, 6).size(0.2, 0.2).build().unwrap();
    let mut sim = SimulationBuilder::new(mesh, Fabric::cotton_like())
        .settings(SolverSettings {
            max_speed: 0.5,
            max_halvings: 3,
            parallel: false,
            ..SolverSettings::default()
        })
        .build()
        .unwrap();
    let mut last = None;
    let error = loop {
        let before = (sim.positions().to_vec(), sim.time(), sim.step_count());
        match sim.step() {
            Ok(_) => last = Some(before),
            Err(e) => break (e, before),
        }
        assert!(sim.step_count() < 100, "never reached the limit");
    };
    let (error, before) = error;
    assert!(last.is_some());
    match error {
        SimError::Diverged {
            step,
            last_good,
            reason: DivergenceReason::SpeedLimit { .. },
        } => {
            assert_eq!((step, last_good), (before.2 + 1, before.2));
        }
        other => panic!("{other}"),
    }
    assert_eq!(sim.positions(), &before.0[..]);
    assert_eq!(sim.time(), before.1);
    assert_eq!(sim.step_count(), before.2);
}

/// A sheet shot down through another at 15 m/s: in one step of a sixtieth of a second it
/// would cross the lower sheet's whole depth of field, every particle an impact.
fn shot_through(max_halvings: u32) -> Simulation {
    let sheet = |z: f64| {
        GridBuilder::new(16, 16)
            .size(0.3, 0.3)
            .origin(Vec3::new(0.0, 0.0, z))
            .build()
            .unwrap()
    };
    let mesh = cloth_core::ClothMesh::join(&[sheet(0.0), sheet(0.05)]).unwrap();
    let n = mesh.vertex_count();
    let v = (0..n)
        .map(|i| {
            if i < n / 2 {
                Vec3::zeros()
            } else {
                Vec3::new(0.0, 0.0, -15.0)
            }
        })
        .collect();
    SimulationBuilder::new(mesh, Fabric::cotton_like())
        .settings(SolverSettings {
            time_step: 1.0 / 60.0,
            max_halvings,
            parallel: false,
            ..SolverSettings::default()
        })
        .velocities(v)
        .build()
        .unwrap()
}

#[test]
fn a_step_whose_impacts_go_over_budget_is_taken_in_substeps() {
    let mut whole = shot_through(0);
    let stats = whole.step().unwrap();
    let n = whole.positions().len();
    // At the floor the passes have no budget: they found more than it ...
    assert!(stats.self_impacts > 2 * n, "{} impacts", stats.self_impacts);
    assert_eq!(stats.retries, 0);
    // (its solve converged and nothing diverged: the budget is all that differs)
    assert!(stats.cg_converged && stats.max_speed < 100.0);
    let mut cut = shot_through(6);
    let stats = cut.step().unwrap();
    // ... and above it the step was cut until each substep's were within it.
    assert!(stats.retries > 0 && stats.substeps > 1, "{stats:?}");
    // Neither lets the sheets pass through each other.
    assert_eq!(whole.self_intersections().count, 0);
    assert_eq!(cut.self_intersections().count, 0);
}

/// A 20 x 20 sheet held flat along one edge, let go to swing down and run to rest at
/// 1/30 s (its solves cut at `iterations`), its step growing to `most` if given; the steps
/// taken and, per step, its length and whether it was cut (taken in substeps).
fn settle(iterations: usize, max_halvings: u32, most: Option<f64>) -> (Simulation, u64, Vec<(f64, bool)>) {
    let mut sim = sheet(
        Vec3::x(),
        Vec3::y(),
        (0..20).map(Pin::fixed).collect(),
        iterations,
        max_halvings,
    );
    let criteria = RestCriteria {
        max_time_step: most,
        tolerance: 1e-4 / 30.0,
        consecutive_steps: 10,
        max_steps: 3000,
        moving_fraction: 0.0,
    };
    let mut steps = Vec::new();
    let outcome = sim
        .run_to_rest_with(&criteria, |sim, stats| {
            let h = sim.settings().time_step;
            steps.push((h, stats.smallest_substep < h || !stats.cg_converged));
            ControlFlow::Continue(())
        })
        .unwrap();
    assert_eq!(outcome.reason, StopReason::AtRest, "{outcome:?}");
    (sim, outcome.steps, steps)
}

#[test]
fn a_run_to_rest_may_grow_its_step_and_rests_where_a_fixed_one_does() {
    let (fixed, fixed_steps, _) = settle(1000, 6, None);
    let (grown, grown_steps, lengths) = settle(1000, 6, Some(0.1));
    // The forces balance where they did; implicit Euler's longer steps got there sooner.
    let apart = fixed
        .positions()
        .iter()
        .zip(grown.positions())
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    assert!(apart < 1e-3, "{apart} m apart");
    assert!(
        2 * grown_steps < fixed_steps,
        "{grown_steps} steps grown, {fixed_steps} fixed"
    );
    assert!(
        lengths.iter().any(|&(h, _)| (h - 0.1).abs() < 1e-12),
        "never grew to 0.1 s"
    );
    assert!(lengths.iter().all(|&(h, _)| h <= 0.1 + 1e-12));
    // The solver's own step is given back.
    assert_eq!(grown.settings().time_step, 1.0 / 30.0);
}

#[test]
fn a_step_that_had_to_be_cut_starts_the_growth_again() {
    // Solves cut at a few iterations fail at the longer steps, and those steps are cut.
    let (_, _, steps) = settle(25, 6, Some(0.1));
    let base = 1.0 / 30.0;
    assert!((steps[0].0 - base).abs() < 1e-15);
    let mut cut = 0;
    for pair in steps.windows(2) {
        let ((h, was_cut), (next, _)) = (pair[0], pair[1]);
        let expected = if was_cut { base } else { (1.25 * h).min(0.1) };
        assert!(
            (next - expected).abs() < 1e-12,
            "after {h} (cut: {was_cut}): {next}"
        );
        cut += usize::from(was_cut);
    }
    assert!(cut > 0, "no step was cut");
}
