//! Contact with rigid bodies: the scenes of the contact issue, each checked at every step
//! for particles inside a body, plus friction against Coulomb's law and tunnelling.

use cloth::collide::Bodies;
use cloth::{math::Vec3, RestCriteria, Simulation, StopReason};
use cloth_fixtures::{
    ContactScene, CubeCorner, FallingPlate, SphereDrop, Tablecloth, TiltedPlane, TurningSphere,
};
use std::ops::ControlFlow;
use std::sync::Arc;

/// Steps `scene` until at rest or `max_steps`, asserting after every step that no particle
/// is deeper inside a body than a tenth of the contact thickness.
fn run_checked(scene: &mut ContactScene, max_steps: u64, thickness: f64) -> StopReason {
    let criteria = RestCriteria {
        max_time_step: None,
        tolerance: 1e-5,
        consecutive_steps: 10,
        max_steps,
        moving_fraction: 0.0,
    };
    let bodies = scene.bodies.clone();
    let mut worst = Depth::default();
    let outcome = scene
        .simulation
        .run_to_rest_with(&criteria, |sim, stats| {
            worst.check(&bodies, sim, stats.step);
            ControlFlow::Continue(())
        })
        .expect("the run does not fail");
    worst.assert_within(thickness);
    outcome.reason
}

/// As [`run_checked`], but every linear solve to the solver's own tolerance: `run_to_rest`
/// also stops a solve at a velocity error below what the rest test sees, which is not
/// symmetric.
fn run_checked_fully_solved(scene: &mut ContactScene, max_steps: u64, thickness: f64) -> StopReason {
    let bodies = scene.bodies.clone();
    let mut worst = Depth::default();
    let reason = step_to_rest(scene, max_steps, |scene, step| {
        worst.check(&bodies, &scene.simulation, step)
    });
    worst.assert_within(thickness);
    reason
}

/// Full steps (see [`run_checked_fully_solved`]) until every particle moves less than
/// 10 um per step for 10 steps, or `max_steps`; `observe` sees the scene after each step.
fn step_to_rest(
    scene: &mut ContactScene,
    max_steps: u64,
    mut observe: impl FnMut(&ContactScene, u64),
) -> StopReason {
    let mut calm = 0;
    for _ in 0..max_steps {
        let stats = scene.simulation.step().expect("the run does not fail");
        observe(scene, stats.step);
        calm = if stats.max_displacement < 1e-5 {
            calm + 1
        } else {
            0
        };
        if calm >= 10 {
            return StopReason::AtRest;
        }
    }
    StopReason::StepLimit
}

/// The deepest any particle has been inside a body, the step and the particle.
#[derive(Default)]
struct Depth(f64, u64, Option<usize>);

impl Depth {
    fn check(&mut self, bodies: &Bodies, sim: &Simulation, step: u64) {
        let (depth, who) = bodies.deepest_inside(sim.time(), sim.positions());
        if depth > self.0 {
            *self = Self(depth, step, who);
        }
    }
    fn assert_within(&self, thickness: f64) {
        assert!(
            self.0 <= 0.1 * thickness,
            "particle {:?} was {:.3} mm inside a body at step {} (limit {:.3} mm)",
            self.2,
            self.0 * 1e3,
            self.1,
            0.1 * thickness * 1e3
        );
    }
}

#[test]
fn sheet_dropped_on_a_sphere_rests_outside_it() {
    let setup = SphereDrop::default();
    let mut scene = setup.build().unwrap();
    let reason = run_checked(&mut scene, 2000, setup.thickness);
    assert_eq!(
        reason,
        StopReason::AtRest,
        "the sheet should come to rest on the sphere"
    );
    let n = setup.particles_per_side;
    let x = scene.simulation.positions();
    let at = |i: usize, j: usize| x[j * n + i];
    // It drapes: the corners hang well below the sphere's equator.
    assert!(at(0, 0).z < -0.1, "corner at z = {}", at(0, 0).z);
    // With finite friction the folds do not keep the symmetries (see the no-slip test).
    eprintln!(
        "sphere drop, mu = {}: asymmetric by {:.1} mm",
        setup.friction,
        asymmetry(x, n) * 1e3
    );
}

