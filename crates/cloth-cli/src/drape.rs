//! `cloth drape`: many patterns on one body, each into a folder of its own, with one
//! summary. The work is the library's (`cloth::drape`); this file parses, schedules the
//! patterns over `--jobs` threads, shows progress and catches Ctrl-C and SIGTERM.

use crate::failure::Failure;
use cloth::collide::{SurfaceOptions, TriSurface};
use cloth::drape::{find_patterns, write_summary, DrapeRequest, PatternInput, SummaryEntry};
use cloth::presets::FabricLibrary;
use cloth::run_folder::claim_output_folder;
use cloth::scene_file::{RunObserver, UpAxis};
use cloth::{Interrupt, Simulation, StepStats};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

#[derive(Clone, Copy, clap::ValueEnum)]
pub enum Axis {
    Y,
    Z,
}

#[derive(clap::Args)]
pub struct DrapeArgs {
    /// Patterns (our TOML or GarmentCode JSON), or folders to search for them.
    #[arg(required = true)]
    pub patterns: Vec<PathBuf>,
    /// The body to drape on (OBJ, STL, PLY, glTF, GLB).
    #[arg(long)]
    pub body: PathBuf,
    /// The body file's up axis (GarmentCode's and SMPL's bodies are y-up; default: y for
    /// glTF, z for the other formats).
    #[arg(long, value_enum)]
    pub body_up_axis: Option<Axis>,
    /// The up axis of the OBJ and PLY outputs (default z, the engine's; y for Blender's,
    /// Maya's, Houdini's and Marvelous Designer's importers, and the frame of a y-up body).
    #[arg(long, value_enum)]
    pub up_axis: Option<Axis>,
    /// A fabric preset (`cloth fabrics` lists them).
    #[arg(long, default_value = "cotton_poplin")]
    pub fabric: String,
    /// Target edge length of the cloth mesh, m.
    #[arg(long, default_value_t = cloth::garment::garment::DEFAULT_EDGE_LENGTH)]
    pub edge_length: f64,
    /// The body's contact layer, 3 mm, thinned down to this where the body is flat, m: at
    /// each point, this plus the dip of the cloth's longest edges over the body's curve
    /// there (3 mm keeps it uniform).
    #[arg(long, default_value_t = cloth::drape::DEFAULT_BODY_MIN_THICKNESS)]
    pub min_thickness: f64,
    /// The folder for the outputs: one folder per pattern, and summary.json, summary.md.
    #[arg(long)]
    pub out: PathBuf,
    /// Run every pattern again, also those finished by an earlier batch, and write into
    /// folders that hold something else.
    #[arg(long)]
    pub force: bool,
    /// Patterns draped at once (the cores shared out among them).
    #[arg(long, default_value_t = 1)]
    pub jobs: usize,
    /// Stop a pattern after this many seconds: its state and report are kept, and it
    /// counts as failed.
    #[arg(long)]
    pub time_limit: Option<f64>,
    /// Print nothing but errors and the final count.
    #[arg(long)]
    pub quiet: bool,
    /// Drape on a Dask cluster, given its scheduler's address (tcp://host:8786), through
    /// the Python package (`pip install "cloth-drape[dask]"`; the interpreter is $CLOTH_PYTHON,
    /// else python3): each job carries its pattern and the body, so the workers need no
    /// shared file system, and the outputs come back into --out.
    #[arg(long, value_name = "ADDRESS")]
    pub dask: Option<String>,
}

/// One pattern's folder, and whether a run may write into it.
fn folder_for(out: &Path, pattern: &PatternInput, force: bool) -> Result<PathBuf, String> {
    let folder = out.join(&pattern.name);
    // A folder of an earlier drape (it holds the scene written for it) is ours to redo.
    let ours = folder.join("scene.toml").exists();
    if !ours && !force {
        claim_output_folder(&folder, false).map_err(|e| format!("{e}: pass --force to write into it"))?;
    }
    Ok(folder)
}

