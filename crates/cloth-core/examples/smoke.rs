use cloth_core::*;
fn main() {
    let n: usize = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(30);
    let mesh = GridBuilder::new(n, n).size(1.0, 1.0).build().unwrap();
    let g = mesh.grid().unwrap();
    let fabric = Fabric::cotton_like().with_damping(0.0);
    let mut sim = SimulationBuilder::new(mesh, fabric)
        .pin(Pin::fixed(g.index(0, n - 1)))
        .pin(Pin::fixed(g.index(n - 1, n - 1)))
        .build()
        .unwrap();
    println!("kappa {:?}", sim.bending_calibration());
    for k in 0..200 {
        let s = sim.step().unwrap();
        if k % 20 == 0 {
            println!("{:?}", (s.step, s.cg_iterations, s.cg_residual, s.assembly_seconds*1e3, s.solve_seconds*1e3, s.max_speed, s.kinetic_energy));
        }
    }
    let gs = GridStretch::new(sim.mesh(), sim.positions()).unwrap();
    println!("{gs:?}");
}
