//! How a loop of the step runs: spread over rayon's pool, or on the calling thread alone.
//! Passed down explicitly, as faer passes its `Par`, so that one solver setting decides
//! it for every loop and a small piece of work can run alone without a flag of its own.

/// Where a loop runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Parallelism {
    /// On the calling thread, in order.
    Sequential,
    /// Split over rayon's thread pool.
    Rayon,
}

impl Parallelism {
    /// Rayon when `parallel` (the solver's setting), else sequential.
    pub fn from_setting(parallel: bool) -> Self {
        if parallel {
            Self::Rayon
        } else {
            Self::Sequential
        }
    }

    pub fn is_rayon(self) -> bool {
        self == Self::Rayon
    }

    /// Sequential for work of fewer than `threshold` items, where splitting it costs more
    /// than it saves; else as it is.
    pub fn for_size(self, items: usize, threshold: usize) -> Self {
        if items >= threshold {
            self
        } else {
            Self::Sequential
        }
    }
}