/// Sees one pattern's run: gives it the interrupt (Ctrl-C and the time limit, which the
/// simulation checks inside each step), and tells the progress display where it is.
struct Watch<'a> {
    interrupted: &'a Arc<AtomicBool>,
    deadline: Option<Instant>,
    status: &'a Mutex<Vec<String>>,
    slot: usize,
    name: &'a str,
    last: Instant,
}

impl RunObserver for Watch<'_> {
    fn interrupt(&self) -> Interrupt {
        let interrupt = Interrupt::new(self.interrupted.clone());
        match self.deadline {
            Some(d) => interrupt.with_deadline(d),
            None => interrupt,
        }
    }

    fn step(&mut self, stage: &'static str, _sim: &Simulation, stats: &StepStats) -> ControlFlow<()> {
        if self.last.elapsed() >= Duration::from_millis(250) {
            self.last = Instant::now();
            if let Ok(mut s) = self.status.lock() {
                s[self.slot] = format!("{} {stage} {}", self.name, stats.step);
            }
        }
        ControlFlow::Continue(())
    }
}

/// Drapes one pattern into its folder and says how it ended.
fn drape_one(
    pattern: &PatternInput,
    request: &DrapeRequest,
    args: &DrapeArgs,
    interrupted: &Arc<AtomicBool>,
    status: &Mutex<Vec<String>>,
    slot: usize,
) -> SummaryEntry {
    let start = Instant::now();
    let folder = match folder_for(&args.out, pattern, args.force) {
        Ok(f) => f,
        Err(reason) => return SummaryEntry::refused(&pattern.name, &pattern.path, reason, 0.0),
    };
    if !args.force && request.finished_in(&folder) {
        if let Some(entry) = SummaryEntry::from_report(&pattern.name, &pattern.path, &folder, true) {
            return entry;
        }
    }
    let refused = |reason: String| {
        SummaryEntry::refused(
            &pattern.name,
            &pattern.path,
            reason,
            start.elapsed().as_secs_f64(),
        )
    };
    if let Err(e) = std::fs::create_dir_all(&folder) {
        return refused(format!("cannot create '{}': {e}", folder.display()));
    }
    let _ = std::fs::remove_file(folder.join(cloth::drape::FINISHED_FILE));
    let scene_path = folder.join("scene.toml");
    if let Err(e) = std::fs::write(&scene_path, request.scene_toml(pattern)) {
        return refused(format!("cannot write '{}': {e}", scene_path.display()));
    }
    let scene = match request.scene(pattern) {
        Ok(s) => s,
        Err(e) => return refused(e.to_string()),
    };
    let prepared = match scene.prepare(&scene_path.display().to_string(), &folder) {
        Ok(p) => p,
        Err(e) => return refused(e.to_string()),
    };
    let mut watch = Watch {
        interrupted,
        deadline: args.time_limit.map(|s| start + Duration::from_secs_f64(s)),
        status,
        slot,
        name: &pattern.name,
        last: Instant::now(),
    };
    if let Err(e) = prepared.run_into(&scene, &folder, &mut watch) {
        return refused(e.to_string());
    }
    let Some(mut entry) = SummaryEntry::from_report(&pattern.name, &pattern.path, &folder, false) else {
        return refused(format!("its report in '{}' cannot be read", folder.display()));
    };
    // Interrupted, and not by Ctrl-C: the deadline passed.
    if entry.outcome == "interrupted" && !interrupted.load(Ordering::Relaxed) {
        entry.stopped_by_time_limit(args.time_limit.unwrap_or(0.0));
    }
    if entry.finished() {
        if let Err(e) = request.mark_finished(&folder) {
            entry.outcome = "failed".into();
            entry.failure = Some(format!("cannot mark '{}' finished: {e}", folder.display()));
        }
    }
    entry
}

/// The cores a batch shares out: `RAYON_NUM_THREADS` when set, as rayon's own pool would
/// read it, else the machine's.
fn cores() -> usize {
    std::env::var("RAYON_NUM_THREADS")
        .ok()
        .and_then(|n| n.parse::<usize>().ok())
        .filter(|&n| n > 0)
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
}

