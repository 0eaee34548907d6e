//! Attachments hold a particle on one side of a plane: a sheet attached above a plane
//! rests on it, carrying its weight as the penalty's depth predicts, and a sheet attached
//! below one falls past it exactly as a free sheet does; attachments replaced during the
//! run hold from the next step as if given at the start.

use cloth_core::{
    math::Vec3, Attachment, Fabric, GridBuilder, Simulation, SimulationBuilder, SolverSettings,
};

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

#[test]
fn attachments_replaced_during_a_run_hold_as_if_given_from_the_start() {
    // Held above the plane for a second, then let go: from rest it falls as a free sheet
    // falls from rest, but for the solver's tolerance (its first guess is the last step's).
    let mut held = fallen(Some(Vec3::z()), 100);
    assert!(held
        .set_attachments(vec![Attachment {
            particle: held.positions().len(),
            point: Vec3::zeros(),
            direction: Vec3::z(),
        }])
        .is_err());
    assert!(held
        .set_attachments(vec![Attachment {
            particle: 0,
            point: Vec3::zeros(),
            direction: Vec3::new(0.0, 0.0, 2.0),
        }])
        .is_err());
    let start = held.positions().to_vec();
    held.set_attachments(Vec::new()).unwrap();
    let mut free = fallen(None, 0);
    free.set_positions(&start).unwrap();
    free.set_velocities(held.velocities()).unwrap();
    for _ in 0..20 {
        held.step().unwrap();
        free.step().unwrap();
    }
    let apart = held
        .positions()
        .iter()
        .zip(free.positions())
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    assert!(apart < 1e-6, "{apart} m from the free sheet");
    assert!(held.positions()[0].z < -0.15, "{}", held.positions()[0].z);
    // And held again by a plane through where it is now, it comes to rest on that plane.
    let level = held.positions().iter().map(|p| p.z).fold(f64::INFINITY, f64::min);
    let plane: Vec<Attachment> = (0..start.len())
        .map(|particle| Attachment {
            particle,
            point: Vec3::new(0.0, 0.0, level),
            direction: Vec3::z(),
        })
        .collect();
    held.set_attachments(plane).unwrap();
    for _ in 0..100 {
        held.step().unwrap();
    }
    assert!(held.velocities().iter().all(|v| v.norm() < 1e-4), "still moving");
    assert!(held.positions().iter().all(|p| p.z > level - 0.01 && p.z < level));
}