/// Largest departure of the sheet from the square's symmetries about the vertical axis
/// (mirror in x, mirror in y, swap of x and y), m. `x` is an `n` x `n` grid, `j * n + i`.
fn asymmetry(x: &[Vec3], n: usize) -> f64 {
    let mut worst: f64 = 0.0;
    for j in 0..n {
        for i in 0..n {
            let p = x[j * n + i];
            let images = [
                (x[j * n + n - 1 - i], Vec3::new(-p.x, p.y, p.z)),
                (x[(n - 1 - j) * n + i], Vec3::new(p.x, -p.y, p.z)),
                (x[i * n + j], Vec3::new(p.y, p.x, p.z)),
            ];
            for (image, expected) in images {
                worst = worst.max((image - expected).amax());
            }
        }
    }
    worst
}

/// The source's no-slip condition: the sheet keeps the scene's symmetries at rest. The
/// linear solves are tight here: a solve's error is not symmetric, and the landing (each
/// particle's contact and release, the folds of the hanging sheet) amplifies it, from
/// 10 um at rest with a tolerance of 1e-8 to 3 mm with 1e-6.
#[test]
fn sheet_held_on_a_sphere_without_slip_rests_symmetric() {
    let setup = SphereDrop {
        friction: f64::INFINITY,
        ..SphereDrop::default()
    };
    let mut scene = setup.build().unwrap();
    let mut settings = scene.simulation.settings().clone();
    settings.pcg.rel_tolerance = 1e-8;
    scene.simulation.set_settings(settings).unwrap();
    let reason = run_checked_fully_solved(&mut scene, 2000, setup.thickness);
    assert_eq!(reason, StopReason::AtRest);
    let n = setup.particles_per_side;
    let x = scene.simulation.positions();
    let asymmetry = asymmetry(x, n);
    eprintln!("sphere drop, no slip: asymmetric by {:.4} mm", asymmetry * 1e3);
    assert!(asymmetry < 1e-3, "asymmetric by {:.3} mm", asymmetry * 1e3);
    // Held where it landed: the middle rests on the top at the thickness, the corners hang.
    let middle = x[(n / 2) * n + n / 2];
    let top = setup.radius + setup.thickness;
    assert!(
        (middle.z - top).abs() < 0.1 * setup.thickness,
        "middle at z = {}",
        middle.z
    );
    assert!(x[0].z < 0.0, "corner at z = {}", x[0].z);
}

#[test]
fn tablecloth_rests_on_the_table_and_hangs_over_its_edges() {
    let setup = Tablecloth::default();
    let mut scene = setup.build().unwrap();
    let reason = run_checked(&mut scene, 2000, setup.thickness);
    assert_eq!(reason, StopReason::AtRest);
    let n = setup.particles_per_side;
    let x = scene.simulation.positions();
    let top = setup.table_height + setup.thickness;
    let centre = x[(n / 2) * n + n / 2];
    assert!((centre.z - top).abs() < 1e-3, "centre at z = {}", centre.z);
    // Every edge's middle hangs down over the side of the table.
    for k in [n / 2, (n - 1) * n + n / 2, (n / 2) * n, (n / 2) * n + n - 1] {
        assert!(
            x[k].z < setup.table_height - 0.1,
            "edge particle {k} at z = {}",
            x[k].z
        );
        let out = x[k].x.abs().max(x[k].y.abs());
        assert!(
            out >= 0.5 * setup.table_size,
            "edge particle {k} hangs inside the table: {:?}",
            x[k]
        );
    }
}

#[test]
fn sheet_on_a_turning_sphere_turns_with_it() {
    let setup = TurningSphere::default();
    let mut scene = setup.build().unwrap();
    let seconds = 3.0;
    let steps = (seconds / setup.time_step).round() as u64;
    assert_eq!(
        run_checked(&mut scene, steps, setup.thickness),
        StopReason::StepLimit
    );
    // The direction from the middle particle to the middle of an edge turns with the sphere.
    let n = setup.particles_per_side;
    let x = scene.simulation.positions();
    let d = x[(n / 2) * n + n - 1] - x[(n / 2) * n + n / 2];
    let turned = d.y.atan2(d.x);
    let expected = setup.rate * seconds;
    let wrapped = (turned - expected + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI)
        - std::f64::consts::PI;
    assert!(
        wrapped.abs() < 0.05 * expected,
        "sheet turned {turned:.3} rad, the sphere {expected:.3} rad"
    );
}

