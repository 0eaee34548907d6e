//! How a caller stops a run inside a step: a flag another thread raises (Ctrl-C) and a
//! deadline. Between steps an observer can stop a run; but one step of a badly started
//! cloth can take minutes (the impact passes of panels placed through each other), and a
//! time limit or a Ctrl-C must not wait for it.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Instant;

/// Raised when its flag is set or its deadline has passed. The default is never raised.
#[derive(Debug, Clone, Default)]
pub struct Interrupt {
    flag: Option<Arc<AtomicBool>>,
    deadline: Option<Instant>,
}

impl Interrupt {
    /// Raised when `flag` is set.
    pub fn new(flag: Arc<AtomicBool>) -> Self {
        Self {
            flag: Some(flag),
            deadline: None,
        }
    }

    /// Also raised from `deadline` on.
    pub fn with_deadline(mut self, deadline: Instant) -> Self {
        self.deadline = Some(deadline);
        self
    }

    /// Whether the run should stop now.
    pub fn is_raised(&self) -> bool {
        self.flag.as_ref().is_some_and(|f| f.load(Ordering::Relaxed))
            || self.deadline.is_some_and(|d| Instant::now() >= d)
    }
}
