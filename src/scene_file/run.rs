//! Running a prepared scene, and what the run reports.

use super::build::{Prepared, PreparedCloth};
use super::records::SceneFile;
use super::SceneFileError;
use crate::garment::sewing::{drape, sew};
use cloth_core::{ClothMesh, StepStats, StopReason, StrainReport, Vec3};
use serde::Serialize;
use std::time::Instant;

/// What one stage did.
#[derive(Debug, Clone, Serialize)]
pub struct StageReport {
    pub stage: &'static str,
    pub steps: u64,
    pub seconds: f64,
    pub cg_iterations: usize,
    /// Why it ended: "sewn", "at_rest" or "step_limit".
    pub ended: &'static str,
}

/// The run's report (report.json).
#[derive(Debug, Clone, Serialize)]
pub struct RunReport {
    pub scene: String,
    pub particles: usize,
    pub triangles: usize,
    pub stages: Vec<StageReport>,
    pub total_seconds: f64,
    /// Warp and weft strain at the end, % (maximum and 99th percentile).
    pub max_warp: f64,
    pub max_weft: f64,
    pub p99_warp: f64,
    pub p99_weft: f64,
    /// The deepest any particle is inside a body at the end, m.
    pub deepest_penetration: f64,
    /// The widest seam gap when the seams were welded, m (garments only).
    pub largest_seam_gap: Option<f64>,
    pub warnings: Vec<String>,
}

/// The cloth at the end of a run, and the report.
pub struct RunResult {
    pub mesh: ClothMesh,
    pub positions: Vec<Vec3>,
    pub report: RunReport,
}

impl Prepared {
    /// Runs the scene: a garment is sewn and draped, a sheet run to rest. `observe` sees
    /// every step with its stage's name.
    pub fn run(
        self,
        scene: &SceneFile,
        mut observe: impl FnMut(&'static str, &StepStats),
    ) -> Result<RunResult, SceneFileError> {
        let start = Instant::now();
        let mut stages = Vec::new();
        let (sim, gap) = match self.cloth {
            PreparedCloth::Garment { garment, fabrics } => {
                let sewn = sew(
                    &garment,
                    &fabrics,
                    self.bodies.clone(),
                    &scene.sewing,
                    |_, s, _| observe("sewing", s),
                )?;
                stages.push(StageReport {
                    stage: "sewing",
                    steps: sewn.report.steps,
                    seconds: sewn.report.seconds,
                    cg_iterations: sewn.report.cg_iterations,
                    ended: "sewn",
                });
                let draped = drape(&sewn, self.bodies.clone(), &scene.drape, |_, s| {
                    observe("draping", s)
                })?;
                stages.push(StageReport {
                    stage: "draping",
                    steps: draped.outcome.steps,
                    seconds: draped.seconds,
                    cg_iterations: draped.cg_iterations,
                    ended: ended(draped.outcome.reason),
                });
                (draped.simulation, Some(sewn.report.max_gap))
            }
            PreparedCloth::Sheet { builder } => {
                let mut sim = builder.build().map_err(|source| SceneFileError::Param {
                    file: scene.name.clone(),
                    source,
                })?;
                let stage_start = Instant::now();
                let mut cg = 0;
                let outcome = sim
                    .run_to_rest_with(&scene.rest, |_, s| {
                        cg += s.cg_iterations;
                        observe("running", s)
                    })
                    .map_err(|source| SceneFileError::Run {
                        stage: "running",
                        source,
                    })?;
                stages.push(StageReport {
                    stage: "running",
                    steps: outcome.steps,
                    seconds: stage_start.elapsed().as_secs_f64(),
                    cg_iterations: cg,
                    ended: ended(outcome.reason),
                });
                (sim, None)
            }
        };
        let strain = StrainReport::new(sim.mesh(), sim.positions());
        let (deepest, _) = self.bodies.deepest_inside(sim.time(), sim.positions());
        let report = RunReport {
            scene: self.name,
            particles: sim.mesh().vertex_count(),
            triangles: sim.mesh().triangles().len(),
            stages,
            total_seconds: start.elapsed().as_secs_f64(),
            max_warp: strain.max_warp,
            max_weft: strain.max_weft,
            p99_warp: strain.p99_warp,
            p99_weft: strain.p99_weft,
            deepest_penetration: deepest,
            largest_seam_gap: gap,
            warnings: self.warnings.iter().map(ToString::to_string).collect(),
        };
        Ok(RunResult {
            mesh: sim.mesh().clone(),
            positions: sim.positions().to_vec(),
            report,
        })
    }
}

fn ended(reason: StopReason) -> &'static str {
    match reason {
        StopReason::AtRest => "at_rest",
        StopReason::StepLimit => "step_limit",
    }
}
