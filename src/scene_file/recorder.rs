//! Between the stages' step loops and the caller's observer: keeps the last good state (so
//! a failed or interrupted run still has something to write), times the stages, writes
//! frames and takes the checkpoints the scene asks for.

use super::frame::UpAxis;
use super::history::HistoryRow;
use super::observer::RunObserver;
use super::records::{AnimationFormat, OutputSpec};
use super::report::{Checkpoint, FrameRecord, RunOutcome, StageReport};
use super::strain_summary::StrainSummary;
use cloth_core::{math::Vec3, ClothMesh, Simulation, StepStats, Tangle};
use cloth_formats::gltf::GlbAnimationWriter;
use cloth_formats::obj::{write_cloth_obj_with_uv, ClothObj};
use cloth_formats::panels::PanelLabels;
use cloth_formats::pc2::Pc2Writer;
use std::ops::ControlFlow;
use std::path::Path;
use std::time::Instant;

pub(super) struct Recorder<'a> {
    observer: &'a mut dyn RunObserver,
    frames_every: u64,
    up_axis: UpAxis,
    animation_format: Option<AnimationFormat>,
    /// The current stage's animation file, from its first frame.
    animation: Option<AnimationFile>,
    /// What went wrong finishing an animation file, for the report's warnings.
    animation_errors: Vec<String>,
    /// A garment's panels, the frames' OBJ groups (its triangles keep their order through
    /// welding, so one labelling serves every stage).
    panels: Option<&'a PanelLabels>,
    checkpoints: &'a [u64],
    frames_dir: Option<&'a Path>,
    /// The last good state: the mesh is replaced when a stage changes it (welding), with
    /// its seams still to weld and the radius within which self-collision exempts pairs.
    mesh: ClothMesh,
    seams: Vec<[usize; 2]>,
    exemption_radius: f64,
    positions: Vec<Vec3>,
    /// Simulated time of the last good state, s.
    time: f64,
    stage: &'static str,
    stage_start: Instant,
    /// This stage's steps and CG iterations (its step times are the history's last rows).
    steps: u64,
    cg: usize,
    /// Steps taken in more than one substep, and substeps retried, this stage.
    cut: u64,
    retries: u64,
    /// Every step of the run.
    history: Vec<HistoryRow>,
    checkpoint_rows: Vec<Checkpoint>,
    frames: Vec<FrameRecord>,
    /// Why the recorder itself stopped the run (a frame it could not write).
    failure: Option<String>,
    /// The pieces of the cloth found through each other at the start of each stage.
    tangles: Vec<(&'static str, Tangle)>,
    passes_thin_parts: Vec<bool>,
}

/// An animation file being written.
enum AnimationFile {
    Pc2(Pc2Writer),
    Gltf(GlbAnimationWriter),
}

impl AnimationFile {
    fn finish(self) -> std::io::Result<()> {
        match self {
            Self::Pc2(cache) => cache.finish(),
            Self::Gltf(animation) => animation.finish(),
        }
    }
}

/// What a run leaves: its last good state and what was recorded on the way.
pub(super) struct Recorded {
    pub mesh: ClothMesh,
    pub seams: Vec<[usize; 2]>,
    pub exemption_radius: f64,
    pub positions: Vec<Vec3>,
    pub time: f64,
    pub checkpoints: Vec<Checkpoint>,
    pub frames: Vec<FrameRecord>,
    /// Each stage's pieces found through each other at its start, and when they came apart.
    pub tangles: Vec<(&'static str, Tangle)>,
    /// Per particle of the last stage, whether it passes the bodies' thin parts for good.
    pub passes_thin_parts: Vec<bool>,
    /// Animation files that could not be completed, and why.
    pub animation_errors: Vec<String>,
    /// Every step of the run.
    pub history: Vec<HistoryRow>,
}

impl<'a> Recorder<'a> {
    /// Starts from the cloth as placed.
    pub(super) fn new(
        observer: &'a mut dyn RunObserver,
        output: &'a OutputSpec,
        frames_dir: Option<&'a Path>,
        mesh: &ClothMesh,
        positions: &[Vec3],
    ) -> Self {
        Self {
            observer,
            frames_every: output
                .frames_every
                .unwrap_or(if output.animation.is_some() { 1 } else { 0 }),
            up_axis: output.up_axis,
            animation_format: output.animation,
            animation: None,
            animation_errors: Vec::new(),
            panels: None,
            checkpoints: &output.checkpoints,
            frames_dir,
            mesh: mesh.clone(),
            seams: Vec::new(),
            exemption_radius: 0.0,
            positions: positions.to_vec(),
            time: 0.0,
            stage: "",
            stage_start: Instant::now(),
            steps: 0,
            cg: 0,
            cut: 0,
            retries: 0,
            history: Vec::new(),
            checkpoint_rows: Vec::new(),
            frames: Vec::new(),
            failure: None,
            tangles: Vec::new(),
            passes_thin_parts: Vec::new(),
        }
    }

