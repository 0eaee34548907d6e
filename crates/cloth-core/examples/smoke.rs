//! Quick timing of the benchmark scene: a 1 m sheet of n x n particles hanging from two corners.
use cloth_core::*;
fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(110);
    let tol: f64 = std::env::args()
        .nth(2)
        .and_then(|s| s.parse().ok())
        .unwrap_or(1e-4);
    let mesh = GridBuilder::new(n, n).size(1.0, 1.0).build().unwrap();
    let g = mesh.grid().unwrap();
    let mut settings = SolverSettings::default();
    settings.pcg.rel_tolerance = tol;
    let t0 = std::time::Instant::now();
    let mut sim = SimulationBuilder::new(mesh, Fabric::cotton_like())
        .settings(settings)
        .pin(Pin::fixed(g.index(0, n - 1)))
        .pin(Pin::fixed(g.index(n - 1, n - 1)))
        .build()
        .unwrap();
    println!(
        "build {:.1} ms, kappa {:?}",
        t0.elapsed().as_secs_f64() * 1e3,
        sim.bending_calibration()
    );
    for k in 0..120 {
        let t = std::time::Instant::now();
        let s = sim.step().unwrap();
        if k % 20 == 0 {
            println!(
                "step {} total {:.1} ms: assembly {:.1} ms, solve {:.1} ms, cg {} res {:.1e}, vmax {:.2}",
                s.step,
                t.elapsed().as_secs_f64() * 1e3,
                s.assembly_seconds * 1e3,
                s.solve_seconds * 1e3,
                s.cg_iterations,
                s.cg_residual,
                s.max_speed
            );
        }
    }
    println!("{:?}", GridStretch::new(sim.mesh(), sim.positions()).unwrap());
}