/// Distance of the origin below the plane of the cloth triangle straight above it
/// (negative: the origin is above the cloth, through it).
fn cloth_height_over_origin(scene: &ContactScene) -> Option<f64> {
    let x = scene.simulation.positions();
    scene.simulation.mesh().triangles().iter().find_map(|t| {
        let [a, b, c] = t.map(|i| x[i]);
        let det = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
        let w1 = ((0.0 - a.x) * (c.y - a.y) - (c.x - a.x) * (0.0 - a.y)) / det;
        let w2 = ((b.x - a.x) * (0.0 - a.y) - (0.0 - a.x) * (b.y - a.y)) / det;
        let w0 = 1.0 - w1 - w2;
        let mut n = (b - a).cross(&(c - a)).normalize();
        if n.z < 0.0 {
            n = -n;
        }
        (w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0).then(|| n.dot(&a))
    })
}

/// Steps the corner scene to rest (or `steps`), checking particles against the cube every
/// step; returns the lowest height of the cloth over the corner and the height at the end.
fn corner_clearance(setup: &CubeCorner, steps: u64) -> (f64, f64) {
    let mut scene = setup.build().unwrap();
    let bodies = scene.bodies.clone();
    let mut worst = Depth::default();
    let mut lowest = f64::INFINITY;
    step_to_rest(&mut scene, steps, |scene, step| {
        worst.check(&bodies, &scene.simulation, step);
        if let Some(z) = cloth_height_over_origin(scene) {
            lowest = lowest.min(z);
        }
    });
    worst.assert_within(setup.thickness);
    let end = cloth_height_over_origin(&scene).unwrap_or(f64::NAN);
    (lowest, end)
}

#[test]
fn a_cube_corner_does_not_poke_through_a_coarse_sheet() {
    let setup = CubeCorner::default();
    // The sheet settles over the corner within a few seconds, but its flaps hanging over
    // the cube's edges keep creeping at about 1 mm/s (see the contact issue's note), so
    // this may run the whole 12.5 s rather than stop at rest.
    let (lowest, end) = corner_clearance(&setup, 1500);
    // The corner is at the origin: the cloth over it never goes below it, and rests on it
    // at the contact thickness (less the give of the feature spring under the sheet's weight).
    assert!(
        lowest > 0.0,
        "the corner poked through: cloth over it at {:.3} mm",
        lowest * 1e3
    );
    assert!(
        (end - setup.thickness).abs() < 0.2 * setup.thickness,
        "cloth rests {:.3} mm over the corner, thickness {:.3} mm",
        end * 1e3,
        setup.thickness * 1e3
    );
    // Without the feature pass the same sheet is pierced: the test can tell.
    let particles_only = CubeCorner {
        sharp_angle: 4.0,
        ..CubeCorner::default()
    };
    let (lowest, _) = corner_clearance(&particles_only, 300);
    assert!(lowest < 0.0, "particles alone kept the corner out ({lowest} m)");
}

