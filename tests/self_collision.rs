//! The cloth against itself: layers and folds never pass through each other, layers stay
//! apart by their thickness, and friction between layers follows Coulomb's law. Each
//! scene is also run with self-collision off where that shows the test can fail.

mod common;

use cloth::{
    math::Vec3, ClothMesh, Fabric, GridBuilder, Pin, SelfCollision, Simulation, SimulationBuilder,
    SolverSettings,
};
use cloth_fixtures::{ContactScene, FoldingStrip, SheetOntoSheet, StackedSheets};

/// Steps `sim` `steps` times, calling `check` after every step (every step is a frame).
fn run(sim: &mut Simulation, steps: u64, mut check: impl FnMut(&Simulation)) {
    for _ in 0..steps {
        let stats = sim.step().expect("the run does not fail");
        assert_eq!(stats.self_unresolved, 0, "step {}: impacts left", stats.step);
        check(sim);
    }
}

fn without_self_collision(mut scene: ContactScene) -> Simulation {
    let settings = SolverSettings {
        self_collision: SelfCollision::off(),
        ..scene.simulation.settings().clone()
    };
    scene.simulation.set_settings(settings).unwrap();
    scene.simulation
}

/// The highest intersection count over a run of `steps` without self-collision.
fn intersections_without(scene: ContactScene, steps: u64) -> usize {
    let mut sim = without_self_collision(scene);
    let mut most = 0;
    run(&mut sim, steps, |sim| {
        most = most.max(sim.self_intersections().count)
    });
    most
}

#[test]
fn a_strip_crumpling_onto_the_floor_never_passes_through_itself() {
    let setup = FoldingStrip::default();
    let mut scene = setup.build().unwrap();
    let mut most_contacts = 0;
    run(&mut scene.simulation, 300, |sim| {
        let found = sim.self_intersections();
        assert_eq!(found.count, 0, "step {}: {found:?}", sim.step_count());
        most_contacts = most_contacts.max(sim.self_contacts().len());
    });
    let sim = &scene.simulation;
    // It did fold over itself: it lies in layers, far lower than its length.
    let top = sim.positions().iter().map(|p| p.z).fold(f64::MIN, f64::max);
    assert!(top < 0.2 * setup.length, "top at {top}");
    assert!(most_contacts > 100, "{most_contacts} contacts at most");
    assert!(scene.deepest_penetration() <= 0.1 * setup.thickness);
    // The same fall without self-collision goes through itself.
    let through = intersections_without(setup.build().unwrap(), 300);
    assert!(through > 0, "no intersections without self-collision");
}

#[test]
fn two_stacked_sheets_on_a_sphere_stay_apart_by_half_their_thickness() {
    let setup = StackedSheets::default();
    let mut scene = setup.build().unwrap();
    let thickness = scene.simulation.fabrics()[0].thickness;
    let n = setup.particles_per_side * setup.particles_per_side;
    let mut closest = f64::INFINITY;
    run(&mut scene.simulation, 300, |sim| {
        assert_eq!(sim.self_intersections().count, 0, "step {}", sim.step_count());
        if let Some(d) = sim.closest_self_approach(thickness) {
            closest = closest.min(d);
        }
    });
    assert!(
        closest >= 0.5 * thickness,
        "the layers came {:.3} mm close (thickness {:.3} mm)",
        closest * 1e3,
        thickness * 1e3
    );
    let sim = &scene.simulation;
    // Draped, and in contact: the upper sheet lies on the lower over the sphere's top.
    let x = sim.positions();
    let (lower, upper) = x.split_at(n);
    let top = |s: &[Vec3]| s.iter().map(|p| p.z).fold(f64::MIN, f64::max);
    assert!(top(upper) > top(lower), "upper sheet below the lower one");
    assert!(top(upper) - top(lower) < 3.0 * thickness, "the sheets are apart");
    let corner = upper.iter().map(|p| p.z).fold(f64::MAX, f64::min);
    assert!(corner < 0.0, "the upper sheet does not drape: lowest at {corner}");
    assert!(scene.deepest_penetration() <= 0.1 * setup.thickness);
}

#[test]
fn a_sheet_thrown_onto_a_lying_sheet_does_not_pass_through_it() {
    let setup = SheetOntoSheet::default();
    let mut scene = setup.build().unwrap();
    let h = setup.time_step;
    // It travels more than a hundred thicknesses each step.
    let thickness = scene.simulation.fabrics()[0].thickness;
    assert!(setup.speed * h > 100.0 * thickness);
    let n = setup.particles_per_side * setup.particles_per_side;
    run(&mut scene.simulation, 120, |sim| {
        assert_eq!(sim.self_intersections().count, 0, "step {}", sim.step_count());
    });
    // Every particle of the thrown sheet over the lying one is above it.
    let above = |sim: &Simulation| {
        let x = sim.positions();
        let half = 0.5 * setup.sheet_size;
        let lying = x[..n].iter().map(|p| p.z).fold(f64::MIN, f64::max);
        x[n..]
            .iter()
            .filter(|p| p.x.abs() < half && p.y.abs() < half)
            .all(|p| p.z > lying)
    };
    assert!(above(&scene.simulation), "the thrown sheet went through");
    assert!(scene.deepest_penetration() <= 0.1 * setup.thickness);
    // Without self-collision it does go through.
    let mut sim = without_self_collision(setup.build().unwrap());
    run(&mut sim, 120, |_| {});
    assert!(
        !above(&sim),
        "the thrown sheet stayed above without self-collision"
    );
}

