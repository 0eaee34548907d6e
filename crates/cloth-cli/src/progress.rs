//! What `cloth run` shows while it works: a progress bar on a terminal (stage, steps,
//! steps per second, ETA to the stage's step limit, the current largest strain), plain
//! lines otherwise, every step's statistics with --verbose. It is also where Ctrl-C
//! lands: the next step breaks and the run writes what it has.

use cloth::scene_file::RunObserver;
use cloth::{Interrupt, Simulation, StepStats, StrainReport};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// How often the largest strain is measured for the display (it costs a pass over the
/// triangles).
const STRAIN_EVERY: Duration = Duration::from_millis(500);
/// How often a plain progress line is printed.
const LINE_EVERY: Duration = Duration::from_secs(5);

#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Verbosity {
    Quiet,
    Normal,
    Verbose,
}

pub struct Progress {
    verbosity: Verbosity,
    /// None when stderr is not a terminal: plain lines instead.
    bar: Option<ProgressBar>,
    interrupted: Arc<AtomicBool>,
    stage: &'static str,
    max_steps: u64,
    stage_start: Instant,
    last_line: Instant,
    last_strain: Option<Instant>,
    strain: (f64, f64),
}

impl Progress {
    pub fn new(verbosity: Verbosity, interrupted: Arc<AtomicBool>) -> Self {
        let on_terminal = std::io::stderr().is_terminal();
        let bar = (verbosity != Verbosity::Quiet && on_terminal).then(|| {
            let bar = ProgressBar::with_draw_target(Some(1), ProgressDrawTarget::stderr());
            bar.set_style(
                ProgressStyle::with_template(
                    "{prefix:>8} [{bar:28}] {pos}/{len} steps  {per_sec}  ETA at most {eta}  {msg}",
                )
                .expect("the template is valid")
                .progress_chars("=> "),
            );
            bar
        });
        Self {
            verbosity,
            bar,
            interrupted,
            stage: "",
            max_steps: 0,
            stage_start: Instant::now(),
            last_line: Instant::now(),
            last_strain: None,
            strain: (0.0, 0.0),
        }
    }

    /// Prints a line without tearing the bar.
    fn say(&self, line: &str) {
        match &self.bar {
            Some(bar) => bar.println(line),
            None => eprintln!("{line}"),
        }
    }

    /// Clears the bar when the run is over.
    pub fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }

    fn strain_text(&self) -> String {
        format!("max warp {:.2} %  weft {:.2} %", self.strain.0, self.strain.1)
    }
}

impl RunObserver for Progress {
    fn interrupt(&self) -> Interrupt {
        Interrupt::new(self.interrupted.clone())
    }

    fn stage(&mut self, stage: &'static str, max_steps: u64) {
        self.stage = stage;
        self.max_steps = max_steps;
        self.stage_start = Instant::now();
        self.last_strain = None;
        if let Some(bar) = &self.bar {
            bar.reset();
            bar.set_length(max_steps);
            bar.set_prefix(stage);
        } else if self.verbosity != Verbosity::Quiet {
            eprintln!("{stage}: up to {max_steps} steps");
        }
    }

    fn step(&mut self, _stage: &'static str, sim: &Simulation, stats: &StepStats) -> ControlFlow<()> {
        if self.interrupted.load(Ordering::Relaxed) {
            self.say(&format!(
                "interrupted at {} step {}: writing the state reached",
                self.stage, stats.step
            ));
            return ControlFlow::Break(());
        }
        if self.verbosity == Verbosity::Quiet {
            return ControlFlow::Continue(());
        }
        // The strain is measured only when it is shown: on the bar every half second,
        // in a plain line every few seconds.
        let show = match self.bar {
            Some(_) => self.last_strain.is_none_or(|t| t.elapsed() >= STRAIN_EVERY),
            None => self.last_line.elapsed() >= LINE_EVERY,
        };
        if show {
            let s = StrainReport::new(sim.mesh(), sim.positions());
            self.strain = (s.max_warp, s.max_weft);
            self.last_strain = Some(Instant::now());
        }
        if self.verbosity == Verbosity::Verbose {
            let substeps = if stats.substeps > 1 || stats.retries > 0 {
                format!(
                    " in {} substeps (shortest {:.2e} s, {} retried)",
                    stats.substeps, stats.smallest_substep, stats.retries
                )
            } else {
                String::new()
            };
            self.say(&format!(
                "{} step {}{substeps}: t {:.4} s, {} CG iterations (residual {:.1e}), max speed {:.2e} m/s, \
                 {} contacts, {} self-contacts, {} self-impacts, {} in impact zones, assembly {:.1} ms, solve {:.1} ms, \
                 contact {:.1} ms, self-collision {:.1} ms",
                self.stage,
                stats.step,
                stats.time,
                stats.cg_iterations,
                stats.cg_residual,
                stats.max_speed,
                stats.contacts,
                stats.self_contacts,
                stats.self_impacts,
                stats.self_zone_particles,
                1e3 * stats.assembly_seconds,
                1e3 * stats.solve_seconds,
                1e3 * stats.contact_seconds,
                1e3 * stats.self_collision_seconds,
            ));
        }
        match &self.bar {
            Some(bar) => {
                bar.inc(1);
                if show {
                    bar.set_message(self.strain_text());
                }
            }
            None if show => {
                let rate = stats.step as f64 / self.stage_start.elapsed().as_secs_f64().max(1e-9);
                eprintln!(
                    "{}: step {}/{} ({rate:.1} steps/s), {}",
                    self.stage,
                    stats.step,
                    self.max_steps,
                    self.strain_text()
                );
                self.last_line = Instant::now();
            }
            None => {}
        }
        ControlFlow::Continue(())
    }
}
