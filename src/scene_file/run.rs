//! Running a prepared scene: a garment is sewn and draped, a sheet run to rest. Whatever
//! happens after the first step, the run ends with a state and a report: a divergence or
//! an interrupt keeps the last good state and says what happened.

use super::build::{Prepared, PreparedCloth, SheetTest};
use super::error::{SceneErrorKind, SceneFileError};
use super::fit::fit_where_stretched;
use super::history::HistoryRow;
use super::observer::RunObserver;
use super::panel_report::panel_reports;
use super::recorder::{Recorded, Recorder};
use super::records::SceneFile;
use super::report::{Measurement, RunOutcome, RunReport, RunSettings, TangleRecord};
use super::strain_summary::StrainSummary;
use super::verdict::verdict;
use cloth_core::{
    body_intersections_by_edge, math::Vec3, self_intersecting_pairs, BodyIntersections, ClothMesh, Collider,
    StopReason, StrainReport,
};
use cloth_formats::panels::PanelLabels;
use cloth_garment::sewing::{drape, sew};
use cloth_garment::GarmentError;
use std::path::Path;
use std::time::Instant;

/// The cloth at the end of a run (the last good state if it failed), and the report.
pub struct RunResult {
    pub mesh: ClothMesh,
    pub positions: Vec<Vec3>,
    pub report: RunReport,
    /// A garment's panels on `mesh` (`None` for a sheet).
    pub panels: Option<PanelLabels>,
    /// Every step of every stage.
    pub history: Vec<HistoryRow>,
}

impl RunResult {
    /// Whether every stage ran to its end.
    pub fn finished(&self) -> bool {
        self.report.outcome == RunOutcome::Finished
    }
}