/// The threads of one pattern's run by job `slot` while `running` patterns run at once:
/// the cores shared out among them (the first jobs get any left over; at least one
/// each), so the last patterns of a batch get the cores the others are done with. Jobs
/// sharing one pool waited on each other: a job's thread blocked in a parallel loop
/// steals the other job's work, its whole step at times, and goes on with its own loop
/// only when that is done.
fn pattern_pool(slot: usize, running: usize) -> Result<rayon::ThreadPool, String> {
    let (cores, running) = (cores(), running.max(1));
    let threads = (cores / running + usize::from(slot % running < cores % running)).max(1);
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .thread_name(move |i| format!("cloth-job{slot}-{i}"))
        .build()
        .map_err(|e| format!("cannot start {threads} threads for its run: {e} (try a smaller --jobs)"))
}

/// The line said when a pattern is done.
fn done_line(entry: &SummaryEntry, done: usize, total: usize) -> String {
    let what = if entry.skipped {
        "finished earlier".to_string()
    } else if entry.finished() {
        format!(
            "finished in {:.1} s: {} particles, sewn in {} steps, draped in {} ({}), max warp {:.2} %, weft {:.2} %",
            entry.seconds,
            entry.particles.unwrap_or(0),
            entry.sewing_steps.unwrap_or(0),
            entry.draping_steps.unwrap_or(0),
            entry.drape_ended.as_deref().unwrap_or("?"),
            entry.max_warp.unwrap_or(f64::NAN),
            entry.max_weft.unwrap_or(f64::NAN)
        )
    } else {
        format!(
            "{} after {:.1} s: {}",
            entry.outcome,
            entry.seconds,
            entry.failure.as_deref().unwrap_or("")
        )
    };
    format!("[{done}/{total}] {}: {what}", entry.name)
}

/// `cloth drape`.
/// `cloth drape --dask`: the same drape run by `python -m cloth drape` on the cluster,
/// its exit status the command's.
fn drape_on_dask(args: &DrapeArgs, address: &str) -> Result<(), Failure> {
    for (given, flag) in [
        (args.force, "--force"),
        (args.time_limit.is_some(), "--time-limit"),
        (args.jobs != 1, "--jobs"),
    ] {
        if given {
            return Err(Failure::input(format!(
                "{flag} is not available with --dask (the cluster's workers decide how many run at once)"
            )));
        }
    }
    let python = std::env::var_os("CLOTH_PYTHON").unwrap_or_else(|| "python3".into());
    let shown = python.to_string_lossy().into_owned();
    let found = std::process::Command::new(&python)
        .args(["-c", "import cloth.batch, distributed"])
        .output();
    match found {
        Ok(o) if o.status.success() => {}
        Ok(o) => {
            return Err(Failure::input(format!(
                "--dask runs through the Python package, which {shown} cannot import:                  pip install \"cloth-drape[dask]\" (or set CLOTH_PYTHON): {}",
                String::from_utf8_lossy(&o.stderr).trim()
            )))
        }
        Err(e) => {
            return Err(Failure::input(format!(
                "--dask runs through the Python package, but {shown} cannot be started: {e} \
                 (set CLOTH_PYTHON to a Python with cloth-drape[dask])"
            )))
        }
    }
    let mut command = std::process::Command::new(&python);
    command.args(["-m", "cloth", "drape"]).args(&args.patterns);
    command.arg("--body").arg(&args.body).arg("--out").arg(&args.out);
    let axis = |a: Axis| match a {
        Axis::Y => "y",
        Axis::Z => "z",
    };
    if let Some(a) = args.body_up_axis {
        command.args(["--body-up-axis", axis(a)]);
    }
    if let Some(a) = args.up_axis {
        command.args(["--up-axis", axis(a)]);
    }
    command.args(["--fabric", &args.fabric]);
    command.args(["--edge-length", &args.edge_length.to_string()]);
    command.args(["--min-thickness", &args.min_thickness.to_string()]);
    command.args(["--dask", address]);
    if args.quiet {
        command.arg("--quiet");
    }
    let status = command
        .status()
        .map_err(|e| Failure::input(format!("cannot start {shown}: {e}")))?;
    match status.code() {
        Some(0) => Ok(()),
        Some(2) => Err(Failure::input("the Python drape refused its input (above)")),
        _ => Err(Failure::run(
            "not every pattern finished on the cluster (see the summary)",
        )),
    }
}

