//! The source's model size: a 1 m cotton-like sheet of 110 x 110 particles (12,100),
//! hanging from two corners, integrated with implicit Euler at h = 1/60 s until it is at
//! rest. Prints the source's table (maximum stretch between neighbouring points, warp =
//! horizontal and weft = vertical, after N iterations), the time per step and the CG
//! iterations, then a JSON summary line.
//!
//!     cargo run --release --example hanging_sheet [-- PARTICLES_PER_SIDE]

use cloth::{
    Fabric, GridBuilder, GridStretch, Pin, RestCriteria, SimulationBuilder, StopReason, StrainReport,
};
use std::ops::ControlFlow;
use std::time::Instant;

fn main() {
    let n: usize = match std::env::args().nth(1).map(|s| s.parse()) {
        None => 110,
        Some(Ok(n)) if n >= 4 => n,
        Some(_) => {
            eprintln!("usage: hanging_sheet [PARTICLES_PER_SIDE >= 4]");
            std::process::exit(2);
        }
    };
    let mesh = match GridBuilder::new(n, n).size(1.0, 1.0).build() {
        Ok(mesh) => mesh,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    };
    let g = mesh.grid().expect("a grid");
    let build = Instant::now();
    let mut sim = match SimulationBuilder::new(mesh, Fabric::cotton_like().with_damping(2e-3).with_drag(0.05))
        .pin(Pin::fixed(g.index(0, n - 1)))
        .pin(Pin::fixed(g.index(n - 1, n - 1)))
        .build()
    {
        Ok(sim) => sim,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    };
    println!(
        "{} particles, built in {:.0} ms",
        n * n,
        build.elapsed().as_secs_f64() * 1e3
    );
    println!("| iterations | stretch horizontal (warp) | stretch vertical (weft) | p99 warp | p99 weft | ms/step (median) | CG iterations (median) |");
    println!("|---|---|---|---|---|---|---|");
    let checkpoints = [100u64, 200, 500, 1000, 2000];
    let criteria = RestCriteria {
        max_time_step: None,
        tolerance: 1e-5,
        consecutive_steps: 10,
        max_steps: 2000,
        moving_fraction: 0.0,
    };
    let (mut times, mut iterations) = (Vec::new(), Vec::new());
    let report = |sim: &cloth::Simulation, times: &[f64], iterations: &[usize]| {
        let grid = GridStretch::new(sim.mesh(), sim.positions()).expect("a grid");
        let strain = StrainReport::new(sim.mesh(), sim.positions());
        println!(
            "| {} | {:.3} % | {:.3} % | {:.3} % | {:.3} % | {:.1} | {} |",
            sim.step_count(),
            grid.horizontal,
            grid.vertical,
            strain.p99_warp,
            strain.p99_weft,
            median(times),
            median_usize(iterations)
        );
        (grid, strain)
    };
    let started = Instant::now();
    let outcome = sim.run_to_rest_with(&criteria, |sim, s| {
        times.push((s.assembly_seconds + s.solve_seconds) * 1e3);
        iterations.push(s.cg_iterations);
        if checkpoints.contains(&s.step) {
            report(sim, &times, &iterations);
        }
        ControlFlow::Continue(())
    });
    let (grid, strain) = report(&sim, &times, &iterations);
    let (reason, error) = match &outcome {
        Ok(out) => (
            match out.reason {
                StopReason::AtRest => "at_rest",
                StopReason::StepLimit => "step_limit",
                StopReason::Stopped => "stopped",
            },
            String::new(),
        ),
        Err(e) => ("error", e.to_string()),
    };
    println!(
        "{{\"particles\":{},\"steps\":{},\"stopped\":\"{reason}\",\"error\":\"{error}\",\"seconds\":{:.2},\"median_ms_per_step\":{:.2},\"median_cg_iterations\":{},\"max_stretch_warp_percent\":{:.4},\"max_stretch_weft_percent\":{:.4},\"p99_warp_percent\":{:.4},\"p99_weft_percent\":{:.4}}}",
        n * n,
        sim.step_count(),
        started.elapsed().as_secs_f64(),
        median(&times),
        median_usize(&iterations),
        grid.horizontal,
        grid.vertical,
        strain.p99_warp,
        strain.p99_weft
    );
    if outcome.is_err() {
        std::process::exit(1);
    }
}

fn median(v: &[f64]) -> f64 {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    s.get(s.len() / 2).copied().unwrap_or(0.0)
}

fn median_usize(v: &[usize]) -> usize {
    let mut s = v.to_vec();
    s.sort_unstable();
    s.get(s.len() / 2).copied().unwrap_or(0)
}
