//! The subcommands: each reads its input, calls the library, and says what happened.

use crate::failure::Failure;
use crate::progress::{Progress, Verbosity};
use cloth::garment::mannequin::{Mannequin, Measurements};
use cloth::presets::FabricLibrary;
use cloth::run_folder::{claim_output_folder, FolderRun, RunFolderError};
use cloth::scene_file::{RunOutcome, SceneFile};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// `cloth run`: prepare, simulate, write the outputs. A run that fails or is interrupted
/// still writes its last good state and a report that says what happened.
pub fn run(
    scene_path: &Path,
    out: Option<PathBuf>,
    force: bool,
    verbosity: Verbosity,
) -> Result<(), Failure> {
    let (scene, dir) = SceneFile::from_path(scene_path).map_err(Failure::input)?;
    let file = scene_path.display().to_string();
    let out = out.unwrap_or_else(|| scene_path.with_extension("out"));
    claim_output_folder(&out, force)
        .map_err(|e| Failure::input(format!("{e}: pass --force to write into it")))?;
    let prepared = scene.prepare(&file, &dir).map_err(Failure::input)?;
    for w in &prepared.warnings {
        eprintln!("warning: {w}");
    }
    let interrupted = catch_interrupts()?;
    let mut progress = Progress::new(verbosity, interrupted);
    let run = prepared.run_into(&scene, &out, &mut progress);
    progress.finish();
    let FolderRun { result, written } = run.map_err(|e| match e {
        RunFolderError::Write { .. } => Failure::run(e),
        e => Failure::input(e),
    })?;
    let r = &result.report;
    if verbosity != Verbosity::Quiet {
        println!(
            "{} particles, max warp {:.2} %, weft {:.2} %, deepest penetration {:.1e} m, {:.2} s",
            r.particles, r.strain.max_warp, r.strain.max_weft, r.deepest_penetration, r.total_seconds
        );
        for p in written {
            println!("wrote {}", p.display());
        }
    }
    let report = out.join("report.json");
    match &r.outcome {
        RunOutcome::Finished => Ok(()),
        RunOutcome::Interrupted { stage, step } => Err(Failure {
            message: format!(
                "interrupted at {stage} step {step}: the state reached is in '{}'",
                out.display()
            ),
            status: 130,
        }),
        RunOutcome::Failed { stage, step, error } => Err(Failure::run(format!(
            "{error} (the state after {stage} step {step} and the report are in '{}')",
            report.display()
        ))),
    }
}

/// A flag that Ctrl-C and SIGTERM (a batch scheduler, `timeout`) raise, for the run to
/// stop at its next step and write what it has; a second signal quits at once.
pub fn catch_interrupts() -> Result<Arc<AtomicBool>, Failure> {
    let interrupted = Arc::new(AtomicBool::new(false));
    let flag = interrupted.clone();
    ctrlc::set_handler(move || {
        if flag.swap(true, Ordering::Relaxed) {
            std::process::exit(130);
        }
    })
    .map_err(|e| Failure::run(format!("cannot catch Ctrl-C: {e}")))?;
    Ok(interrupted)
}

/// `cloth check`: everything `run` would read and build, without simulating.
pub fn check(scene_path: &Path) -> Result<(), Failure> {
    let (scene, dir) = SceneFile::from_path(scene_path).map_err(Failure::input)?;
    let prepared = scene
        .prepare(&scene_path.display().to_string(), &dir)
        .map_err(Failure::input)?;
    for w in &prepared.warnings {
        eprintln!("warning: {w}");
    }
    let what = match &prepared.cloth {
        cloth::scene_file::PreparedCloth::Garment { garment, .. } => format!(
            "a garment of {} panels, {} seams, {} particles before sewing",
            garment.panel_names.len(),
            garment.seams.len(),
            garment.mesh.vertex_count()
        ),
        cloth::scene_file::PreparedCloth::Sheet { .. } => "a sheet".to_string(),
    };
    println!(
        "{}: ok: {what}, {} bodies",
        scene_path.display(),
        prepared.bodies.bodies().len()
    );
    Ok(())
}

/// `cloth fabrics [NAME]`.
pub fn fabrics(name: Option<&str>) -> Result<(), Failure> {
    let library = FabricLibrary::builtin();
    match name {
        None => {
            for p in library.presets() {
                println!("{:<24} {}", p.name, p.description);
            }
        }
        Some(name) => {
            let preset = library.get(name).map_err(Failure::input)?;
            println!(
                "{}: {}\norigin: {}",
                preset.name, preset.description, preset.origin
            );
            let json = serde_json::to_string_pretty(&preset.fabric).map_err(Failure::run)?;
            println!("SI values:\n{json}");
            println!(
                "membrane secant stiffness at 1 % strain: {:.1} N/m",
                preset.fabric.membrane_stiffness()
            );
            let kes = cloth::KesMeasurement::from_fabric(&preset.fabric);
            println!(
                "KES-F units (as the model reads them):\n  W {:.3} mg/cm2, T {:.3} mm, MIU {:.3}",
                kes.w,
                kes.t,
                kes.miu.unwrap_or(f64::NAN)
            );
            for (name, d) in [("warp (1)", &kes.warp), ("weft (2)", &kes.weft)] {
                println!(
                    "  {name}: EMT {:.3} %, LT {:.3}, WT {:.3} gf cm/cm2, G {:.3} gf/(cm deg), B {:.4} gf cm2/cm",
                    d.emt, d.lt, d.wt, d.g, d.b
                );
            }
            for u in &preset.unused {
                println!("  unused {} = {}: {}", u.field, u.value, u.reason);
            }
        }
    }
    Ok(())
}

/// `cloth bench`: one JSON object on stdout.
pub fn bench(steps: usize, quick: bool, scaling: bool) -> Result<(), Failure> {
    if steps == 0 {
        return Err(Failure::input("--steps must be at least 1"));
    }
    let results = cloth::bench::standard_benchmarks(steps, quick).map_err(Failure::run)?;
    let scaling = match scaling {
        true => Some(cloth::bench::scaling_benchmarks(steps, quick).map_err(Failure::run)?),
        false => None,
    };
    let json = serde_json::json!({
        "threads": cloth::bench::threads(),
        "quick": quick,
        "scenes": results.scenes,
        "to_rest": results.to_rest,
        "scaling": scaling,
    });
    println!("{json}");
    Ok(())
}

/// `cloth mannequin ... -o FILE`.
pub fn mannequin(measurements: Measurements, output: &Path) -> Result<(), Failure> {
    let mannequin = Mannequin::new(&measurements).map_err(Failure::input)?;
    mannequin
        .write_obj(output)
        .map_err(|e| Failure::run(format!("cannot write '{}': {e}", output.display())))?;
    let lm = mannequin.landmarks();
    println!(
        "wrote {}: bust at {:.3} m, waist at {:.3} m, hip at {:.3} m",
        output.display(),
        lm.bust_z,
        lm.waist_z,
        lm.hip_z
    );
    Ok(())
}
