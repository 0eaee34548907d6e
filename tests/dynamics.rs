//! Integrators: stability, divergence, the same rest state, determinism, pins.

mod common;

use cloth::{
    math::Vec3, DivergenceReason, Fabric, GridBuilder, Integrator, Pin, RestCriteria, SimError,
    SimulationBuilder, SolverSettings, StopReason,
};
use common::{max_distance, two_corner_sheet};
use std::ops::ControlFlow;

const SIZE: f64 = 0.5;
const N: usize = 15;

/// Soft enough that explicit Euler is stable at a step a test can afford; Rayleigh
/// damping near sqrt(2)/omega_max keeps every mode of forward Euler stable for h < beta.
fn fabric() -> Fabric {
    Fabric::isotropic_linear(0.15, 100.0, 5.0, 1e-5)
        .with_damping(7e-4)
        .with_drag(0.05)
}

fn settings(integrator: Integrator, h: f64) -> SolverSettings {
    SolverSettings {
        integrator,
        time_step: h,
        ..Default::default()
    }
}

fn rest(h: f64, max_seconds: f64) -> RestCriteria {
    // At rest: no particle faster than 1 mm/s for 20 steps.
    RestCriteria {
        max_time_step: None,
        tolerance: 1e-3 * h,
        consecutive_steps: 20,
        max_steps: (max_seconds / h) as u64,
        moving_fraction: 0.0,
    }
}

fn implicit_rest(h: f64) -> Vec<Vec3> {
    let mut sim = two_corner_sheet(N, SIZE, fabric(), settings(Integrator::ImplicitEuler, h))
        .build()
        .unwrap();
    let out = sim.run_to_rest(&rest(h, 30.0)).unwrap();
    assert_eq!(out.reason, StopReason::AtRest, "implicit at h = {h}: {out:?}");
    assert!(out.last.cg_converged);
    sim.positions().to_vec()
}

#[test]
fn implicit_is_stable_at_large_steps_and_explicit_diverges_there() {
    let a = implicit_rest(1.0 / 30.0);
    let b = implicit_rest(1.0 / 60.0);
    assert!(
        max_distance(&a, &b) < 0.01 * SIZE,
        "rest shapes at h = 1/30 and 1/60 differ by {}",
        max_distance(&a, &b)
    );

    let mut sim = two_corner_sheet(N, SIZE, fabric(), settings(Integrator::ExplicitEuler, 1.0 / 60.0))
        .build()
        .unwrap();
    let before = sim.positions().to_vec();
    let err = sim.run_to_rest(&rest(1.0 / 60.0, 10.0)).unwrap_err();
    match &err {
        SimError::Diverged {
            step,
            last_good,
            reason,
        } => {
            assert_eq!(*last_good + 1, *step);
            assert!(
                matches!(
                    reason,
                    DivergenceReason::SpeedLimit { .. } | DivergenceReason::NonFinite { .. }
                ),
                "{reason:?}"
            );
            assert!(err.to_string().contains(&format!("step {step}")));
            // Nothing already computed is lost: the state is that of the last good step.
            assert_eq!(sim.step_count(), *last_good);
            assert!(sim.positions().iter().all(|p| p.iter().all(|c| c.is_finite())));
        }
        other => panic!("expected divergence, got {other:?}"),
    }
    assert_ne!(
        sim.positions(),
        &before[..],
        "it should have run some good steps first"
    );
}

#[test]
fn explicit_euler_at_a_stable_step_reaches_the_implicit_rest_shape() {
    let implicit = implicit_rest(1.0 / 60.0);
    for integrator in [Integrator::ExplicitEuler, Integrator::SymplecticEuler] {
        let h = 2.5e-4;
        let mut sim = two_corner_sheet(N, SIZE, fabric(), settings(integrator, h))
            .build()
            .unwrap();
        let out = sim.run_to_rest(&rest(h, 30.0)).unwrap();
        assert_eq!(out.reason, StopReason::AtRest, "{integrator:?}: {out:?}");
        let d = max_distance(sim.positions(), &implicit);
        println!(
            "{integrator:?}: {} steps, rest shape {d:.2e} m from implicit",
            out.steps
        );
        assert!(d < 0.01 * SIZE, "{integrator:?} rest shape {d} m from implicit's");
    }
}