impl Prepared {
    /// Runs the scene. `observer` sees every step and may stop the run; frames, if the
    /// scene asks for them, are written into `frames_dir`. An error means the input was at
    /// fault and nothing ran; once the first stage has begun, a run that fails (a
    /// divergence, seams that will not close or weld) or is stopped returns its last good
    /// state with the outcome in its report.
    pub fn run(
        self,
        scene: &SceneFile,
        frames_dir: Option<&Path>,
        observer: &mut dyn RunObserver,
    ) -> Result<RunResult, SceneFileError> {
        let start = Instant::now();
        let interrupt = observer.interrupt();
        let mut stages = Vec::new();
        let outcome;
        let mut gap = None;
        let mut seam_stalls = Vec::new();
        let mut caught_layers = Vec::new();
        let mut weld_crossings = None;
        let mut untangling_at_rest = None;
        let mut attached_particles = None;
        let mut pinned_particles = None;
        let mut sheet_test = None;
        // A garment's panel of each triangle, and the panels' names (its panels keep their
        // triangles' order through welding).
        let labels: Option<PanelLabels>;
        let (settings, rec) = match self.cloth {
            PreparedCloth::Garment { garment, fabrics } => {
                labels = PanelLabels::new(garment.panel_names.clone(), garment.triangle_panel.clone()).ok();
                attached_particles = Some(garment.attached.iter().map(|(p, _)| p.len()).sum());
                pinned_particles = Some(garment.pinned.len());
                let mut rec = Recorder::new(
                    observer,
                    &scene.output,
                    frames_dir,
                    &garment.mesh,
                    garment.mesh.positions(),
                );
                rec.label_panels(labels.as_ref());
                let (sewing, drape_settings) = (scene.sewing_settings(), scene.drape_settings());
                rec.begin("sewing", sewing.max_steps);
                let sewn = sew(
                    &garment,
                    &fabrics,
                    self.bodies.clone(),
                    &sewing,
                    &interrupt,
                    |sim, s, progress| {
                        // Kept as they come, for a sewing that does not finish.
                        if progress.stalls.len() != seam_stalls.len() {
                            seam_stalls = progress.stalls.to_vec();
                        }
                        if progress.caught != caught_layers.as_slice() {
                            caught_layers = progress.caught.to_vec();
                        }
                        rec.step(sim, s)
                    },
                );
                match sewn {
                    Ok(sewn) => {
                        stages.push(rec.end("sewn"));
                        gap = Some(sewn.report.max_gap);
                        weld_crossings = Some(sewn.report.weld_crossings);
                        caught_layers = sewn.report.caught.clone();
                        rec.begin("draping", drape_settings.max_steps);
                        match drape(
                            &sewn,
                            self.bodies.clone(),
                            &drape_settings,
                            &interrupt,
                            |sim, s| rec.step(sim, s),
                        ) {
                            Ok(draped) => {
                                // Draped twice, the first drape may be the one kept:
                                // what is written is where it rests.
                                rec.rest_on(&draped.simulation);
                                untangling_at_rest = draped.untangling;
                                outcome = ended(&mut rec, &mut stages, draped.outcome.reason)
                            }
                            Err(e) => outcome = failed(&mut rec, &mut stages, e.to_string()),
                        }
                    }
                    Err(GarmentError::Stopped { .. }) => {
                        outcome = ended(&mut rec, &mut stages, StopReason::Stopped)
                    }
                    Err(e) => outcome = failed(&mut rec, &mut stages, e.to_string()),
                }
                // Never welded: the gap now.
                gap = gap.or_else(|| Some(garment.widest_gap(rec.positions()).1));
                (
                    RunSettings::Garment {
                        sewing,
                        drape: drape_settings,
                        self_collision: scene.self_collision,
                    },
                    rec,
                )
            }
            PreparedCloth::Sheet { builder, test } => {
                labels = None;
                sheet_test = test;
                let mut sim = builder.build().map_err(|source| {
                    SceneFileError::new(&scene.name, None, SceneErrorKind::Param(source))
                })?;
                sim.set_interrupt(interrupt);
                let mut rec = Recorder::new(observer, &scene.output, frames_dir, sim.mesh(), sim.positions());
                rec.begin("running", scene.rest.max_steps);
                match sim.run_to_rest_with(&scene.rest, |sim, s| rec.step(sim, s)) {
                    Ok(out) => outcome = ended(&mut rec, &mut stages, out.reason),
                    Err(e) => outcome = failed(&mut rec, &mut stages, e.to_string()),
                }
                (
                    RunSettings::Sheet {
                        solver: scene.solver.clone(),
                        rest: scene.rest,
                        self_collision: scene.self_collision,
                    },
                    rec,
                )
            }
        };
        let Recorded {
            mesh,
            seams,
            exemption_radius,
            positions,
            time,
            checkpoints,
            frames,
            tangles,
            passes_thin_parts,
            animation_errors,
            history,
        } = rec.finish();
        // Names the piece of the cloth a triangle is of.
        let piece_of = |t: usize| match &labels {
            Some(l) => format!("panel '{}'", l.names()[l.of_triangle()[t]]),
            None => format!("the piece of triangle {t}"),
        };
        let tangles = tangles
            .into_iter()
            .map(|(stage, t)| TangleRecord {
                stage,
                pieces: t.triangles.map(&piece_of),
                crossings: t.crossings,
                apart_after: t.released,
            })
            .collect();
        let (deepest, _) = self.bodies.deepest_inside(time, &positions);
        let self_pairs = self_intersecting_pairs(&mesh, &seams, exemption_radius, &positions);
        let body_edges =
            body_intersections_by_edge(self.bodies.as_ref(), time, &mesh, &positions, &passes_thin_parts);
        let body: BodyIntersections = body_edges.iter().map(|(_, found)| *found).sum();
        let strain = StrainReport::new(&mesh, &positions);
        let strain_summary = StrainSummary::from_report(&strain);
        let (panels, fit, verdict) = match &labels {
            Some(l) => {
                let (triangle_panel, names) = (l.of_triangle(), l.names());
                let panels = panel_reports(names, triangle_panel, &mesh, &strain, &self_pairs, &body_edges);
                // A garment worn through the body does not show how its cut fits it: a
                // cuff zipped through the forearm (GarmentCode's rand_1_094) encloses a
                // sliver of the arm, and would read as loose.
                let fit = (outcome == RunOutcome::Finished && body.crossings == 0)
                    .then(|| {
                        let surfaces: Vec<_> =
                            self.bodies.bodies().iter().map(|b| b.surface_at(time)).collect();
                        let crosses =
                            |a: &Vec3, b: &Vec3| self.bodies.as_ref().segment_crossings(time, a, b) > 0;
                        fit_where_stretched(
                            &mesh,
                            &positions,
                            &strain,
                            &surfaces,
                            triangle_panel,
                            names,
                            &crosses,
                        )
                    })
                    .flatten();
                let verdict = verdict(
                    &outcome,
                    &stages,
                    self_pairs.len(),
                    body.crossings,
                    &strain_summary,
                    &panels,
                    fit.as_ref(),
                );
                (panels, fit, verdict)
            }
            None => (Vec::new(), None, None),
        };
        let measurement = match (&outcome, sheet_test) {
            (RunOutcome::Finished, Some(test)) => Some(measure(test, &mesh, &positions)),
            _ => None,
        };
        let report = RunReport {
            engine_version: env!("CARGO_PKG_VERSION"),
            scene: self.name,
            outcome,
            particles: mesh.vertex_count(),
            triangles: mesh.triangles().len(),
            settings,
            stages,
            total_seconds: start.elapsed().as_secs_f64(),
            simulated_time: time,
            strain: strain_summary,
            deepest_penetration: deepest,
            self_intersections: self_pairs.len(),
            body_intersections: body.crossings,
            thin_parts_passed: body.thin_parts_passed,
            largest_seam_gap: gap,
            seam_stalls,
            caught_layers,
            weld_crossings,
            untangling_at_rest,
            attached_particles,
            pinned_particles,
            tangles,
            panels,
            fit,
            verdict,
            checkpoints,
            measurement,
            frames,
            warnings: self
                .warnings
                .iter()
                .map(ToString::to_string)
                .chain(animation_errors)
                .collect(),
        };
        Ok(RunResult {
            mesh,
            positions,
            report,
            panels: labels,
            history,
        })
    }
}

