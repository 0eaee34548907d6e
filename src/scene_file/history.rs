//! A run's steps, one row each: what the solver did and how the cloth moved, for the
//! per-step CSV, the convergence plot, and Python's history.

use cloth_core::StepStats;
use serde::Serialize;

/// One step of a stage.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HistoryRow {
    pub stage: &'static str,
    /// The step's number in its stage, from 1.
    pub step: u64,
    /// Simulated time at its end, s.
    pub time: f64,
    pub cg_iterations: usize,
    /// The final relative residual of the linear solve, |r| / |b|.
    pub cg_residual: f64,
    /// At the step's end, J.
    pub kinetic_energy: f64,
    /// Elastic plus gravitational, at the step's start, J.
    pub potential_energy: f64,
    /// The fastest particle at the step's end, m/s.
    pub max_speed: f64,
    /// Substeps the step was cut into (1 when it was not), and substeps retried.
    pub substeps: u32,
    pub retries: u32,
    /// Particles held by a body contact in the step.
    pub contacts: usize,
    /// Pairs of the cloth closer than their contact distance.
    pub self_contacts: usize,
    /// Wall time of the step, ms.
    pub step_ms: f64,
}

impl HistoryRow {
    pub fn of(stage: &'static str, step: u64, stats: &StepStats) -> Self {
        Self {
            stage,
            step,
            time: stats.time,
            cg_iterations: stats.cg_iterations,
            cg_residual: stats.cg_residual,
            kinetic_energy: stats.kinetic_energy,
            potential_energy: stats.potential_energy,
            max_speed: stats.max_speed,
            substeps: stats.substeps,
            retries: stats.retries,
            contacts: stats.contacts,
            self_contacts: stats.self_contacts,
            step_ms: 1e3
                * (stats.assembly_seconds
                    + stats.solve_seconds
                    + stats.contact_seconds
                    + stats.self_collision_seconds),
        }
    }
}
