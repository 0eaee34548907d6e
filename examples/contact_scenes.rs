//! The contact scenes, run to rest (or a time limit), with a line of figures every few
//! steps and a JSON summary; the cloth and the bodies at the end are written as OBJ files
//! to look at.
//!
//!     cargo run --release --example contact_scenes -- SCENE [PARTICLES_PER_SIDE] [OUT_DIR]
//!
//! SCENE is one of sphere, table, turning, corner, plate.

use cloth::formats::obj::write_cloth_obj;
use cloth::{RestCriteria, StopReason, StrainReport};
use cloth_fixtures::{
    ContactScene, ContactSceneError, CubeCorner, FallingPlate, SphereDrop, Tablecloth, TurningSphere,
};
use std::ops::ControlFlow;
use std::path::PathBuf;
use std::time::Instant;

fn build(name: &str, n: Option<usize>) -> Result<(ContactScene, f64), ContactSceneError> {
    Ok(match name {
        "sphere" => {
            let mut s = SphereDrop::default();
            s.particles_per_side = n.unwrap_or(s.particles_per_side);
            (s.build()?, 20.0)
        }
        "table" => {
            let mut s = Tablecloth::default();
            s.particles_per_side = n.unwrap_or(s.particles_per_side);
            (s.build()?, 20.0)
        }
        "turning" => {
            let mut s = TurningSphere::default();
            s.particles_per_side = n.unwrap_or(s.particles_per_side);
            (s.build()?, 6.0)
        }
        "corner" => {
            let mut s = CubeCorner::default();
            s.particles_per_side = n.unwrap_or(s.particles_per_side);
            (s.build()?, 10.0)
        }
        "plate" => {
            let mut s = FallingPlate::default();
            s.particles_per_side = n.unwrap_or(s.particles_per_side);
            (s.build()?, 3.0)
        }
        _ => {
            eprintln!("unknown scene `{name}`: choose sphere, table, turning, corner or plate");
            std::process::exit(2);
        }
    })
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let name = args.first().map(String::as_str).unwrap_or("sphere");
    let n = match args.get(1).map(|s| s.parse::<usize>()) {
        None => None,
        Some(Ok(n)) if n >= 3 => Some(n),
        Some(_) => {
            eprintln!("PARTICLES_PER_SIDE must be an integer of at least 3");
            std::process::exit(2);
        }
    };
    let out_dir = PathBuf::from(args.get(2).cloned().unwrap_or_else(|| "target/scenes".into()));
    let (mut scene, seconds) = match build(name, n) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    };
    let h = scene.simulation.settings().time_step;
    let max_steps = (seconds / h).round() as u64;
    // A moving body never lets the cloth rest: run those for the time limit.
    let criteria = RestCriteria {
        max_time_step: None,
        tolerance: 1e-5,
        consecutive_steps: 10,
        max_steps,
        moving_fraction: 0.0,
    };
    let start = Instant::now();
    let mut deepest: f64 = 0.0;
    let mut step_ms = Vec::new();
    let bodies = scene.bodies.clone();
    let outcome = scene.simulation.run_to_rest_with(&criteria, |sim, stats| {
        deepest = deepest.max(bodies.deepest_inside(sim.time(), sim.positions()).0);
        step_ms.push((stats.assembly_seconds + stats.solve_seconds + stats.contact_seconds) * 1e3);
        if stats.step % 60 == 0 {
            println!(
                "t = {:6.3} s  contacts {:5}  corrected {:4} (crossed {:3})  features {:3}  max speed {:.2e} m/s  CG {:4}  {:.1} ms",
                stats.time,
                stats.contacts,
                stats.contact_corrections,
                stats.crossings,
                stats.feature_corrections,
                stats.max_speed,
                stats.cg_iterations,
                step_ms.last().copied().unwrap_or(0.0),
            );
        }
        ControlFlow::Continue(())
    });
    let outcome = match outcome {
        Ok(o) => o,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    };
    step_ms.sort_by(f64::total_cmp);
    let median = step_ms.get(step_ms.len() / 2).copied().unwrap_or(0.0);
    let strain = StrainReport::new(scene.simulation.mesh(), scene.simulation.positions());
    let at_rest = outcome.reason == StopReason::AtRest;
    println!(
        "{{\"scene\": \"{name}\", \"particles\": {}, \"at_rest\": {at_rest}, \"steps\": {}, \"simulated_s\": {:.3}, \"wall_s\": {:.2}, \"median_step_ms\": {median:.2}, \"deepest_penetration_mm\": {:.4}, \"max_warp_strain_pct\": {:.3}, \"max_weft_strain_pct\": {:.3}}}",
        scene.simulation.positions().len(),
        outcome.steps,
        scene.simulation.time(),
        start.elapsed().as_secs_f64(),
        deepest * 1e3,
        strain.max_warp,
        strain.max_weft,
    );
    let written = std::fs::create_dir_all(&out_dir).and_then(|_| {
        let sim = &scene.simulation;
        write_cloth_obj(
            &out_dir.join(format!("{name}_cloth.obj")),
            sim.positions(),
            sim.mesh().triangles(),
        )?;
        for (k, body) in scene.bodies.bodies().iter().enumerate() {
            body.surface_at(scene.simulation.time())
                .write_obj(&out_dir.join(format!("{name}_body{k}.obj")))?;
        }
        Ok(())
    });
    match written {
        Ok(()) => println!("wrote {}/{name}_*.obj", out_dir.display()),
        Err(e) => eprintln!("could not write the OBJ files to {}: {e}", out_dir.display()),
    }
}