#[test]
fn friction_holds_a_sheet_on_a_slope_only_when_mu_exceeds_tan_a() {
    let angle: f64 = 0.3;
    let seconds = 1.0;
    let slide = |friction: f64| {
        let setup = TiltedPlane {
            angle,
            friction,
            ..TiltedPlane::default()
        };
        let mut scene = setup.build().unwrap();
        let steps = (seconds / setup.time_step).round() as u64;
        let start: Vec3 = scene.simulation.positions().iter().sum::<Vec3>();
        let criteria = RestCriteria {
            max_time_step: None,
            tolerance: 0.0f64.max(1e-12),
            consecutive_steps: u32::MAX,
            max_steps: steps,
            moving_fraction: 0.0,
        };
        scene.simulation.run_to_rest(&criteria).unwrap();
        assert!(scene.deepest_penetration() <= 0.1 * setup.thickness);
        let n = scene.simulation.positions().len() as f64;
        let end: Vec3 = scene.simulation.positions().iter().sum::<Vec3>();
        (end - start).dot(&setup.downhill()) / n
    };
    let g = 9.81;
    // mu below tan(a) = 0.309: slides with Coulomb's acceleration g (sin a - mu cos a).
    let mu = 0.2;
    let expected = 0.5 * g * (angle.sin() - mu * angle.cos()) * seconds * seconds;
    let got = slide(mu);
    assert!(
        (got - expected).abs() < 0.05 * expected,
        "slid {got:.4} m, Coulomb says {expected:.4} m"
    );
    // mu above tan(a): it stays.
    let held = slide(0.4);
    assert!(held.abs() < 1e-3, "held sheet moved {:.3} mm", held * 1e3);
}

/// Friction that holds a sheet on a slope, let go of (as the sewing does when seams
/// stall), holds it no more: from rest it slides as on a frictionless slope, `g sin a`.
#[test]
fn a_sheet_held_by_friction_slides_freely_once_the_friction_is_let_go() {
    let angle: f64 = 0.3;
    let setup = TiltedPlane {
        angle,
        friction: 0.4,
        ..TiltedPlane::default()
    };
    let mut scene = setup.build().unwrap();
    let run = |scene: &mut ContactScene, seconds: f64| {
        let sim = &mut scene.simulation;
        let start: Vec3 = sim.positions().iter().sum::<Vec3>();
        let criteria = RestCriteria {
            max_time_step: None,
            tolerance: 1e-12,
            consecutive_steps: u32::MAX,
            max_steps: (seconds / setup.time_step).round() as u64,
            moving_fraction: 0.0,
        };
        sim.run_to_rest(&criteria).unwrap();
        let end: Vec3 = sim.positions().iter().sum::<Vec3>();
        (end - start).dot(&setup.downhill()) / sim.positions().len() as f64
    };
    let held = run(&mut scene, 0.5);
    assert!(held.abs() < 1e-3, "held sheet moved {:.3} mm", held * 1e3);
    assert!(scene.simulation.scale_body_friction(-1.0).is_err());
    scene.simulation.scale_body_friction(0.0).unwrap();
    let seconds = 1.0;
    let expected = 0.5 * 9.81 * angle.sin() * seconds * seconds;
    let got = run(&mut scene, seconds);
    assert!(
        (got - expected).abs() < 0.05 * expected,
        "slid {got:.4} m, a frictionless slope gives {expected:.4} m"
    );
    assert!(scene.deepest_penetration() <= 0.1 * setup.thickness);
}

/// A sheet sliding at 1 m/s over a level plate slows down at Coulomb's `mu g` and stops,
/// never turning back: friction as the implicit step's drag against the sliding.
#[test]
fn friction_stops_a_sliding_sheet_as_coulomb_says() {
    let (mu, v0, g) = (0.5, 1.0, 9.81);
    let setup = TiltedPlane {
        angle: 0.0,
        friction: mu,
        ..TiltedPlane::default()
    };
    let mut scene = setup.build().unwrap();
    let sim = &mut scene.simulation;
    let n = sim.positions().len();
    sim.set_velocities(&vec![Vec3::new(v0, 0.0, 0.0); n]).unwrap();
    let mean_x = |sim: &Simulation| sim.positions().iter().map(|p| p.x).sum::<f64>() / n as f64;
    let start = mean_x(sim);
    let h = setup.time_step;
    // Backward Euler with Coulomb's law: v_k = v0 - k mu g h until it stops, x += h v_k.
    let mut expected = 0.0;
    let mut speed = v0;
    for step in 1..=60 {
        speed = (speed - mu * g * h).max(0.0);
        expected += h * speed;
        sim.step().unwrap();
        let v = sim.velocities().iter().map(|v| v.x).sum::<f64>() / n as f64;
        assert!(
            (v - speed).abs() < 0.02 * v0,
            "step {step}: mean speed {v:.4} m/s, Coulomb says {speed:.4} m/s"
        );
    }
    let slid = mean_x(sim) - start;
    assert!(
        (slid - expected).abs() < 0.02 * expected,
        "slid {slid:.4} m, Coulomb says {expected:.4} m"
    );
    let fastest = sim.velocities().iter().map(|v| v.norm()).fold(0.0, f64::max);
    assert!(fastest < 1e-3, "still moving at {fastest} m/s");
}