/// A 30 cm sheet lying on a fixed 60 cm sheet tilted by `angle`, with Coulomb coefficient
/// `mu` between them, let go: the upper sheet's mean downhill speed after each of the
/// first `steps` steps of 1/120 s.
fn sliding_speeds(angle: f64, mu: f64, steps: usize) -> Vec<f64> {
    let h = 1.0 / 120.0;
    let (s, c) = angle.sin_cos();
    let down = Vec3::new(c, 0.0, -s);
    let normal = Vec3::new(s, 0.0, c);
    let sheet = |n: usize, size: f64, centre: Vec3| {
        GridBuilder::new(n, n)
            .size(size, size)
            .origin(centre - 0.5 * size * (down + Vec3::y()))
            .axes(down, Vec3::y())
            .build()
            .unwrap()
    };
    let fabric = Fabric::cotton_like().with_damping(2e-3);
    // Resting on the lower sheet (just inside the contact distance), its particles not
    // over the lower one's.
    let (n, fixed) = (15, 29 * 29);
    let offset = 0.01 * (down + Vec3::y()) + 0.998 * fabric.thickness * normal;
    let mesh = ClothMesh::join(&[sheet(29, 0.6, Vec3::zeros()), sheet(n, 0.3, offset)]).unwrap();
    let settings = SolverSettings {
        time_step: h,
        self_collision: SelfCollision {
            friction: Some(mu),
            ..SelfCollision::default()
        },
        ..SolverSettings::default()
    };
    let mut sim = SimulationBuilder::new(mesh, fabric)
        .settings(settings)
        .pins((0..fixed).map(Pin::fixed))
        .build()
        .unwrap();
    let start = sim.positions()[fixed..].to_vec();
    let speeds = (0..steps)
        .map(|_| {
            sim.step().unwrap();
            sim.velocities()[fixed..]
                .iter()
                .map(|v| v.dot(&down))
                .sum::<f64>()
                / (n * n) as f64
        })
        .collect();
    // It stays on the lower sheet, within the contact distance.
    let lift = sim.positions()[fixed..]
        .iter()
        .zip(&start)
        .map(|(x, x0)| (x - x0).dot(&normal).abs())
        .fold(0.0, f64::max);
    assert!(
        lift < sim.fabrics()[0].thickness,
        "left the lower sheet by {lift}"
    );
    speeds
}

#[test]
fn friction_between_layers_holds_below_the_angle_of_repose_and_slides_by_coulomb_above() {
    let (g, h) = (9.81, 1.0 / 120.0);
    let angle = 30f64.to_radians();
    // tan 30 degrees = 0.577: a coefficient of 0.8 holds the sheet.
    let held = sliding_speeds(angle, 0.8, 30);
    assert!(
        held.iter().all(|v| v.abs() < 1e-3),
        "slides with mu = 0.8: {held:?}"
    );
    // Below it the sheet slides with a = g (sin a - mu cos a), measured from its speed
    // after the first steps (where the contacts settle) to 0.2 s.
    for mu in [0.0, 0.1, 0.3, 0.5] {
        let v = sliding_speeds(angle, mu, 24);
        let measured = (v[23] - v[6]) / (17.0 * h);
        let coulomb = g * (angle.sin() - mu * angle.cos());
        assert!(
            (measured / coulomb - 1.0).abs() < 0.03,
            "mu {mu}: {measured:.4} m/s^2, Coulomb says {coulomb:.4}"
        );
    }
}

#[test]
fn layers_in_contact_give_the_same_result_on_any_number_of_threads() {
    let run_on = |threads: usize| {
        common::on_threads(threads, || {
            let mut scene = StackedSheets {
                particles_per_side: 15,
                ..StackedSheets::default()
            }
            .build()
            .unwrap();
            let mut contacts = 0;
            for _ in 0..40 {
                contacts += scene.simulation.step().unwrap().self_contacts;
            }
            (scene.simulation.positions().to_vec(), contacts)
        })
    };
    let (one, contacts) = run_on(1);
    assert!(contacts > 0, "no contacts: the test tests nothing");
    let (two, same) = run_on(2);
    assert_eq!(contacts, same);
    assert_eq!(one, two);
}