/// What a fabric test reads from the sheet at rest.
fn measure(test: SheetTest, mesh: &ClothMesh, positions: &[Vec3]) -> Measurement {
    match test {
        SheetTest::Cusick => {
            let m = crate::validation::cusick::measure(positions, mesh.triangles());
            Measurement::Cusick {
                drape_coefficient: m.drape_coefficient,
                folds: m.folds,
            }
        }
        SheetTest::Cantilever { test, grid } => {
            let (drop, reach) = crate::validation::cantilever::tip(positions, grid);
            Measurement::Cantilever {
                overhang: test.overhang,
                gamma: test.gamma(),
                tip_drop: drop,
                tip_reach: reach,
                chord_angle_degrees: drop.atan2(reach).to_degrees(),
                drop_over_length: drop / test.overhang,
                elastica_drop_over_length: test.reference_drop(),
            }
        }
    }
}

/// Ends the current stage, which stopped for `reason`; the run's outcome so far.
fn ended(rec: &mut Recorder, stages: &mut Vec<super::StageReport>, reason: StopReason) -> RunOutcome {
    let label = match reason {
        StopReason::AtRest => "at_rest",
        StopReason::StepLimit => "step_limit",
        StopReason::Stopped => rec.stopped_label(),
    };
    stages.push(rec.end(label));
    match reason {
        StopReason::Stopped => rec.stopped(),
        _ => RunOutcome::Finished,
    }
}

/// Ends the current stage as failed with `error`.
fn failed(rec: &mut Recorder, stages: &mut Vec<super::StageReport>, error: String) -> RunOutcome {
    stages.push(rec.end("failed"));
    RunOutcome::Failed {
        stage: rec.stage(),
        step: rec.steps(),
        error,
    }
}
