//! The source's model size: a 1 m x 1 m sheet of 110 x 110 particles (12,100) hanging
//! from two corners under gravity, cotton-like (0.15 kg/m^2, 1000 N/m, B = 1e-5 N*m),
//! implicit Euler at h = 1/60 s. Target: one implicit step in at most 20 ms median on
//! 2 cores (the source needed 8 to 12 s). Run with `cargo bench --bench step`.

use cloth::linalg::{Filter, Multigrid};
use cloth::parallelism::Parallelism;
use cloth::{math::Vec3, Fabric, GridBuilder, Pin, Simulation, SimulationBuilder};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::time::Duration;

const N: usize = 110;

/// The benchmark sheet after `warmup` steps, so the cloth is moving and folded.
fn sheet(warmup: usize) -> Simulation {
    let mesh = GridBuilder::new(N, N).size(1.0, 1.0).build().expect("grid");
    let g = mesh.grid().expect("grid shape");
    let mut sim = SimulationBuilder::new(mesh, Fabric::cotton_like())
        .pin(Pin::fixed(g.index(0, N - 1)))
        .pin(Pin::fixed(g.index(N - 1, N - 1)))
        .build()
        .expect("valid scene");
    for _ in 0..warmup {
        sim.step().expect("stable");
    }
    sim
}

fn benches(c: &mut Criterion) {
    let mut sim = sheet(30);
    let mut group = c.benchmark_group("sheet_110x110");
    group.sample_size(20).measurement_time(Duration::from_secs(15));

    group.bench_function("forces", |b| b.iter(|| black_box(sim.forces().len())));
    group.bench_function("forces_and_jacobian_assembly", |b| {
        b.iter(|| black_box(sim.assemble_system()))
    });

    sim.step().expect("stable");
    let a = sim.system_matrix().clone();
    let x: Vec<Vec3> = (0..a.n()).map(|i| Vec3::new(i as f64, 1.0, -0.5)).collect();
    let mut y = vec![Vec3::zeros(); a.n()];
    // The preconditioner on its own: its setup (once per solve, for a new matrix) and one
    // V-cycle (once per CG iteration), on the same matrix with no constraint.
    let filter = Filter::new(a.n(), 0);
    let mut multigrid = Multigrid::new(&a);
    // Built here too, so a filtered run of the cycle alone has a hierarchy to cycle.
    multigrid
        .build(&a, &filter, Parallelism::Rayon)
        .expect("definite");
    group.bench_function("multigrid_setup", |b| {
        b.iter(|| {
            multigrid
                .build(&a, &filter, Parallelism::Rayon)
                .expect("definite")
        })
    });
    // The product and the cycle on rayon's pool, then on one thread: what the work costs
    // without the threads' hand-overs, for how many products' worth a cycle is.
    for (par, on) in [(Parallelism::Rayon, ""), (Parallelism::Sequential, "_one_thread")] {
        group.bench_function(format!("matrix_vector_product{on}"), |b| {
            b.iter(|| a.mul(black_box(&x), &mut y, par))
        });
        group.bench_function(format!("multigrid_cycle{on}"), |b| {
            b.iter(|| multigrid.apply(&a, &filter, black_box(&x), &mut y, par))
        });
    }

    // Consecutive steps of the falling sheet: the median is a typical step of the run.
    let mut iterations = Vec::new();
    group.bench_function("implicit_step", |b| {
        b.iter(|| iterations.push(sim.step().expect("stable").cg_iterations))
    });
    group.finish();
    // A filtered run (`cargo bench --bench step -- forces`) takes no step.
    if iterations.is_empty() {
        return;
    }
    iterations.sort_unstable();
    eprintln!(
        "implicit_step: {} particles, {} blocks, median {} CG iterations over {} steps",
        a.n(),
        a.nnz_blocks(),
        iterations[iterations.len() / 2],
        iterations.len()
    );
}

criterion_group!(step, benches);
criterion_main!(step);
