//! The self-collision scenes, stepped for a while with a line of figures every few steps:
//! contacts, impacts, CG iterations, time, and the cloth's intersection count at every step.
//! The cloth at the end is written as OBJ.
//!
//!     cargo run --release --example self_collision -- fold|stack|throw [STEPS] [OUT_DIR]

use cloth::formats::obj::write_cloth_obj;
use cloth_fixtures::{ContactScene, FoldingStrip, SheetOntoSheet, StackedSheets};
use std::path::PathBuf;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let name = args.first().map(String::as_str).unwrap_or("fold");
    let steps: u64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(300);
    let out = PathBuf::from(args.get(2).map(String::as_str).unwrap_or("target/self_collision"));
    let scene: ContactScene = match name {
        "fold" => FoldingStrip::default().build(),
        "stack" => StackedSheets::default().build(),
        "throw" => SheetOntoSheet::default().build(),
        _ => {
            eprintln!("unknown scene `{name}`: choose fold, stack or throw");
            std::process::exit(2);
        }
    }
    .unwrap_or_else(|e| {
        eprintln!("{e}");
        std::process::exit(1)
    });
    let mut sim = scene.simulation;
    let start = Instant::now();
    let mut worst = 0;
    let mut closest = (f64::INFINITY, 0);
    for _ in 0..steps {
        let t = Instant::now();
        let s = match sim.step() {
            Ok(s) => s,
            Err(e) => {
                eprintln!("{e}");
                break;
            }
        };
        let ms = t.elapsed().as_secs_f64() * 1e3;
        let crossing = sim.self_intersections();
        worst = worst.max(crossing.count);
        if let Some(d) = sim.closest_self_approach(0.01) {
            if d < closest.0 {
                closest = (d, s.step);
            }
        }
        if s.step % 10 == 0 || crossing.count > 0 || s.self_unresolved > 0 {
            println!(
                "step {:4}: contacts {:5} impacts {:4} zone {:4} frozen {:3} unresolved {:2} | cg {:4} | {:6.1} ms (self {:5.1}) | max speed {:.3} | intersections {} {:?}",
                s.step,
                s.self_contacts,
                s.self_impacts,
                s.self_zone_particles,
                s.self_frozen,
                s.self_unresolved,
                s.cg_iterations,
                ms,
                s.self_collision_seconds * 1e3,
                s.max_speed,
                crossing.count,
                crossing.first
            );
        }
    }
    println!(
        "closest approach at the end {:?} mm, over the run {:.3} mm at step {}",
        sim.closest_self_approach(0.01).map(|d| d * 1e3),
        closest.0 * 1e3,
        closest.1
    );
    println!(
        "{name}: {} particles, {} steps in {:.1} s, most intersections at a step {worst}, depth in body {:.2e}",
        sim.mesh().vertex_count(),
        sim.step_count(),
        start.elapsed().as_secs_f64(),
        scene.bodies.deepest_inside(sim.time(), sim.positions()).0
    );
    std::fs::create_dir_all(&out).ok();
    let path = out.join(format!("{name}.obj"));
    if let Err(e) = write_cloth_obj(&path, sim.positions(), sim.mesh().triangles()) {
        eprintln!("{}: {e}", path.display());
    }
}