/// A sheet dragged over a level plate by one edge at constant speed: once it slides
/// steadily, its pull on the pinned edge balances Coulomb's friction on the rest, mu g
/// times their mass. Here each contact's friction comes through its neighbours' pull, not
/// from a uniform motion.
#[test]
fn a_dragged_sheet_pulls_back_with_coulombs_friction() {
    use cloth::collide::{Body, TriSurface};
    use cloth::{GridBuilder, Pin, SimulationBuilder};
    use cloth_fixtures::scene_fabric;
    let (mu, g, thickness, speed, h) = (0.5, 9.81, 0.003, 0.1, 1.0 / 120.0);
    let plate = TriSurface::cuboid(Vec3::new(2.0, 2.0, 0.05)).unwrap();
    let pose = nalgebra::Isometry3::translation(0.0, 0.0, -0.05);
    let body = Body::new("plate", plate)
        .with_pose(pose)
        .unwrap()
        .with_thickness(thickness)
        .unwrap()
        .with_friction(mu)
        .unwrap();
    let n = 11;
    let mesh = GridBuilder::new(n, n)
        .size(0.2, 0.2)
        .origin(Vec3::new(-0.1, -0.1, thickness))
        .build()
        .unwrap();
    let x0 = mesh.positions().to_vec();
    // The edge at the lowest y, pulled along -y.
    let edge: Vec<usize> = (0..n).collect();
    let pins = edge.iter().map(|&i| {
        let start = x0[i];
        Pin::path(i, move |t| start - t * speed * Vec3::y())
    });
    let builder = SimulationBuilder::new(mesh, scene_fabric().with_drag(0.0))
        .time_step(h)
        .pins(pins);
    let mut scene = ContactScene::new(body, builder).unwrap();
    let sim = &mut scene.simulation;
    let dragged: f64 = sim.masses()[n..].iter().sum();
    let mut pulls = Vec::new();
    for step in 0..240 {
        sim.step().unwrap();
        if step >= 180 {
            let forces = sim.forces();
            pulls.push(edge.iter().map(|&i| forces[i].y).sum::<f64>());
        }
    }
    let pull = pulls.iter().sum::<f64>() / pulls.len() as f64;
    let expected = mu * g * dragged;
    eprintln!("dragged sheet: pull {pull:.5} N, Coulomb's friction {expected:.5} N");
    let slowest = sim.velocities()[n..]
        .iter()
        .map(|v| -v.y)
        .fold(f64::INFINITY, f64::min);
    assert!(
        (slowest - speed).abs() < 0.02 * speed,
        "the sheet should slide with its edge: slowest particle at {slowest} m/s"
    );
    assert!(
        (pull - expected).abs() < 0.03 * expected,
        "pull on the edge {pull:.5} N, Coulomb's friction {expected:.5} N"
    );
}

#[test]
fn a_fast_sheet_does_not_pass_through_a_thin_plate() {
    let setup = FallingPlate::default();
    let mut scene = setup.build().unwrap();
    let bodies = scene.bodies.clone();
    for _ in 0..30 {
        let stats = scene.simulation.step().unwrap();
        let x = scene.simulation.positions();
        let (depth, _) = bodies.deepest_inside(scene.simulation.time(), x);
        assert!(
            depth <= 0.1 * setup.thickness,
            "step {}: {depth} m inside",
            stats.step
        );
        let lowest = x.iter().map(|p| p.z).fold(f64::INFINITY, f64::min);
        assert!(
            lowest > 0.0,
            "step {}: a particle is at z = {lowest}, under the plate's top",
            stats.step
        );
    }
    // It moves 0.17 m a step at the start: only the path test can have caught it.
    let lowest = scene
        .simulation
        .positions()
        .iter()
        .map(|p| p.z)
        .fold(f64::INFINITY, f64::min);
    assert!((lowest - setup.thickness).abs() < 1e-3, "resting at z = {lowest}");
}

