//! Contact at the source's model size. Run with `cargo bench --bench contact`.
//!
//! - `query/*`: the per-particle proximity query of 12,100 particles (110 x 110) against a
//!   UV sphere of 39,600 triangles, every particle within the contact layer (the costly
//!   case: each query ends in a projection onto the surface). `at_rest` asks at one point,
//!   `sweep` along a step's path from 5 mm above the layer to 1 mm inside it (ray cast
//!   first, then the projection), as the end-of-step pass does.
//! - `sphere_drop_110x110/implicit_step`: whole implicit steps of a 1 m sheet of 12,100
//!   particles lying on a sphere (R = 0.25 m) after it has landed: contacts, friction,
//!   release passes and the end-of-step sweep included. Target: 25 ms median on 2 cores.

use cloth::collide::{Bodies, Body, TriSurface};
use cloth::{math::Vec3, Collider, ParticlePath, Proximity};
use cloth_fixtures::SphereDrop;
use criterion::{criterion_group, criterion_main, Criterion};
use rayon::prelude::*;
use std::hint::black_box;
use std::time::Duration;

const N: usize = 110;
const RADIUS: f64 = 0.25;
const THICKNESS: f64 = 0.003;

/// 110 x 110 points over the sphere's upper half, `height` beyond the contact layer.
fn cap_points(height: f64) -> Vec<Vec3> {
    let r = RADIUS + THICKNESS + height;
    (0..N * N)
        .map(|k| {
            let (i, j) = (k % N, k / N);
            let polar = 0.5 * std::f64::consts::FRAC_PI_2 * (1.0 + i as f64 / N as f64);
            let azimuth = std::f64::consts::TAU * j as f64 / N as f64;
            r * Vec3::new(
                polar.sin() * azimuth.cos(),
                polar.sin() * azimuth.sin(),
                polar.cos(),
            )
        })
        .collect()
}

fn count_near(bodies: &Bodies, from: &[Vec3], to: &[Vec3]) -> usize {
    from.par_iter()
        .zip(to)
        .filter(|(a, b)| {
            matches!(
                bodies.sweep(
                    &ParticlePath::new(0.0, **a, 1.0 / 60.0, **b),
                    f64::INFINITY,
                    4.0 * THICKNESS
                ),
                Proximity::Near(_)
            )
        })
        .count()
}

fn query(c: &mut Criterion) {
    let sphere = TriSurface::sphere(RADIUS, 200, 100).expect("sphere");
    let triangles = sphere.triangles().len();
    let body = Body::new("sphere", sphere)
        .with_thickness(THICKNESS)
        .expect("thickness");
    let bodies = Bodies::new(vec![body]);
    let above = cap_points(0.005);
    let inside = cap_points(-0.001);
    assert_eq!(count_near(&bodies, &inside, &inside), N * N);
    eprintln!("query: {} particles against {triangles} triangles", N * N);

    let mut group = c.benchmark_group("query");
    group.sample_size(30).measurement_time(Duration::from_secs(10));
    group.bench_function("at_rest", |b| {
        b.iter(|| black_box(count_near(&bodies, &inside, &inside)))
    });
    group.bench_function("sweep", |b| {
        b.iter(|| black_box(count_near(&bodies, &above, &inside)))
    });
    group.finish();
}

fn implicit_step(c: &mut Criterion) {
    let setup = SphereDrop {
        particles_per_side: N,
        ..SphereDrop::default()
    };
    let mut scene = setup.build().expect("scene");
    // Landed: about a third of the sheet lies on the sphere, the rest still swings down.
    for _ in 0..40 {
        scene.simulation.step().expect("stable");
    }
    let mut stats = Vec::new();
    let mut group = c.benchmark_group("sphere_drop_110x110");
    group.sample_size(20).measurement_time(Duration::from_secs(20));
    group.bench_function("implicit_step", |b| {
        b.iter(|| stats.push(scene.simulation.step().expect("stable")))
    });
    group.finish();
    // A filtered run (`cargo bench --bench contact -- query`) takes no step.
    if stats.is_empty() {
        return;
    }
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    eprintln!(
        "implicit_step: {} steps, median {} contacts, {} CG iterations, contact stage {:.2} ms, solve {:.2} ms",
        stats.len(),
        median(stats.iter().map(|s| s.contacts as f64).collect()),
        median(stats.iter().map(|s| s.cg_iterations as f64).collect()),
        1e3 * median(stats.iter().map(|s| s.contact_seconds).collect()),
        1e3 * median(stats.iter().map(|s| s.solve_seconds).collect()),
    );
}

criterion_group!(contact, query, implicit_step);
criterion_main!(contact);