    /// Labels the frames' OBJ with a garment's panels.
    pub(super) fn label_panels(&mut self, panels: Option<&'a PanelLabels>) {
        self.panels = panels;
    }

    pub(super) fn begin(&mut self, stage: &'static str, max_steps: u64) {
        self.finish_animation();
        self.stage = stage;
        self.stage_start = Instant::now();
        self.steps = 0;
        self.cg = 0;
        self.cut = 0;
        self.retries = 0;
        self.observer.stage(stage, max_steps);
    }

    /// The stage's report, ended as `ended`; its animation file is put in place.
    pub(super) fn end(&mut self, ended: &'static str) -> StageReport {
        self.finish_animation();
        StageReport {
            stage: self.stage,
            steps: self.steps,
            seconds: self.stage_start.elapsed().as_secs_f64(),
            cg_iterations: self.cg,
            steps_cut: self.cut,
            retries: self.retries,
            ended,
        }
    }

    pub(super) fn stage(&self) -> &'static str {
        self.stage
    }

    pub(super) fn steps(&self) -> u64 {
        self.steps
    }

    pub(super) fn positions(&self) -> &[Vec3] {
        &self.positions
    }

    /// How a stage the recorder's observer stopped ended: failed when the recorder
    /// itself stopped it, else interrupted.
    pub(super) fn stopped_label(&self) -> &'static str {
        if self.failure.is_some() {
            "failed"
        } else {
            "interrupted"
        }
    }

    /// The outcome of a run the observer stopped.
    pub(super) fn stopped(&self) -> RunOutcome {
        let (stage, step) = (self.stage, self.steps);
        match &self.failure {
            Some(error) => RunOutcome::Failed {
                stage,
                step,
                error: error.clone(),
            },
            None => RunOutcome::Interrupted { stage, step },
        }
    }

    /// Completes the current stage's animation file, if it has one.
    fn finish_animation(&mut self) {
        if let Some(cache) = self.animation.take() {
            if let Err(e) = cache.finish() {
                self.animation_errors
                    .push(format!("the {} stage's animation file: {e}", self.stage));
            }
        }
    }

    pub(super) fn finish(mut self) -> Recorded {
        self.finish_animation();
        Recorded {
            mesh: self.mesh,
            seams: self.seams,
            exemption_radius: self.exemption_radius,
            positions: self.positions,
            time: self.time,
            checkpoints: self.checkpoint_rows,
            frames: self.frames,
            tangles: self.tangles,
            passes_thin_parts: self.passes_thin_parts,
            animation_errors: self.animation_errors,
            history: self.history,
        }
    }

    /// Takes the state of `sim`: after each step, and at the stage's end when that is not
    /// its last step's (a garment draped twice keeps the drape that crossed itself less).
    pub(super) fn rest_on(&mut self, sim: &Simulation) {
        let stage = self.stage;
        self.tangles.retain(|(s, _)| *s != stage);
        self.tangles
            .extend(sim.tangles().iter().map(|t| (stage, t.clone())));
        self.positions.clear();
        self.positions.extend_from_slice(sim.positions());
        self.time = sim.time();
    }

    /// After every step of the current stage.
    pub(super) fn step(&mut self, sim: &Simulation, stats: &StepStats) -> ControlFlow<()> {
        if self.steps == 0 {
            // A stage may run on a new mesh (the welded garment).
            self.mesh.clone_from(sim.mesh());
            self.seams.clear();
            self.seams.extend_from_slice(sim.seams());
            self.exemption_radius = sim.self_exemption_radius();
            self.passes_thin_parts = sim.passes_thin_parts();
        }
        self.rest_on(sim);
        self.steps += 1;
        self.cg += stats.cg_iterations;
        self.cut += u64::from(stats.substeps > 1);
        self.retries += u64::from(stats.retries);
        self.history.push(HistoryRow::of(self.stage, self.steps, stats));
        if self.checkpoints.contains(&self.steps) {
            let strain = StrainSummary::of(sim.mesh(), sim.positions());
            self.checkpoint_rows.push(Checkpoint {
                stage: self.stage,
                step: self.steps,
                time: sim.time(),
                max_warp: strain.max_warp,
                max_weft: strain.max_weft,
                median_step_ms: median(&self.stage_step_ms()),
            });
        }
        if self.frames_every > 0 && self.steps.is_multiple_of(self.frames_every) {
            if let Err(e) = self.write_frame(sim) {
                self.failure = Some(e);
                return ControlFlow::Break(());
            }
        }
        self.observer.step(self.stage, sim, stats)
    }

    /// The wall time of each step of the current stage so far, ms.
    fn stage_step_ms(&self) -> Vec<f64> {
        let start = self.history.len() - self.steps as usize;
        self.history[start..].iter().map(|r| r.step_ms).collect()
    }

    fn write_frame(&mut self, sim: &Simulation) -> Result<(), String> {
        let Some(dir) = self.frames_dir else {
            return Ok(());
        };
        if self.frames.is_empty() {
            std::fs::create_dir_all(dir)
                .map_err(|e| format!("creating the frames folder '{}': {e}", dir.display()))?;
        }
        let positions = self.up_axis.turned_from_z_up(sim.positions());
        let folder = dir
            .file_name()
            .map(|f| f.to_string_lossy().into_owned())
            .unwrap_or_default();
        let (name, sample) = match self.animation_format {
            None => {
                let name = format!("frame_{:05}.obj", self.frames.len() + 1);
                let what = format!("the cloth at {} step {}", self.stage, self.steps);
                self.write_obj(&dir.join(&name), &what, sim.mesh(), &positions)?;
                (name, None)
            }
            Some(AnimationFormat::Pc2) => {
                let name = format!("{}.pc2", self.stage);
                let path = dir.join(&name);
                if self.animation.is_none() {
                    // The mesh the cache plays on: the stage's, as its first frame has it.
                    let obj = format!("{}.obj", self.stage);
                    let what = format!(
                        "the cloth at {} step {}, the mesh of {name}",
                        self.stage, self.steps
                    );
                    self.write_obj(&dir.join(&obj), &what, sim.mesh(), &positions)?;
                    let cache = Pc2Writer::create(&path, positions.len(), 0.0, 1.0)
                        .map_err(|e| format!("creating '{}': {e}", path.display()))?;
                    self.animation = Some(AnimationFile::Pc2(cache));
                }
                let Some(AnimationFile::Pc2(cache)) = self.animation.as_mut() else {
                    unreachable!("a stage's animation is of the scene's one format");
                };
                let sample = cache.samples();
                let points: Vec<[f32; 3]> = positions
                    .iter()
                    .map(|p| [p.x as f32, p.y as f32, p.z as f32])
                    .collect();
                cache
                    .push(&points)
                    .map_err(|e| format!("writing '{}': {e}", path.display()))?;
                (name, Some(sample))
            }
            Some(AnimationFormat::Gltf) => {
                // glTF is y-up whatever the OBJ's frame: it turns the engine's positions
                // itself.
                let name = format!("{}.glb", self.stage);
                let path = dir.join(&name);
                if self.animation.is_none() {
                    let generator = format!("cloth {}", env!("CARGO_PKG_VERSION"));
                    let animation = GlbAnimationWriter::create(&path, sim.mesh(), self.panels, generator)
                        .map_err(|e| format!("creating '{}': {e}", path.display()))?;
                    self.animation = Some(AnimationFile::Gltf(animation));
                }
                let Some(AnimationFile::Gltf(animation)) = self.animation.as_mut() else {
                    unreachable!("a stage's animation is of the scene's one format");
                };
                let sample = animation.frames() as u32;
                animation
                    .push(sim.time(), sim.positions())
                    .map_err(|e| format!("writing '{}': {e}", path.display()))?;
                (name, Some(sample))
            }
        };
        self.frames.push(FrameRecord {
            file: format!("{folder}/{name}"),
            stage: self.stage,
            step: self.steps,
            time: sim.time(),
            self_intersections: sim.self_intersections().count,
            sample,
        });
        Ok(())
    }

    /// The cloth as OBJ at `path`, in the output frame, its header saying `what` it is.
    fn write_obj(&self, path: &Path, what: &str, mesh: &ClothMesh, positions: &[Vec3]) -> Result<(), String> {
        let comments = self.up_axis.file_header(what);
        let obj = ClothObj {
            comments: &comments,
            mesh,
            positions,
            panels: self.panels,
        };
        write_cloth_obj_with_uv(path, &obj).map_err(|e| format!("writing frame '{}': {e}", path.display()))
    }
}

/// The median of `values` (the mean of the middle two of an even count; 0 for none).
pub(crate) fn median(values: &[f64]) -> f64 {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    match v.len() {
        0 => 0.0,
        n if n % 2 == 1 => v[n / 2],
        n => 0.5 * (v[n / 2 - 1] + v[n / 2]),
    }
}
