//! Pieces of cloth that start through each other (GarmentCode's hood through its bodice)
//! are exempt from each other until they have come apart, then collide as any cloth.

use cloth_core::{ClothMesh, Fabric, GridBuilder, Pin, Simulation, SimulationBuilder, SolverSettings, Vec3};

/// A 20 cm sheet lying at z = 0 held by its corners, and a 20 x 10 cm strip standing
/// through its middle (its lower edge `below` under the sheet), as one mesh of two pieces.
fn crossed(below: f64) -> (ClothMesh, usize) {
    let sheet = GridBuilder::new(21, 21)
        .size(0.2, 0.2)
        .origin(Vec3::new(-0.1, -0.1, 0.0))
        .build()
        .unwrap();
    let strip = GridBuilder::new(21, 11)
        .size(0.2, 0.1)
        .origin(Vec3::new(-0.1, 0.005, -below))
        .axes(Vec3::x(), Vec3::z())
        .build()
        .unwrap();
    let n = sheet.vertex_count();
    let mut positions = sheet.positions().to_vec();
    positions.extend(strip.positions());
    let mut uv = sheet.uv().to_vec();
    uv.extend(strip.uv());
    let mut triangles = sheet.triangles().to_vec();
    triangles.extend(strip.triangles().iter().map(|t| t.map(|i| i + n)));
    (ClothMesh::new(positions, uv, triangles).unwrap(), n)
}

fn simulation(mesh: ClothMesh, strip_velocity: Vec3, first_strip: usize) -> Simulation {
    let n = mesh.vertex_count();
    let v = (0..n)
        .map(|i| {
            if i >= first_strip {
                strip_velocity
            } else {
                Vec3::zeros()
            }
        })
        .collect();
    SimulationBuilder::new(mesh, Fabric::cotton_like().with_damping(0.01))
        .settings(SolverSettings {
            gravity: Vec3::zeros(),
            time_step: 1.0 / 100.0,
            ..SolverSettings::default()
        })
        .pins([0, 20, 420, 440].map(Pin::fixed))
        .velocities(v)
        .build()
        .unwrap()
}

#[test]
fn pieces_through_each_other_at_the_start_come_apart_then_collide() {
    let (mesh, first_strip) = crossed(0.035);
    // The strip rises at 1 m/s: out of the sheet after 3.5 cm.
    let mut sim = simulation(mesh, Vec3::new(0.0, 0.0, 1.0), first_strip);
    let tangles = sim.tangles().to_vec();
    assert_eq!(tangles.len(), 1, "{tangles:?}");
    let t = &tangles[0];
    assert!(t.crossings >= 20, "{} crossings", t.crossings);
    assert!(t.triangles[0] < 800 && t.triangles[1] >= 800, "{:?}", t.triangles);
    assert_eq!(t.released, None);
    assert!(sim.self_intersections().count > 0);
    // Passing out of each other: no impacts between them, nothing thrown.
    let mut released = None;
    for _ in 0..8 {
        let stats = sim.step().unwrap();
        assert_eq!(stats.self_impacts, 0, "step {}", stats.step);
        assert!(stats.max_speed < 1.5, "step {}: {}", stats.step, stats.max_speed);
        released = released.or(sim.tangles()[0].released);
    }
    let at = released.expect("the strip came out of the sheet");
    assert!((3..=6).contains(&at), "released after step {at}");
    assert_eq!(sim.self_intersections().count, 0);
    // Apart, they collide: the strip thrown back down lands on the sheet, not through it.
    let x = sim.positions().to_vec();
    let v: Vec<Vec3> = (0..x.len())
        .map(|i| {
            if i >= first_strip {
                Vec3::new(0.0, 0.0, -1.0)
            } else {
                Vec3::zeros()
            }
        })
        .collect();
    sim.set_velocities(&v).unwrap();
    let mut impacts = 0;
    for _ in 0..15 {
        let stats = sim.step().unwrap();
        impacts += stats.self_impacts + stats.self_contacts;
        assert_eq!(sim.self_intersections().count, 0, "step {}", stats.step);
    }
    assert!(impacts > 0, "the strip never met the sheet");
    // Pressed down, the sheet sags under the strip, which stays on it.
    let lowest = |x: &[Vec3]| x.iter().map(|p| p.z).fold(f64::INFINITY, f64::min);
    let (sheet, strip) = sim.positions().split_at(first_strip);
    assert!(
        lowest(strip) > lowest(sheet),
        "strip down to {}, sheet to {}",
        lowest(strip),
        lowest(sheet)
    );
}

#[test]
fn pieces_apart_at_the_start_are_not_tangled() {
    // The strip's lower edge 1 cm above the sheet.
    let (mesh, first_strip) = crossed(-0.01);
    let sim = simulation(mesh, Vec3::zeros(), first_strip);
    assert!(sim.tangles().is_empty());
}
