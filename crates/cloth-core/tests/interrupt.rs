//! Stopping a run from outside, inside a step: the state kept is a whole step's.

use cloth_core::{
    math::Vec3, Fabric, GridBuilder, Interrupt, Pin, RestCriteria, SimError, Simulation, SimulationBuilder,
    SolverSettings, StopReason,
};
use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// A sheet hanging from a corner: it swings for as long as one cares to step it.
fn hanging_sheet() -> Simulation {
    let mesh = GridBuilder::new(30, 30)
        .size(0.5, 0.5)
        .axes(Vec3::x(), -Vec3::z())
        .build()
        .unwrap();
    SimulationBuilder::new(mesh, Fabric::cotton_like())
        .settings(SolverSettings {
            parallel: false,
            ..SolverSettings::default()
        })
        .pin(Pin::fixed(0))
        .build()
        .unwrap()
}

#[test]
fn a_raised_flag_fails_the_step_and_keeps_the_state() {
    let mut sim = hanging_sheet();
    sim.step().unwrap();
    let flag = Arc::new(AtomicBool::new(true));
    sim.set_interrupt(Interrupt::new(flag.clone()));
    let before = sim.positions().to_vec();
    match sim.step() {
        Err(SimError::Interrupted {
            step: 2,
            last_good: 1,
        }) => {}
        other => panic!("{other:?}"),
    }
    assert_eq!(sim.step_count(), 1);
    assert_eq!(sim.positions(), &before[..]);
    flag.store(false, Ordering::Relaxed);
    sim.step().unwrap();
    assert_eq!(sim.step_count(), 2);
}

#[test]
fn a_passed_deadline_stops_a_run_to_rest_before_its_first_step() {
    let mut sim = hanging_sheet();
    sim.set_interrupt(Interrupt::default().with_deadline(Instant::now()));
    let out = sim
        .run_to_rest_with(&RestCriteria::default(), |_, _| ControlFlow::Continue(()))
        .unwrap();
    assert_eq!(
        (out.reason, out.steps, sim.step_count()),
        (StopReason::Stopped, 0, 0)
    );
}

#[test]
fn a_flag_raised_during_a_run_leaves_the_last_whole_step() {
    let mut sim = hanging_sheet();
    let flag = Arc::new(AtomicBool::new(false));
    sim.set_interrupt(Interrupt::new(flag.clone()));
    let raiser = {
        let flag = flag.clone();
        std::thread::spawn(move || {
            std::thread::sleep(Duration::from_millis(100));
            flag.store(true, Ordering::Relaxed);
        })
    };
    let criteria = RestCriteria {
        // Never at rest: only the flag ends it.
        tolerance: 1e-300,
        max_steps: u64::MAX,
        ..RestCriteria::default()
    };
    let out = sim
        .run_to_rest_with(&criteria, |_, _| ControlFlow::Continue(()))
        .unwrap();
    raiser.join().unwrap();
    assert_eq!(out.reason, StopReason::Stopped);
    assert!(
        out.steps > 0 && out.steps == sim.step_count(),
        "{} {}",
        out.steps,
        sim.step_count()
    );
    // The same run stepped that many times uninterrupted is where it stopped.
    let mut again = hanging_sheet();
    for _ in 0..out.steps {
        again.step().unwrap();
    }
    assert_eq!(again.positions(), sim.positions());
}
