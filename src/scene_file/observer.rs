//! How a caller watches a run step by step (a progress bar, a log) and stops it (Ctrl-C).

use cloth_core::{Interrupt, Simulation, StepStats};
use std::ops::ControlFlow;

/// Sees a run's stages and steps. Breaking from [`step`](Self::step) stops the run after
/// that step: the run keeps the state reached and reports itself interrupted.
pub trait RunObserver {
    /// A stage begins: its name and its step limit (a run to rest usually ends sooner).
    fn stage(&mut self, _stage: &'static str, _max_steps: u64) {}

    /// What may stop the run inside a step (a Ctrl-C flag, a deadline): asked once, as
    /// the run begins. Never, by default.
    fn interrupt(&self) -> Interrupt {
        Interrupt::default()
    }

    /// After every step of `stage`.
    fn step(&mut self, stage: &'static str, sim: &Simulation, stats: &StepStats) -> ControlFlow<()>;
}

/// Sees nothing and never stops the run: for callers that want only its result (the
/// benchmarks, the tests).
#[derive(Debug, Clone, Copy, Default)]
pub struct Silent;

impl RunObserver for Silent {
    fn step(&mut self, _: &'static str, _: &Simulation, _: &StepStats) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }
}
