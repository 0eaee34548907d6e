//! Watching a run from Python while the GIL is released: the callback is called (with the
//! GIL) every N steps with a snapshot, and Ctrl-C is noticed; either may stop the run,
//! which then keeps the state reached.

use crate::arrays::vec3_array;
use crate::results::{Snapshot, StepStats};
use cloth::scene_file::RunObserver;
use cloth::Simulation;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use std::ops::ControlFlow;
use std::time::{Duration, Instant};

/// How often signals are looked at: often enough for Ctrl-C to feel immediate, rarely
/// enough that taking the GIL costs nothing next to the steps.
const SIGNAL_CHECK: Duration = Duration::from_millis(100);

pub struct Watcher {
    callback: Option<Py<PyAny>>,
    every: u64,
    last_check: Instant,
    /// What stopped the run from Python: the callback's exception, or KeyboardInterrupt.
    error: Option<PyErr>,
}

impl Watcher {
    pub fn new(callback: Option<Py<PyAny>>, every: u64) -> PyResult<Self> {
        if every == 0 {
            return Err(PyValueError::new_err("every: must be at least 1 step"));
        }
        Ok(Self {
            callback,
            every,
            last_check: Instant::now(),
            error: None,
        })
    }

    /// After step `stats.step` of `stage`.
    pub fn observe(&mut self, stage: &str, sim: &Simulation, stats: &cloth::StepStats) -> ControlFlow<()> {
        let call = self.callback.is_some() && stats.step.is_multiple_of(self.every);
        let check = self.last_check.elapsed() >= SIGNAL_CHECK;
        if !call && !check {
            return ControlFlow::Continue(());
        }
        Python::attach(|py| {
            if check {
                self.last_check = Instant::now();
                if let Err(e) = py.check_signals() {
                    self.error = Some(e);
                    return ControlFlow::Break(());
                }
            }
            if let (true, Some(callback)) = (call, &self.callback) {
                let snapshot = Snapshot {
                    stage: stage.to_string(),
                    stats: StepStats::from(*stats),
                    positions: vec3_array(py, sim.positions()).into_any().unbind(),
                    velocities: vec3_array(py, sim.velocities()).into_any().unbind(),
                };
                match callback.call1(py, (snapshot,)) {
                    Err(e) => {
                        self.error = Some(e);
                        return ControlFlow::Break(());
                    }
                    // Only an explicit False stops: a callback returning nothing goes on.
                    Ok(r) if r.bind(py).is(pyo3::types::PyBool::new(py, false)) => {
                        return ControlFlow::Break(());
                    }
                    Ok(_) => {}
                }
            }
            ControlFlow::Continue(())
        })
    }

    /// The error the run should end with, if Python stopped it.
    pub fn take_error(&mut self) -> Option<PyErr> {
        self.error.take()
    }
}

impl RunObserver for Watcher {
    fn step(&mut self, stage: &'static str, sim: &Simulation, stats: &cloth::StepStats) -> ControlFlow<()> {
        self.observe(stage, sim, stats)
    }
}