/// A 3 cm thick slab (a hand) and a 30 cm sheet standing across it (a panel through it).
fn hand_and_sheet() -> (Arc<cloth::collide::Bodies>, cloth::ClothMesh) {
    use cloth::collide::{Body, TriSurface};
    use cloth::GridBuilder;
    let hand = TriSurface::cuboid(Vec3::new(0.015, 0.04, 0.045)).unwrap();
    let bodies = Arc::new(Bodies::new(vec![Body::new("hand", hand)]));
    let mesh = GridBuilder::new(31, 31)
        .size(0.3, 0.3)
        .origin(Vec3::new(0.003, -0.15, -0.15))
        .axes(Vec3::y(), Vec3::z())
        .build()
        .unwrap();
    (bodies, mesh)
}

/// A 30 cm sheet standing across a 3 cm thick slab (a hand through a panel), moving at
/// 0.5 m/s along its normal for 0.2 s, with its whole area passing through the bodies or
/// not; the sheet's positions after.
fn sheet_through_a_hand(pass: bool) -> (Vec<Vec3>, Simulation, Arc<cloth::collide::Bodies>) {
    use cloth::{Fabric, PassThrough, SimulationBuilder, SolverSettings};
    let (bodies, mesh) = hand_and_sheet();
    let n = mesh.vertex_count();
    let inside = mesh
        .positions()
        .iter()
        .filter(|p| bodies.signed_distance(0.0, p).is_some_and(|(d, _)| d < 0.0))
        .count();
    assert!(inside > 50, "{inside} particles start in the hand");
    let pieces = if pass {
        vec![PassThrough {
            members: (0..n).collect(),
            until_out: true,
        }]
    } else {
        Vec::new()
    };
    let mut sim = SimulationBuilder::new(mesh, Fabric::cotton_like().with_damping(0.01))
        .settings(SolverSettings {
            gravity: Vec3::zeros(),
            time_step: 0.01,
            ..SolverSettings::default()
        })
        .velocities(vec![Vec3::new(0.5, 0.0, 0.0); n])
        .pass_through(pieces)
        .collider(bodies.clone())
        .build()
        .unwrap();
    for _ in 0..20 {
        sim.step().unwrap();
    }
    (sim.positions().to_vec(), sim, bodies)
}

#[test]
fn a_sheet_placed_through_a_hand_passes_out_of_it_whole_then_is_held_by_it() {
    let spread = |x: &[Vec3]| {
        let (lo, hi) = x.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.x), hi.max(p.x))
        });
        hi - lo
    };
    // Held by the hand, the part of the sheet in it is pushed out to its nearest faces and
    // the sheet hangs on it, bent round it.
    let (caught, _, _) = sheet_through_a_hand(false);
    println!("caught spread {}", spread(&caught));
    assert!(spread(&caught) > 0.02, "spread {}", spread(&caught));
    // Passing, it comes out flat beyond the hand, and from then on the hand holds it.
    let (passed, mut sim, bodies) = sheet_through_a_hand(true);
    println!("passed spread {}", spread(&passed));
    assert!(spread(&passed) < 0.005, "spread {}", spread(&passed));
    assert!(passed.iter().all(|p| p.x > 0.015), "not out of the hand");
    assert!(sim.passing().is_empty(), "still passing");
    let n = passed.len();
    sim.set_velocities(&vec![Vec3::new(-0.5, 0.0, 0.0); n]).unwrap();
    for _ in 0..20 {
        sim.step().unwrap();
        let (depth, _) = bodies.deepest_inside(sim.time(), sim.positions());
        assert_eq!(depth, 0.0, "inside the hand at step {}", sim.step_count());
    }
    assert_eq!(sim.body_intersections(), 0);
    // Stopped on the hand's face: the middle of the sheet rests against it.
    let middle = sim.positions()[15 * 31 + 15];
    assert!(middle.x > 0.015 && middle.x < 0.03, "{middle}");
}

