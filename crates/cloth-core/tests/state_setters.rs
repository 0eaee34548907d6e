//! Replacing the state between steps: the positions a caller (Python, a restart) sets are
//! the ones the next step starts from.

use cloth_core::{math::Vec3, Fabric, GridBuilder, ParamError, Pin, SimulationBuilder, SolverSettings};

fn sheet(pins: &[usize]) -> cloth_core::Simulation {
    let mesh = GridBuilder::new(8, 6)
        .size(0.2, 0.15)
        .axes(Vec3::x(), -Vec3::z())
        .build()
        .unwrap();
    SimulationBuilder::new(mesh, Fabric::cotton_like())
        .settings(SolverSettings {
            parallel: false,
            ..SolverSettings::default()
        })
        .pins(pins.iter().map(|&i| Pin::fixed(i)))
        .build()
        .unwrap()
}

#[test]
fn a_moved_free_sheet_falls_as_it_would_have_a_metre_away() {
    let mut a = sheet(&[]);
    let mut b = sheet(&[]);
    for _ in 0..3 {
        a.step().unwrap();
        b.step().unwrap();
    }
    let offset = Vec3::new(1.0, -0.5, 2.0);
    let moved: Vec<Vec3> = b.positions().iter().map(|x| x + offset).collect();
    b.set_positions(&moved).unwrap();
    for _ in 0..5 {
        a.step().unwrap();
        b.step().unwrap();
    }
    let worst = a
        .positions()
        .iter()
        .zip(b.positions())
        .map(|(xa, xb)| (xb - xa - offset).norm())
        .fold(0.0, f64::max);
    // Round-off of coordinates near 2 m, not a difference of motion.
    assert!(worst < 1e-9, "moved sheet differs by {worst} m");
    // A sheet that was not moved would have moved by centimetres here.
    assert!((a.positions()[0] - sheet(&[]).positions()[0]).norm() > 1e-3);
}

#[test]
fn a_pinned_particle_moved_away_goes_back_to_its_pin() {
    let mut sim = sheet(&[0]);
    let pin = sim.positions()[0];
    let mut x = sim.positions().to_vec();
    x[0] += Vec3::new(0.0, 0.0, 0.05);
    sim.set_positions(&x).unwrap();
    assert_eq!(sim.positions()[0], x[0]);
    sim.step().unwrap();
    assert_eq!(sim.positions()[0], pin);
}

#[test]
fn wrong_lengths_and_non_finite_positions_are_refused_and_change_nothing() {
    let mut sim = sheet(&[]);
    let before = sim.positions().to_vec();
    let short = &before[..before.len() - 1];
    assert!(matches!(
        sim.set_positions(short),
        Err(ParamError::OutOfRange {
            name: "positions",
            ..
        })
    ));
    let mut bad = before.clone();
    bad[7].y = f64::NAN;
    let err = sim.set_positions(&bad).unwrap_err().to_string();
    assert!(err.contains("positions") && err.contains("finite"), "{err}");
    assert_eq!(sim.positions(), &before[..]);
}