#[test]
fn results_do_not_depend_on_the_thread_count() {
    let run = |threads: usize| {
        common::on_threads(threads, || {
            // A horizontal sheet falling from two corners: large motion, folds.
            let mesh = GridBuilder::new(40, 40).size(1.0, 1.0).build().unwrap();
            let g = mesh.grid().unwrap();
            let fabric = Fabric::cotton_like().with_damping(1e-3);
            let mut sim = SimulationBuilder::new(mesh, fabric)
                .pin(Pin::fixed(g.index(0, 39)))
                .pin(Pin::fixed(g.index(39, 39)))
                .build()
                .unwrap();
            for _ in 0..40 {
                sim.step().unwrap();
            }
            sim.positions().to_vec()
        })
    };
    let (one, two) = (run(1), run(2));
    let scale = one.iter().map(|p| p.norm()).fold(0.0, f64::max);
    let d = max_distance(&one, &two);
    assert!(d <= 1e-9 * scale, "1 and 2 threads differ by {d}");
}

#[test]
fn pins_follow_their_paths_exactly() {
    let mesh = GridBuilder::new(8, 8).size(0.2, 0.2).build().unwrap();
    let start = mesh.positions()[0];
    let path = move |t: f64| start + Vec3::new(0.05 * (3.0 * t).sin(), 0.0, 0.1 * t);
    for integrator in [
        Integrator::ImplicitEuler,
        Integrator::ExplicitEuler,
        Integrator::SymplecticEuler,
    ] {
        let h = if integrator == Integrator::ImplicitEuler {
            1.0 / 60.0
        } else {
            2e-4
        };
        let mut sim = SimulationBuilder::new(
            mesh.clone(),
            Fabric::isotropic_linear(0.15, 50.0, 2.0, 1e-6).with_damping(1e-3),
        )
        .settings(settings(integrator, h))
        .pin(Pin::path(0, path))
        .pin(Pin::fixed(7))
        .build()
        .unwrap();
        let fixed = sim.positions()[7];
        for _ in 0..100 {
            sim.step().unwrap();
            assert_eq!(sim.positions()[0], path(sim.time()), "{integrator:?}");
            assert_eq!(sim.positions()[7], fixed, "{integrator:?}");
        }
    }
}

#[test]
fn a_run_says_why_it_stopped() {
    let mut sim = two_corner_sheet(N, SIZE, fabric(), SolverSettings::default())
        .build()
        .unwrap();
    let out = sim
        .run_to_rest(&RestCriteria {
            max_time_step: None,
            tolerance: 1e-9,
            consecutive_steps: 5,
            max_steps: 7,
            moving_fraction: 0.0,
        })
        .unwrap();
    assert_eq!(
        (out.reason, out.steps, sim.step_count()),
        (StopReason::StepLimit, 7, 7)
    );
    assert!(out.last.cg_iterations > 0 && out.last.kinetic_energy > 0.0 && out.last.solve_seconds > 0.0);
    // Each step's statistics are reported.
    let mut seen = Vec::new();
    sim.run_to_rest_with(
        &RestCriteria {
            max_time_step: None,
            tolerance: 1e-9,
            consecutive_steps: 5,
            max_steps: 3,
            moving_fraction: 0.0,
        },
        |_, s| {
            seen.push(s.step);
            ControlFlow::Continue(())
        },
    )
    .unwrap();
    assert_eq!(seen, vec![8, 9, 10]);
    // The observer stops a run after the step it breaks on.
    let out = sim
        .run_to_rest_with(
            &RestCriteria {
                max_time_step: None,
                tolerance: 1e-9,
                consecutive_steps: 5,
                max_steps: 100,
                moving_fraction: 0.0,
            },
            |_, s| {
                if s.step == 12 {
                    ControlFlow::Break(())
                } else {
                    ControlFlow::Continue(())
                }
            },
        )
        .unwrap();
    assert_eq!(
        (out.reason, out.steps, sim.step_count()),
        (StopReason::Stopped, 2, 12)
    );
}

#[test]
fn a_bad_pin_path_is_an_error_that_keeps_the_state() {
    let mesh = GridBuilder::new(4, 4).build().unwrap();
    let mut sim = SimulationBuilder::new(mesh, fabric())
        .pin(Pin::path(0, |t| {
            if t > 0.05 {
                Vec3::new(f64::NAN, 0.0, 0.0)
            } else {
                Vec3::zeros()
            }
        }))
        .build()
        .unwrap();
    let err = loop {
        match sim.step() {
            Ok(_) => continue,
            Err(e) => break e,
        }
    };
    assert!(matches!(err, SimError::InvalidPin { particle: 0, .. }), "{err}");
    assert!(err.to_string().contains("particle 0"));
    assert!(sim.positions().iter().all(|p| p.iter().all(|c| c.is_finite())));
}