#[test]
fn a_sheet_passing_a_hand_for_good_stays_through_it_and_its_crossings_are_counted_apart() {
    use cloth::{count_body_intersections, Fabric, PassThrough, SimulationBuilder, SolverSettings};
    let (bodies, mesh) = hand_and_sheet();
    let n = mesh.vertex_count();
    let mut sim = SimulationBuilder::new(mesh, Fabric::cotton_like().with_damping(0.01))
        .settings(SolverSettings {
            gravity: Vec3::zeros(),
            time_step: 0.01,
            ..SolverSettings::default()
        })
        .pass_through(vec![PassThrough {
            members: (0..n).collect(),
            until_out: false,
        }])
        .collider(bodies.clone())
        .build()
        .unwrap();
    for _ in 0..10 {
        sim.step().unwrap();
    }
    // Left where it was, through the hand, and still passing it.
    assert_eq!(sim.passing().len(), 1);
    assert!(sim.positions().iter().all(|p| (p.x - 0.003).abs() < 1e-6));
    let apart = sim.body_intersections_apart();
    assert_eq!(apart.crossings, 0);
    assert_eq!(sim.body_intersections(), 0);
    // Counted as any cloth's, the sheet's edges cross the hand's sides where it cuts them.
    let all = count_body_intersections(bodies.as_ref(), sim.time(), sim.mesh(), sim.positions(), &[]);
    assert!(all.crossings > 0 && all.thin_parts_passed == 0, "{all:?}");
    assert_eq!(apart.thin_parts_passed, all.crossings);
}

/// A strip of cloth 1 mm wide and 6 cm long lying along the bottom of the groove between
/// two cylinders of radius 4 cm side by side `gap` apart (an arm against the trunk), 2 mm
/// above the line where they are nearest, where the walls are 0.1 mm farther apart than
/// there, far closer than their two contact layers: its side at x = -1 mm starts inside
/// the left one, its side at x = 0 between them. Returns the deepest any particle was
/// inside either over 30 steps, m.
fn strip_in_a_groove(gap: f64) -> f64 {
    use cloth::collide::{Body, TriSurface};
    use cloth::{Fabric, GridBuilder, SimulationBuilder, SolverSettings};
    let radius = 0.04;
    let lying = |x: f64| {
        let along_y = nalgebra::UnitQuaternion::from_axis_angle(&Vec3::x_axis(), std::f64::consts::FRAC_PI_2);
        let pose = nalgebra::Isometry3::from_parts(nalgebra::Translation3::new(x, 0.0, 0.0), along_y);
        Body::new("cylinder", TriSurface::cylinder(radius, 0.1, 256).unwrap())
            .with_pose(pose)
            .unwrap()
    };
    let off = radius + 0.5 * gap;
    let bodies = Arc::new(Bodies::new(vec![lying(-off), lying(off)]));
    let mesh = GridBuilder::new(2, 13)
        .size(0.001, 0.06)
        .origin(Vec3::new(-0.001, -0.03, 0.002))
        .build()
        .unwrap();
    let inside = mesh
        .positions()
        .iter()
        .filter(|p| bodies.signed_distance(0.0, p).is_some_and(|(d, _)| d < 0.0))
        .count();
    assert_eq!(inside, 13, "one side of the strip starts in the left cylinder");
    let mut sim = SimulationBuilder::new(mesh, Fabric::cotton_like())
        .settings(SolverSettings {
            gravity: Vec3::zeros(),
            time_step: 0.01,
            ..SolverSettings::default()
        })
        .collider(bodies.clone())
        .build()
        .unwrap();
    let mut worst = Depth::default();
    for _ in 0..30 {
        let stats = sim.step().unwrap();
        worst.check(&bodies, &sim, stats.step);
    }
    worst.0
}

#[test]
fn cloth_put_out_of_one_wall_of_a_groove_narrower_than_two_contact_layers_is_not_put_into_the_other() {
    for gap in [0.0005, 0.0] {
        let depth = strip_in_a_groove(gap);
        assert!(
            depth <= 0.0,
            "{:.3} mm inside a wall with the cylinders {gap} m apart",
            depth * 1e3
        );
    }
}
