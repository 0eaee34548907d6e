//! Attachments hold a particle on one side of a plane: a sheet attached above a plane
//! rests on it, carrying its weight as the penalty's depth predicts, and a sheet attached
//! below one falls past it exactly as a free sheet does.

use cloth_core::{Attachment, Fabric, GridBuilder, Simulation, SimulationBuilder, SolverSettings, Vec3};

/// A 20 cm square sheet, flat at z = 0, each particle attached to the plane through its
/// start with `direction`; falls under gravity for `steps` hundredths of a second.
fn fallen(direction: Option<Vec3>, steps: usize) -> Simulation {
    let mesh = GridBuilder::new(11, 11).size(0.2, 0.2).build().unwrap();
    let attachments = match direction {
        Some(direction) => mesh
            .positions()
            .iter()
            .enumerate()
            .map(|(particle, &point)| Attachment {
                particle,
                point,
                direction,
            })
            .collect(),
        None => Vec::new(),
    };
    let mut sim = SimulationBuilder::new(mesh, Fabric::cotton_like().with_drag(0.0))
        .settings(SolverSettings {
            time_step: 0.01,
            ..SolverSettings::default()
        })
        .attachments(attachments)
        .build()
        .unwrap();
    for _ in 0..steps {
        sim.step().unwrap();
    }
    sim
}

#[test]
fn a_sheet_attached_above_a_plane_rests_on_it_with_its_weight_on_the_penalty() {
    let sim = fallen(Some(Vec3::z()), 100);
    let x = sim.positions();
    let v = sim.velocities();
    assert!(v.iter().all(|v| v.norm() < 1e-4), "still moving");
    // At rest the attachments carry the weight: sum k d_i = M g, so the mean depth below
    // the plane is M g / (N k), with k ten times the fabric's membrane stiffness.
    let mass: f64 = sim.masses().iter().sum();
    let k = 10.0 * sim.fabrics()[0].membrane_stiffness();
    let expected = mass * 9.81 / (x.len() as f64 * k);
    let depth = -x.iter().map(|p| p.z).sum::<f64>() / x.len() as f64;
    assert!(
        (depth - expected).abs() < 0.02 * expected,
        "mean depth {depth} m, expected {expected} m"
    );
    assert!(x.iter().all(|p| p.z < 0.0), "a particle is not held at all");
}

#[test]
fn a_sheet_attached_below_a_plane_falls_as_a_free_one() {
    let held = fallen(Some(-Vec3::z()), 20);
    let free = fallen(None, 20);
    // Moving down the side it is free to move to, nothing acts on it.
    assert_eq!(held.positions(), free.positions());
    assert!(held.positions()[0].z < -0.15, "{}", held.positions()[0].z);
}
