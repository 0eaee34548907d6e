//! Watching a run from Python while the GIL is released: the callback is called (with the
//! GIL) every N steps with a snapshot, a tqdm progress bar is moved on, and Ctrl-C is
//! noticed; the callback or Ctrl-C may stop the run, which then keeps the state reached.
//! The steps seen are kept as history rows when asked (a scene's run keeps its own).

use crate::arrays::vec3_array;
use crate::results::{Snapshot, StepStats};
use cloth::scene_file::{HistoryRow, RunObserver};
use cloth::Simulation;
use pyo3::exceptions::{PyImportError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
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
    /// A tqdm bar, the steps of the stage so far and those it shows.
    progress: Option<Py<PyAny>>,
    steps: u64,
    shown: u64,
    /// The steps seen, when kept.
    history: Option<Vec<HistoryRow>>,
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
            progress: None,
            steps: 0,
            shown: 0,
            history: None,
        })
    }

    /// Keeping a history row of every step it sees, for [`Self::finish`].
    pub fn keeping_history(mut self) -> Self {
        self.history = Some(Vec::new());
        self
    }

    /// With a tqdm progress bar of `total` steps (`None`: unknown) described as `stage`,
    /// when `on`; an `ImportError` saying what to install without tqdm.
    pub fn with_progress(
        mut self,
        py: Python<'_>,
        on: bool,
        total: Option<u64>,
        stage: &str,
    ) -> PyResult<Self> {
        if !on {
            return Ok(self);
        }
        let tqdm = py.import("tqdm").map_err(|_| {
            PyImportError::new_err("progress=True needs tqdm: pip install tqdm (or cloth-drape[progress])")
        })?;
        let options = PyDict::new(py);
        options.set_item("total", total)?;
        options.set_item("desc", stage)?;
        options.set_item("unit", "step")?;
        let bar = tqdm.getattr("tqdm")?.call((), Some(&options))?;
        self.progress = Some(bar.unbind());
        Ok(self)
    }

    /// Shows the steps not yet shown on the bar.
    fn advance(&mut self, py: Python<'_>) -> PyResult<()> {
        if let Some(bar) = &self.progress {
            if self.steps > self.shown {
                bar.call_method1(py, "update", (self.steps - self.shown,))?;
                self.shown = self.steps;
            }
        }
        Ok(())
    }

    /// Brings the bar up to date and closes it; hands over the steps seen, if kept.
    pub fn finish(&mut self, py: Python<'_>) -> PyResult<Vec<HistoryRow>> {
        self.advance(py)?;
        if let Some(bar) = self.progress.take() {
            bar.call_method0(py, "close")?;
        }
        Ok(self.history.take().unwrap_or_default())
    }

    /// After step `stats.step` of `stage`.
    pub fn observe(
        &mut self,
        stage: &'static str,
        sim: &Simulation,
        stats: &cloth::StepStats,
    ) -> ControlFlow<()> {
        self.steps += 1;
        if let Some(history) = &mut self.history {
            history.push(HistoryRow::of(stage, stats.step, stats));
        }
        let call = self.callback.is_some() && stats.step.is_multiple_of(self.every);
        let check = self.last_check.elapsed() >= SIGNAL_CHECK;
        if !call && !check {
            return ControlFlow::Continue(());
        }
        Python::attach(|py| {
            if check {
                self.last_check = Instant::now();
                if let Err(e) = py.check_signals().and_then(|()| self.advance(py)) {
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

impl Drop for Watcher {
    /// A bar left open (the run raised) is closed, so the terminal is left clean.
    fn drop(&mut self) {
        if let Some(bar) = self.progress.take() {
            Python::attach(|py| {
                let _ = bar.call_method0(py, "close");
            });
        }
    }
}

impl RunObserver for Watcher {
    /// A new stage: the bar starts again from 0 towards its step limit.
    fn stage(&mut self, stage: &'static str, max_steps: u64) {
        let Some(bar) = &self.progress else {
            return;
        };
        Python::attach(|py| {
            let restarted = bar
                .call_method1(py, "reset", (max_steps,))
                .and_then(|_| bar.call_method1(py, "set_description", (stage,)));
            if let Err(e) = restarted {
                self.error.get_or_insert(e);
            }
        });
        self.steps = 0;
        self.shown = 0;
    }

    fn step(&mut self, stage: &'static str, sim: &Simulation, stats: &cloth::StepStats) -> ControlFlow<()> {
        self.observe(stage, sim, stats)
    }
}