/// A strip wound twice round like a ramp, `pitch` between its turns: every normal within a
/// degree of vertical, all of it one connected piece, yet its upper turn lies over the
/// lower. Returns the simulation with the lower turn pinned and the upper one thrown down
/// at `speed`, and the number of particles pinned.
fn ramp(pitch: f64, speed: f64, self_collision: SelfCollision) -> (Simulation, usize) {
    use std::f64::consts::TAU;
    let (radius, width, along, across) = (0.06, 0.02, 120, 3);
    let mut positions = Vec::new();
    let mut uv = Vec::new();
    for i in 0..=along {
        let angle = 2.0 * TAU * i as f64 / along as f64;
        for j in 0..=across {
            let r = radius - 0.5 * width + width * j as f64 / across as f64;
            positions.push(Vec3::new(r * angle.cos(), r * angle.sin(), pitch * angle / TAU));
            uv.push(nalgebra::Vector2::new(
                radius * angle,
                width * j as f64 / across as f64,
            ));
        }
    }
    let id = |i: usize, j: usize| i * (across + 1) + j;
    let mut triangles = Vec::new();
    for i in 0..along {
        for j in 0..across {
            triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    let mesh = ClothMesh::new(positions, uv, triangles).unwrap();
    // The first turn's particles.
    let lower = (along / 2 + 1) * (across + 1);
    let mut v = vec![Vec3::zeros(); mesh.vertex_count()];
    for vi in &mut v[lower..] {
        *vi = Vec3::new(0.0, 0.0, -speed);
    }
    let settings = SolverSettings {
        time_step: 0.01,
        self_collision,
        ..SolverSettings::default()
    };
    let sim = SimulationBuilder::new(mesh, Fabric::cotton_like())
        .settings(settings)
        .pins((0..lower).map(Pin::fixed))
        .velocities(v)
        .build()
        .unwrap();
    (sim, lower)
}

#[test]
fn a_ramp_wound_over_itself_does_not_pass_through_its_lower_turn() {
    // Its turns 2 mm apart, the upper one moving 5 mm a step: through the lower turn
    // within the first step unless the search looks inside the ramp, whose normals lie in
    // a narrow cone (the contour test, which sees its contour wind round twice).
    let (pitch, speed) = (0.002, 0.5);
    let (mut sim, lower) = ramp(pitch, speed, SelfCollision::default());
    let thickness = sim.fabrics()[0].thickness;
    let mut contacts = Vec::new();
    run(&mut sim, 10, |sim| {
        let found = sim.self_intersections();
        assert_eq!(found.count, 0, "step {}: {found:?}", sim.step_count());
        contacts.push(sim.self_contacts().len());
    });
    // Once they meet (the first step's impacts land them within the contact distance),
    // the turns are in contact: the proximity search looks inside the ramp too.
    assert!(
        contacts[1..].iter().all(|&c| c > 100),
        "contacts per step {contacts:?}"
    );
    // The upper turn lies on the lower one where it is over it (away from the start,
    // where the turns meet): above it by about the thickness.
    let (inner, outer) = (0.05, 0.07);
    let mut over = 0;
    for p in &sim.positions()[lower..] {
        let r = p.xy().norm();
        let angle = p.y.atan2(p.x).rem_euclid(std::f64::consts::TAU);
        if !(r > inner && r < outer && angle > 0.3 && angle < std::f64::consts::TAU - 0.3) {
            continue;
        }
        over += 1;
        let beneath = pitch * angle / std::f64::consts::TAU;

        assert!(
            p.z - beneath > 0.5 * thickness,
            "{p} is {} above the lower turn",
            p.z - beneath
        );
    }
    assert!(over > lower / 4, "{over} particles over the lower turn");
    let (mut through, _) = ramp(pitch, speed, SelfCollision::off());
    let mut most = 0;
    run(&mut through, 10, |sim| {
        most = most.max(sim.self_intersections().count)
    });
    assert!(most > 0, "no intersections without self-collision");
}

#[test]
fn explicit_steps_push_layers_apart_too() {
    // The stacked sheets, 2 mm apart, within a 4 mm contact distance from the start and
    // stepped by forward Euler: the repulsion (with friction between the layers predicted
    // from the forces) pushes them apart, and nothing passes through.
    let setup = StackedSheets {
        particles_per_side: 10,
        ..StackedSheets::default()
    };
    let mut scene = setup.build().unwrap();
    let thickness = 0.004;
    let settings = SolverSettings {
        integrator: cloth::Integrator::ExplicitEuler,
        time_step: 5e-6,
        self_collision: SelfCollision {
            thickness: Some(thickness),
            ..SelfCollision::default()
        },
        ..scene.simulation.settings().clone()
    };
    scene.simulation.set_settings(settings).unwrap();
    let mut contacts = Vec::new();
    run(&mut scene.simulation, 200, |sim| {
        assert_eq!(sim.self_intersections().count, 0, "step {}", sim.step_count());
        contacts.push(sim.self_contacts().len());
    });
    assert!(contacts[0] > 100, "{} contacts at the start", contacts[0]);
    let approach = scene.simulation.closest_self_approach(thickness);
    assert!(
        approach.is_none_or(|d| d > setup.gap),
        "closest approach {approach:?}, started {} apart",
        setup.gap
    );
}