pub fn drape(args: DrapeArgs) -> Result<(), Failure> {
    if let Some(address) = &args.dask {
        return drape_on_dask(&args, address);
    }
    if !(args.edge_length.is_finite() && args.edge_length > 0.0) {
        return Err(Failure::input(format!(
            "--edge-length {} must be a positive length in m",
            args.edge_length
        )));
    }
    if args.jobs == 0 {
        return Err(Failure::input("--jobs must be at least 1"));
    }
    if let Some(t) = args.time_limit {
        if !(t.is_finite() && t > 0.0) {
            return Err(Failure::input(format!(
                "--time-limit {t} must be a positive number of seconds"
            )));
        }
    }
    let body_min_thickness = cloth::drape::body_min_thickness(args.min_thickness)
        .map_err(|e| Failure::input(format!("--min-thickness {e}")))?;
    FabricLibrary::builtin()
        .fabric(&args.fabric)
        .map_err(Failure::input)?;
    let patterns = find_patterns(&args.patterns).map_err(Failure::input)?;
    // The body once, up front: a bad one is the batch's input error, not every pattern's.
    let body = std::path::absolute(&args.body)
        .map_err(|e| Failure::input(format!("{}: {e}", args.body.display())))?;
    let surface = TriSurface::read(&body, &SurfaceOptions::default()).map_err(Failure::input)?;
    if !args.quiet {
        for d in surface.defects() {
            eprintln!("warning: {}: {d}", body.display());
        }
    }
    let axis = |a| match a {
        Axis::Y => UpAxis::Y,
        Axis::Z => UpAxis::Z,
    };
    let request = DrapeRequest {
        body,
        body_up_axis: args.body_up_axis.map(axis),
        fabric: args.fabric.clone(),
        edge_length: args.edge_length,
        body_min_thickness,
        up_axis: args.up_axis.map(axis),
    };
    std::fs::create_dir_all(&args.out).map_err(|e| {
        Failure::input(format!(
            "cannot create output folder '{}': {e}",
            args.out.display()
        ))
    })?;

    let interrupted = crate::commands::catch_interrupts()?;

    let total = patterns.len();
    let bar = (!args.quiet && std::io::stderr().is_terminal()).then(|| {
        let bar = ProgressBar::with_draw_target(Some(total as u64), ProgressDrawTarget::stderr());
        bar.set_style(
            ProgressStyle::with_template("[{bar:24}] {pos}/{len} patterns  {elapsed}  {msg}")
                .expect("the template is valid")
                .progress_chars("=> "),
        );
        bar.enable_steady_tick(Duration::from_millis(250));
        bar
    });
    let say = |line: String| match &bar {
        Some(b) => b.println(line),
        None if !args.quiet => eprintln!("{line}"),
        None => {}
    };
    let jobs = args.jobs.min(total);
    let status = Mutex::new(vec![String::new(); jobs]);
    let next = Mutex::new(0usize);
    let entries: Mutex<Vec<Option<SummaryEntry>>> = Mutex::new(vec![None; total]);
    let summary_error: Mutex<Option<String>> = Mutex::new(None);
    let live = AtomicUsize::new(jobs);
    let write = |entries: &[Option<SummaryEntry>]| {
        let written: Vec<SummaryEntry> = entries.iter().flatten().cloned().collect();
        if let Err(e) = write_summary(&args.out, &written) {
            *summary_error.lock().unwrap_or_else(|e| e.into_inner()) = Some(format!(
                "cannot write the summary in '{}': {e}",
                args.out.display()
            ));
        }
    };
    std::thread::scope(|scope| {
        for slot in 0..jobs {
            let (request, args, interrupted) = (&request, &args, &interrupted);
            let (status, next, entries, patterns, bar, say, write, live) =
                (&status, &next, &entries, &patterns, &bar, &say, &write, &live);
            scope.spawn(move || {
                // Counted down however the worker ends, so the display never waits forever.
                let _alive = Alive(live);
                loop {
                    if interrupted.load(Ordering::Relaxed) {
                        break;
                    }
                    let k = {
                        let mut n = next.lock().unwrap_or_else(|e| e.into_inner());
                        let k = *n;
                        *n += 1;
                        k
                    };
                    let Some(pattern) = patterns.get(k) else { break };
                    // A bug in one pattern's run must not take the batch down with it.
                    let entry = match pattern_pool(slot, jobs.min(total - k)) {
                        Ok(pool) => std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                            pool.install(|| drape_one(pattern, request, args, interrupted, status, slot))
                        }))
                        .unwrap_or_else(|_| {
                            SummaryEntry::refused(
                                &pattern.name,
                                &pattern.path,
                                "internal error: the run panicked".into(),
                                0.0,
                            )
                        }),
                        Err(e) => SummaryEntry::refused(&pattern.name, &pattern.path, e, 0.0),
                    };
                    let mut all = entries.lock().unwrap_or_else(|e| e.into_inner());
                    all[k] = Some(entry.clone());
                    let done = all.iter().flatten().count();
                    write(&all);
                    drop(all);
                    say(done_line(&entry, done, total));
                    if let Some(b) = bar {
                        b.inc(1);
                    }
                }
            });
        }
        if let Some(b) = &bar {
            while live.load(Ordering::Relaxed) > 0 {
                let line = status.lock().map(|s| s.join("  ")).unwrap_or_default();
                b.set_message(line);
                std::thread::sleep(Duration::from_millis(250));
            }
        }
    });
    if let Some(b) = &bar {
        b.finish_and_clear();
    }
    let entries: Vec<SummaryEntry> = entries
        .into_inner()
        .unwrap_or_else(|e| e.into_inner())
        .into_iter()
        .flatten()
        .collect();
    if let Some(e) = summary_error.into_inner().unwrap_or_else(|e| e.into_inner()) {
        return Err(Failure::run(e));
    }
    let finished = entries.iter().filter(|e| e.finished()).count();
    println!(
        "{finished} of {total} patterns finished; summary in '{}'",
        args.out.join(cloth::drape::SUMMARY_MD).display()
    );
    if interrupted.load(Ordering::Relaxed) {
        return Err(Failure {
            message: format!("interrupted after {} of {total} patterns", entries.len()),
            status: 130,
        });
    }
    if finished < total {
        return Err(Failure::run(format!(
            "{} of {total} patterns did not finish",
            total - finished
        )));
    }
    Ok(())
}

