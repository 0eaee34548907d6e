//! What a run reports (report.json; report.md says the same in tables).

use super::panel_report::PanelReport;
use super::strain_summary::StrainSummary;
use cloth_core::{RestCriteria, SelfCollision, SolverSettings};
use cloth_garment::sewing::{DrapeSettings, SewingSettings};
use serde::Serialize;

/// What one stage did.
#[derive(Debug, Clone, Serialize)]
pub struct StageReport {
    pub stage: &'static str,
    pub steps: u64,
    pub seconds: f64,
    pub cg_iterations: usize,
    /// Steps taken in shorter substeps, after one diverged, did not converge or met too
    /// many impacts ...
    pub steps_cut: u64,
    /// ... and the substeps undone and taken again at half the length.
    pub retries: u64,
    /// Why it ended: "sewn", "at_rest", "step_limit", "interrupted" or "failed".
    pub ended: &'static str,
}

/// How the whole run ended.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum RunOutcome {
    /// Every stage ran to its end (at rest, or its step limit: see the stages).
    Finished,
    /// The observer stopped it (Ctrl-C): the outputs hold the state after `step`.
    Interrupted { stage: &'static str, step: u64 },
    /// A stage failed (a divergence, seams that would not close): the outputs hold the last
    /// good state, after `step` of `stage`.
    Failed {
        stage: &'static str,
        step: u64,
        error: String,
    },
}

/// The settings the run used.
#[derive(Debug, Clone, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum RunSettings {
    Garment {
        sewing: SewingSettings,
        drape: DrapeSettings,
        self_collision: SelfCollision,
    },
    Sheet {
        solver: SolverSettings,
        rest: RestCriteria,
        self_collision: SelfCollision,
    },
}

/// The largest stretch at a step the scene asked about: the source's table of maximum
/// warp and weft stretch after N iterations.
#[derive(Debug, Clone, Serialize)]
pub struct Checkpoint {
    pub stage: &'static str,
    pub step: u64,
    /// Simulated time, s.
    pub time: f64,
    /// %.
    pub max_warp: f64,
    pub max_weft: f64,
    /// Median wall time per step so far in this stage, ms.
    pub median_step_ms: f64,
}

/// The run's report (report.json).
#[derive(Debug, Clone, Serialize)]
pub struct RunReport {
    /// The version of the engine that wrote it (the `cloth` crate's).
    pub engine_version: &'static str,
    pub scene: String,
    pub outcome: RunOutcome,
    pub particles: usize,
    pub triangles: usize,
    pub settings: RunSettings,
    pub stages: Vec<StageReport>,
    pub total_seconds: f64,
    /// The simulated time of the final state (of its stage), s.
    pub simulated_time: f64,
    /// Warp and weft strain of the final state.
    pub strain: StrainSummary,
    /// The deepest any particle is inside a body at the end, m.
    pub deepest_penetration: f64,
    /// Edge-triangle pairs of the cloth passing through each other at the end (pairs
    /// sharing or neighbouring particles, or near in the flat cloth, exempt).
    pub self_intersections: usize,
    /// Cloth edges passing through body triangles at the end, counted the same way, but
    /// for the next.
    pub body_intersections: usize,
    /// Crossings of the body's thin parts (hands, forearms) by panels that pass them for
    /// the whole run, as GarmentCode's own simulator lets skirts pass the arms: panels
    /// dressing the legs (see `cloth_garment::pattern::BodyPart::Legs`).
    pub thin_parts_passed: usize,
    /// The widest seam gap: when the seams were welded, or at the end if they never were,
    /// m (garments only).
    pub largest_seam_gap: Option<f64>,
    /// When seams stopped closing while sewn, and how the pull was raised to close them.
    pub seam_stalls: Vec<cloth_garment::sewing::SeamStall>,
    /// Layers of cloth found across the seams' sides while sewn (a hood's edge between the
    /// shoulders), and the panel let through each (garments only).
    pub caught_layers: Vec<cloth_garment::sewing::CaughtLayer>,
    /// The cloth's crossings the weld made, and those left after clearing them (garments
    /// that were sewn only).
    pub weld_crossings: Option<cloth_garment::sewing::WeldCrossings>,
    /// What was done with a garment that came to rest through itself: smoothed apart and
    /// draped on, then draped again loose if it still crossed; each one's crossings and
    /// whether it was kept (garments only).
    pub untangling_at_rest: Option<cloth_garment::sewing::UntanglingAtRest>,
    /// Particles of the pattern's attached edges (a waist, a neckline), each held on one
    /// side of where it was placed (garments only).
    pub attached_particles: Option<usize>,
    /// Vertices of the garment's pinned edges and panels, before welding: held where the
    /// sewing left them, for the whole drape (garments only).
    pub pinned_particles: Option<usize>,
    /// Pieces of the cloth (panels) found through each other at the start of a stage,
    /// exempt from each other until they came apart.
    pub tangles: Vec<TangleRecord>,
    /// The strain and the intersections above, panel by panel (garments only).
    pub panels: Vec<PanelReport>,
    /// What the cut asks of the fabric round the body where a finished garment is most
    /// stretched, if the cloth goes round the body there (see [`super::Fit`]); not measured
    /// for a garment through the body.
    pub fit: Option<super::Fit>,
    /// A finished garment's verdict: "clean" (at rest, nothing through itself or the
    /// body, p99 warp and weft strain under 5 %) or why not, naming the panels (see
    /// `verdict`); `None` for a run that did not finish, and for sheets.
    pub verdict: Option<String>,
    pub checkpoints: Vec<Checkpoint>,
    /// What a fabric test reads from the cloth at rest (a finished run of a test scene).
    pub measurement: Option<Measurement>,
    /// Frames written, if the scene asked for them.
    pub frames: Vec<FrameRecord>,
    pub warnings: Vec<String>,
}

/// Two pieces of the cloth found passing through each other when a stage began.
#[derive(Debug, Clone, Serialize)]
pub struct TangleRecord {
    pub stage: &'static str,
    /// The pieces: panels of a garment, or the pieces of a sheet by a triangle of each.
    pub pieces: [String; 2],
    /// Edge-triangle pairs of the two passing through each other at the start.
    pub crossings: usize,
    /// The step of the stage after which they were found apart; `None`: still through
    /// each other at its end.
    pub apart_after: Option<u64>,
}

/// A fabric test's reading.
#[derive(Debug, Clone, Serialize)]
#[serde(tag = "test", rename_all = "snake_case")]
pub enum Measurement {
    Cusick {
        /// Drape coefficient, %.
        drape_coefficient: f64,
        folds: usize,
    },
    Cantilever {
        /// m.
        overhang: f64,
        /// w L^3 / B.
        gamma: f64,
        /// The tip's drop below the platform and reach beyond its edge, m.
        tip_drop: f64,
        tip_reach: f64,
        chord_angle_degrees: f64,
        drop_over_length: f64,
        /// The inextensible elastica's drop / L at the same gamma.
        elastica_drop_over_length: f64,
    },
}

/// One frame file of the run.
#[derive(Debug, Clone, Serialize)]
pub struct FrameRecord {
    /// Relative to the output folder.
    pub file: String,
    pub stage: &'static str,
    pub step: u64,
    pub time: f64,
    /// The cloth's edge-triangle pairs passing through each other in the frame.
    pub self_intersections: usize,
    /// The frame's sample in the animation file `file` (from 0), when frames go to one.
    pub sample: Option<u32>,
}
