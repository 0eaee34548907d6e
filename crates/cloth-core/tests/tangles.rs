//! Pieces of cloth that start through each other (GarmentCode's hood through its bodice)
//! are exempt from each other until they have come apart, then collide as any cloth.

use cloth_core::{
    math::Vec3, ClothMesh, Fabric, GridBuilder, Pin, RestCriteria, Simulation, SimulationBuilder,
    SolverSettings, StopReason,
};

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

/// Per particle of the `n`, `strip` for the strip's (from `first_strip` on), zero for the
/// sheet's.
fn strip_only(n: usize, first_strip: usize, strip: Vec3) -> Vec<Vec3> {
    (0..n)
        .map(|i| if i >= first_strip { strip } else { Vec3::zeros() })
        .collect()
}

fn simulation(mesh: ClothMesh, strip_velocity: Vec3, first_strip: usize) -> Simulation {
    let v = strip_only(mesh.vertex_count(), first_strip, strip_velocity);
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
    let down = strip_only(sim.positions().len(), first_strip, Vec3::new(0.0, 0.0, -1.0));
    sim.set_velocities(&down).unwrap();
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
fn pieces_moved_apart_collide_from_the_next_step_on() {
    // Tangled at the start, then the strip moved out of the sheet by hand (as a garment
    // at rest through itself is smoothed apart): released there, before any step, so the
    // next step cannot take it back through the sheet unseen.
    let (mesh, first_strip) = crossed(0.035);
    let mut sim = simulation(mesh, Vec3::zeros(), first_strip);
    assert_eq!(sim.tangles()[0].released, None);
    let n = sim.positions().len();
    let lift = strip_only(n, first_strip, Vec3::new(0.0, 0.0, 0.04));
    let lifted: Vec<Vec3> = sim.positions().iter().zip(&lift).map(|(p, by)| p + by).collect();
    sim.set_positions(&lifted).unwrap();
    assert_eq!(sim.self_intersections().count, 0);
    assert_eq!(sim.tangles()[0].released, Some(0));
    // Thrown down through the sheet from there, it lands on it.
    sim.set_velocities(&strip_only(n, first_strip, Vec3::new(0.0, 0.0, -1.0)))
        .unwrap();
    for _ in 0..15 {
        let stats = sim.step().unwrap();
        assert_eq!(sim.self_intersections().count, 0, "step {}", stats.step);
    }
}

#[test]
fn pieces_apart_at_the_start_are_not_tangled() {
    // The strip's lower edge 1 cm above the sheet.
    let (mesh, first_strip) = crossed(-0.01);
    let sim = simulation(mesh, Vec3::zeros(), first_strip);
    assert!(sim.tangles().is_empty());
}

/// A 20 x 40 cm sheet folded in half along y = 20 cm, its upper half 1 cm over its lower,
/// with one particle of the upper half `through` below the lower: a tent of the one piece
/// through itself, where no pieces are tangled to be exempt from each other. Index of the
/// tent's apex.
fn folded_with_a_tent_through(through: f64) -> (ClothMesh, usize) {
    let mesh = GridBuilder::new(21, 41).size(0.2, 0.4).build().unwrap();
    let mut x = mesh.positions().to_vec();
    for p in &mut x {
        if p.y > 0.2 + 1e-9 {
            *p = Vec3::new(p.x, 0.4 - p.y, 0.01);
        } else if p.y > 0.2 - 1e-9 {
            p.z = 0.005;
        }
    }
    // Row 30 (y = 30 cm, folded back over y = 10 cm), column 10.
    let apex = 30 * 21 + 10;
    x[apex].z = -through;
    let uv = mesh.uv().to_vec();
    (ClothMesh::new(x, uv, mesh.triangles().to_vec()).unwrap(), apex)
}

/// The sheet of [`folded_with_a_tent_through`], its tent 1.5 cm through, free but for two
/// corners of its lower half, without gravity; and the tent's apex.
fn tent_simulation() -> (Simulation, usize) {
    let (mesh, apex) = folded_with_a_tent_through(0.015);
    let sim = SimulationBuilder::new(mesh, Fabric::cotton_like().with_damping(0.01))
        .settings(SolverSettings {
            gravity: Vec3::zeros(),
            time_step: 1.0 / 100.0,
            ..SolverSettings::default()
        })
        .pins([0, 20].map(Pin::fixed))
        .build()
        .unwrap();
    (sim, apex)
}

/// Steps the tent of [`tent_simulation`] 30 times: out of the sheet within 10, and,
/// colliding again once out, still out at the end, its apex above the lower half.
fn comes_out_and_stays_out(sim: &mut Simulation, apex: usize) {
    let mut out = None;
    for k in 1..=30 {
        sim.step().unwrap();
        if out.is_none() && sim.self_intersections().count == 0 {
            out = Some(k);
        }
    }
    let out = out.expect("the tent is still through the sheet");
    assert!(out <= 10, "out after {out} steps");
    assert_eq!(sim.self_intersections().count, 0);
    let x = sim.positions();
    let under = 10 * 21 + 10;
    assert!(x[apex].z > x[under].z, "apex {} over {}", x[apex].z, x[under].z);
}

#[test]
fn cloth_through_itself_in_one_piece_is_pulled_out_then_collides() {
    let (mut sim, apex) = tent_simulation();
    // One piece: nothing is tangled, and the tent's six edges go through the lower half.
    assert!(sim.tangles().is_empty());
    let start = sim.self_intersections().count;
    assert!(start >= 6, "{start} crossings");
    // The pull takes the tent back up through the lower half.
    comes_out_and_stays_out(&mut sim, apex);
}

#[test]
fn cloth_being_pulled_out_of_itself_is_not_at_rest_until_the_pull_gives_up() {
    // Held through itself, every particle pinned: nothing moves, and the pull out of itself
    // leaves no fewer crossings step after step until it stops for want of progress.
    let rest = RestCriteria::default();
    let run = |through: f64| {
        let (mesh, _) = folded_with_a_tent_through(through);
        let n = mesh.vertex_count();
        let mut sim = SimulationBuilder::new(mesh, Fabric::cotton_like())
            .settings(SolverSettings {
                gravity: Vec3::zeros(),
                time_step: 1.0 / 100.0,
                ..SolverSettings::default()
            })
            .pins((0..n).map(Pin::fixed))
            .build()
            .unwrap();
        let crossings = sim.self_intersections().count;
        let outcome = sim.run_to_rest(&rest).unwrap();
        assert_eq!(outcome.reason, StopReason::AtRest);
        (crossings, outcome.steps)
    };
    // Not through: at rest at the end of the first window.
    let (crossings, window) = run(-0.005);
    assert_eq!(crossings, 0);
    assert!(window < 100, "{window}");
    // Through: the pull goes on for 100 steps without gaining; at the end of the window
    // it stops in, at rest.
    let (crossings, steps) = run(0.015);
    assert!(crossings >= 6);
    assert!(
        steps > 100 && steps <= 100 + window,
        "at rest after {steps} steps, windows of {window}"
    );
}

#[test]
fn pulled_again_loose_the_cloth_comes_out_of_what_the_collision_held() {
    let (mut sim, apex) = tent_simulation();
    let start = sim.self_intersections().count;
    // The pull off, the collision holds the tent through the lower half: its cloth
    // springing back up would pass through it.
    sim.set_loose_pull(false);
    for _ in 0..30 {
        sim.step().unwrap();
    }
    let held = sim.self_intersections().count;
    assert!(held > 0, "{start} crossings, then {held}");
    // Pulled again, the crossing cloth loose: out, and colliding again once it is.
    sim.set_loose_pull(true);
    comes_out_and_stays_out(&mut sim, apex);
}