/// Counts a worker down when it ends.
struct Alive<'a>(&'a AtomicUsize);

impl Drop for Alive<'_> {
    fn drop(&mut self) {
        self.0.fetch_sub(1, Ordering::Relaxed);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_patterns_running_at_once_share_the_cores_out_each_on_its_own_threads() {
        let cores = cores();
        for running in [1, 2, 3, cores, cores + 2] {
            let threads: Vec<usize> = (0..running)
                .map(|slot| match pattern_pool(slot, running) {
                    Ok(pool) => {
                        // Its parallel loops run only on its own threads.
                        let names: Vec<String> = pool.install(|| {
                            use rayon::prelude::*;
                            (0..64)
                                .into_par_iter()
                                .map(|_| std::thread::current().name().unwrap_or("").to_string())
                                .collect()
                        });
                        let own = format!("cloth-job{slot}-");
                        assert!(names.iter().all(|n| n.starts_with(&own)), "job {slot}: {names:?}");
                        pool.current_num_threads()
                    }
                    Err(e) => panic!("job {slot} of {running}: {e}"),
                })
                .collect();
            assert!(threads.iter().all(|&t| t >= 1), "{running} running: {threads:?}");
            assert_eq!(
                threads.iter().sum::<usize>(),
                cores.max(running),
                "{running} running: {threads:?}"
            );
        }
    }
}
