//! The source's second and third stages: sew the placed panels with gravity off, weld
//! the seams, then drape with gravity on until at rest.

mod caught;
mod cut_off;
mod from_clear_end;
mod settings;
mod smoothing_apart;
mod untangling_at_rest;
mod weld_crossings;
mod zip;

pub use caught::CaughtLayer;
pub use settings::{DrapeSettings, SewingSettings};
pub use smoothing_apart::Smoothing;
pub use untangling_at_rest::{Crossed, DrapedAgain, SmoothedOn, UntanglingAtRest, SMOOTHINGS};
pub use weld_crossings::WeldCrossings;

use crate::garment::{Garment, GarmentError, HeldOpen, Ring, Welded};
use crate::pattern::BodyPart;
use caught::Catcher;
use cloth_core::{math::Vec3, RestCriteria, SelfCollision, SimulationBuilder, SolverSettings, StepStats};
use cloth_core::{
    Attachment, Collider, Fabric, Integrator, Interrupt, PassThrough, Pin, RestOutcome, SeamPull, SimError,
    Simulation,
};
use from_clear_end::FromClearEnds;
use std::ops::ControlFlow;
use std::sync::Arc;
use std::time::Instant;
use untangling_at_rest::{smooth_and_drape_on, AtRest};
use zip::AtStrongest;

/// What the sewing stage did.
#[derive(Debug, Clone, PartialEq)]
pub struct SewingReport {
    pub steps: u64,
    pub seconds: f64,
    pub cg_iterations: usize,
    /// Widest seam gap when the seams were welded, m.
    pub max_gap: f64,
    /// The pull at full strength on a pair of the mean spacing, N (each pair's is in
    /// proportion to its share of the seam, see [`Garment::seam_shares`]).
    pub pull: f64,
    /// Each time the seams stalled, and how the pull was raised to close them.
    pub stalls: Vec<SeamStall>,
    /// The layers of cloth found across the seams, and whether the side let through each
    /// was through it by the weld.
    pub caught: Vec<CaughtLayer>,
    /// The cloth's crossings the weld made, and those left after clearing them.
    pub weld_crossings: WeldCrossings,
}

/// Seams that stopped closing: the widest then, and what was done.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SeamStall {
    /// The step at which the stall was seen.
    pub step: u64,
    /// The seam with the widest gap then, and the gap, m.
    pub seam: String,
    pub gap: f64,
    /// The pull from then on, over its full strength.
    pub pull_factor: f64,
    /// What was done.
    pub then: StallThen,
    /// For a zip, what closing asked of the ring round the body through the widest pair
    /// (see [`crate::garment::Ring::closing_strain`]): the stretch as a fraction, or the
    /// slack left as a negative one; none where no such ring goes round a body.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ring_asks: Option<f64>,
}

/// What was done about seams that stalled.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StallThen {
    /// The body's friction on the cloth, and the hold on the panels' placed height, were
    /// let go, for the panels to slide round it (at the first stall; the pull is raised
    /// from the next).
    FrictionReleased,
    /// The pull was raised (or, having torn the cloth, lowered) and sewing went on.
    Pulled,
    /// With the pull at its strongest, the seams were welded where they stood (the widest
    /// gap under [`FORCED_WELD`] of a cell, or under [`CLOTH_WELD`] with only cloth
    /// between the open pairs' sides).
    Welded,
    /// With the pull at its strongest and nothing between the open pairs' sides, they were
    /// drawn together over a stall's window of steps and welded (see `zip`).
    Zipped,
    /// With the pull at its strongest and the body between the named seam's own sides,
    /// the sewing started over from the placed panels with every seam clear as placed
    /// drawn shut first and held shut (see [`sew`]), and those the body lay across as
    /// placed between clear ends pulled from one ([`StallThen::FromClearEnd`]).
    StartedOver,
    /// As the sewing started over, the named seam (its widest gap as placed), which the
    /// body lay across where the panels were placed but not at its ends, was pulled shut
    /// from a clear end that joins it to another seam, a pair at a time, each once its
    /// neighbour had closed (see `from_clear_end`).
    FromClearEnd,
}

/// Where the sewing stands after a step, for its observer.
#[derive(Debug, Clone, Copy)]
pub struct SewingProgress<'a> {
    /// The widest seam gap, m, and its seam.
    pub gap: f64,
    pub seam: &'a str,
    /// The stalls so far, and how the pull was raised.
    pub stalls: &'a [SeamStall],
    /// The layers found across the seams so far, and whether they have passed.
    pub caught: &'a [CaughtLayer],
}

/// The garment sewn: its welded mesh at the positions where the seams closed.
#[derive(Debug, Clone)]
pub struct Sewn {
    pub welded: Welded,
    /// The garment's distinct fabrics, and which one each triangle is of.
    pub fabrics: Vec<Fabric>,
    pub triangle_fabric: Vec<usize>,
    pub report: SewingReport,
    /// Bending calibration of the panels, kept for the drape.
    pub bending_calibration: Vec<[f64; 2]>,
    /// The panels still passing the body's thin parts, in welded particles: those placed
    /// through one (see [`Garment::passing`]) until they are out of it, and those dressing
    /// the legs for the whole drape too (see [`sewing_passes`]).
    pub passing: Vec<PassThrough>,
    /// The attached edges' particles, welded, each held on the side of its edge's plane
    /// (see `attachments_as_placed`).
    pub attachments: Vec<Attachment>,
    /// The pinned vertices' particles (see [`Garment::pin`]), held where sewn.
    pub pins: Vec<usize>,
}

/// Sews `garment`, each panel of its fabric in `panel_fabrics`, around the bodies of
/// `collider`: gravity off, the implicit integrator, a seam pull ramped up over
/// [`SewingSettings::ramp_time`] to a force that stretches the cloth by at most
/// [`SewingSettings::pull_strain`], and extra air drag so panels glide into place. Stops
/// when every seam gap is under the tolerance, then welds. `observe` sees every step (with
/// the widest gap and the stalls so far) and may stop it ([`GarmentError::Stopped`]), as may `interrupt`
/// inside a step.
///
/// A seam held open by the body between its own sides, that was clear of it where the
/// panels were placed, was drawn round the body by the seams that closed before it: the
/// sewing starts over from the placed panels, once, with every seam that was clear as
/// placed drawn shut first and held shut from then on, as GarmentCode's own simulator
/// joins every seam before its first step; the others are pulled as before, but those the
/// body lay across as placed between clear ends are pulled from an end joined to another
/// seam, a pair at a time (see `from_clear_end`). A held seam that was not clear as placed
/// starts over too if it is pulled so (the steps of both attempts are counted, and
/// `observe` sees them all).
pub fn sew(
    garment: &Garment,
    panel_fabrics: &[Fabric],
    collider: Arc<dyn Collider>,
    settings: &SewingSettings,
    interrupt: &Interrupt,
    mut observe: impl FnMut(&Simulation, &StepStats, &SewingProgress) -> ControlFlow<()>,
) -> Result<Sewn, GarmentError> {
    settings.validate()?;
    if panel_fabrics.len() != garment.panel_names.len() {
        return Err(GarmentError::Parameter {
            name: "panel_fabrics",
            value: panel_fabrics.len() as f64,
            expected: "one fabric per panel",
        });
    }
    let mut attempt = Attempt {
        held: None,
        steps: 0,
        cg: 0,
        stalls: Vec::new(),
        failed: None,
        began: Instant::now(),
    };
    loop {
        let mut held = None;
        let error = match sew_once(
            garment,
            panel_fabrics,
            collider.clone(),
            settings,
            interrupt,
            &attempt,
            &mut held,
            &mut observe,
        ) {
            Ok(Some(sewn)) => return Ok(sewn),
            // Cloth or the body lay between the seam's sides where the panels were placed:
            // drawn shut first it would pass through them. The attempt before stands.
            Ok(None) => {
                return Err(attempt
                    .failed
                    .take()
                    .expect("an attempt drawing seams shut first follows a failure"))
            }
            Err(error) => error,
        };
        match held {
            Some(held) if attempt.held.is_none() => {
                attempt.steps += held.steps;
                attempt.cg += held.cg;
                attempt.stalls = held.stalls;
                attempt.stalls.push(SeamStall {
                    step: attempt.steps,
                    seam: garment.seams[held.seam].name.clone(),
                    gap: held.gap,
                    pull_factor: held.pull_factor,
                    then: StallThen::StartedOver,
                    ring_asks: None,
                });
                attempt.held = Some(held.seam);
                attempt.failed = Some(error);
            }
            _ => return Err(error),
        }
    }
}

/// The attempt at sewing before this one, if any: the seam the body held open, the steps
/// and iterations taken and the stalls met, and the failure that ended it.
#[derive(Debug)]
struct Attempt {
    /// The seam the body held open (GarmentCode's rand_1_088 drew its cuffs along and off
    /// the arms by the wide sleeve ends gathered onto them before their own seams closed,
    /// and stalled with the arm between a cuff's seam to its sleeve): it must be clear as
    /// placed for this attempt to run, which draws every seam clear as placed shut first.
    held: Option<usize>,
    steps: u64,
    cg: usize,
    stalls: Vec<SeamStall>,
    failed: Option<GarmentError>,
    began: Instant,
}

/// A seam one attempt stopped at with the body between its own sides, and the attempt's
/// steps, iterations and stalls.
struct HeldByBody {
    seam: usize,
    gap: f64,
    pull_factor: f64,
    steps: u64,
    cg: usize,
    stalls: Vec<SeamStall>,
}

/// One attempt at [`sew`], after the steps of `attempt`, drawing every seam clear as
/// placed shut first if the one before was held open by the body; `None` if cloth or a
/// body lies between that seam's sides where the panels were placed. A failure with the
/// body between the named seam's own sides is told in `held`.
#[allow(clippy::too_many_arguments)]
fn sew_once<F>(
    garment: &Garment,
    panel_fabrics: &[Fabric],
    collider: Arc<dyn Collider>,
    settings: &SewingSettings,
    interrupt: &Interrupt,
    attempt: &Attempt,
    held: &mut Option<HeldByBody>,
    observe: &mut F,
) -> Result<Option<Sewn>, GarmentError>
where
    F: FnMut(&Simulation, &StepStats, &SewingProgress) -> ControlFlow<()>,
{
    // Panels of one fabric share it, so its bending calibration is computed once.
    let mut fabrics: Vec<Fabric> = Vec::new();
    let panel_material: Vec<usize> = panel_fabrics
        .iter()
        .map(|f| match fabrics.iter().position(|g| g == f) {
            Some(k) => k,
            None => {
                fabrics.push(f.clone());
                fabrics.len() - 1
            }
        })
        .collect();
    let mut triangle_fabric: Vec<usize> = garment
        .triangle_panel
        .iter()
        .map(|&p| panel_material[p])
        .collect();
    // The softest fabric sets the pull, so no panel stretches further.
    let softest = fabrics
        .iter()
        .map(Fabric::membrane_stiffness)
        .fold(f64::INFINITY, f64::min);
    // Each pair is pulled by its share of the seam's length; the mean share is the
    // spacing of the pairs.
    let shares = garment.seam_shares();
    let spacing = shares.iter().sum::<f64>() / shares.len().max(1) as f64;
    let seam_weights: Vec<f64> = shares
        .iter()
        .map(|s| if spacing > 0.0 { s / spacing } else { 1.0 })
        .collect();
    slacken_gathers(garment, spacing, &mut fabrics, &mut triangle_fabric);
    // The body holds the cloth by its friction while the seams close, as a dresser's
    // hands would: without it, the pull of panels placed far below (a skirt's tiers, a
    // flounce) or round a slope (a band round the upper arms) drew the bodices they are
    // sewn to down off the shoulders (GarmentCode's rand_1_022, 037, 094). It is let go
    // when the seams stall (see `StallThen::FrictionReleased`). Between layers there is
    // none: panels placed over each other slide into place, and the implicit step's
    // friction between layers costs a second solve.
    let sewing_fabrics = fabrics
        .iter()
        .map(|f| f.clone().with_drag(f.drag.max(settings.drag)))
        .collect();
    let self_collision = SelfCollision {
        friction: settings.self_collision.friction.or(Some(0.0)),
        ..settings.self_collision
    };
    let solver = SolverSettings {
        integrator: Integrator::ImplicitEuler,
        time_step: settings.time_step,
        gravity: Vec3::zeros(),
        self_collision,
        ..SolverSettings::default()
    };
    let bodies = collider.clone();
    let attachments = attachments_as_placed(garment);
    let mut sim = SimulationBuilder::new(garment.mesh.clone(), fabrics[0].clone())
        .fabrics(sewing_fabrics, triangle_fabric.clone())
        .settings(solver)
        .seams(garment.seam_pairs())
        .seam_weights(seam_weights.clone())
        .touching(garment.touching.clone())
        .attachments([attachments.clone(), height_holds(garment, settings.height_slack)].concat())
        .pass_through(sewing_passes(garment))
        .collider(collider)
        .build()?;
    sim.set_interrupt(interrupt.clone());
    let stall = Stall::new(settings);
    // After an attempt held open by the body, every seam clear as placed is drawn shut
    // first, no faster than half a spacing a step, so the solve spreads the move into the
    // cloth beside them, and held shut: drawn in and let go, a seam was pulled open
    // again by those the pulls closed later (GarmentCode's rand_1_094 at 3 cm, not held
    // at its height, a sleeve's top seam round the arm, when only the held seam and those
    // round it were drawn in). Seams the body lies across as placed between clear ends are
    // pulled shut from an end joined to another seam, a pair at a time (see
    // `from_clear_end`): the held seam too, its sides not clear as placed (GarmentCode's
    // rand_1_035 on `mean_all`, a flounce whose inner seam reaches past the other leg).
    let mut draw_first = None;
    let mut from_ends: Option<FromClearEnds> = None;
    if let Some(held) = attempt.held {
        let clear = |s: usize| {
            zip::held_open(garment, &sim, bodies.as_ref(), &garment.seams[s].pairs) == HeldOpen::Nothing
        };
        let x = sim.positions();
        let ends = FromClearEnds::new(&garment.seams, seam_weights.clone(), |[a, b]| {
            bodies.segment_crossings(sim.time(), &x[a], &x[b]) > 0
        });
        if !clear(held) && !ends.pulls(held) {
            return Ok(None);
        }
        let first: Vec<[usize; 2]> = (0..garment.seams.len())
            .filter(|&s| clear(s))
            .flat_map(|s| garment.seams[s].pairs.iter().copied())
            .collect();
        let widest = first
            .iter()
            .map(|&[a, b]| (x[a] - x[b]).norm())
            .fold(0.0, f64::max);
        let steps = (widest / (0.5 * spacing)).ceil() as u64;
        draw_first = Some(zip::Zip::holding(first, x, steps.max(stall.window)));
        if !ends.is_empty() {
            sim.set_seam_weights(&ends.weights())?;
            from_ends = Some(ends);
        }
    }
    let pull = settings.pull_strain * softest * spacing;
    let mut cg = 0;
    let (mut seam, mut gap) = garment.widest_gap(sim.positions());
    let mut steps = 0;
    let (mut pull_level, mut stall) = (PullLevel::new(), stall);
    let mut stalls = attempt.stalls.clone();
    let stall_at = |step: u64, seam: usize, gap: f64, pull_factor: f64, then: StallThen| SeamStall {
        step: attempt.steps + step,
        seam: garment.seams[seam].name.clone(),
        gap,
        pull_factor,
        then,
        ring_asks: None,
    };
    if let Some(ends) = &from_ends {
        let x = sim.positions();
        for s in ends.seams() {
            let gap = garment.seams[s]
                .pairs
                .iter()
                .map(|&[a, b]| (x[a] - x[b]).norm())
                .fold(0.0, f64::max);
            stalls.push(stall_at(0, s, gap, pull_level.boost, StallThen::FromClearEnd));
        }
    }
    let mut catcher = Catcher::new(garment);
    // The step until which closed seams are sewn on while a layer found across them passes
    // (a stall's window after it was found), and how many times they were found closed
    // over cloth.
    let (mut sew_on_until, mut closing_catches) = (0, 0);
    let mut stall_catches = 0;
    // Seams being drawn shut, once the strongest pull has stalled with nothing between.
    let mut zip: Option<zip::Zip> = None;
    loop {
        if zip.as_ref().is_some_and(zip::Zip::finished) {
            break;
        }
        if gap < settings.gap_tolerance {
            let passing = sim.layer_passes().iter().any(|p| p.ended.is_none());
            if steps < sew_on_until && passing {
                // Closed over a layer being let through: sewn on until it is through.
            } else if closing_catches < CLOSING_CATCHES
                && (passing || catcher.catch(garment, &mut sim, bodies.as_ref(), attempt.steps + steps) > 0)
            {
                // A layer still on its way through after a window, or new cloth found
                // across the closed seams: another window (a weld now would cross it).
                closing_catches += 1;
                sew_on_until = steps + stall.window;
            } else {
                break;
            }
        }
        if steps == settings.max_steps {
            if gap < settings.gap_tolerance {
                break;
            }
            return Err(GarmentError::NotSewn {
                steps: attempt.steps + steps,
                seam: garment.seams[seam].name.clone(),
                gap_mm: 1e3 * gap,
                tolerance_mm: 1e3 * settings.gap_tolerance,
            });
        }
        let ramp = (sim.time() / settings.ramp_time).min(1.0);
        if zip.is_none() && ramp >= 1.0 && gap >= settings.gap_tolerance && stall.stalled(gap, steps) {
            let caught = catcher.catch(garment, &mut sim, bodies.as_ref(), attempt.steps + steps) > 0;
            if caught {
                sew_on_until = steps + stall.window;
            }
            if caught && stall_catches < STALL_CATCHES {
                // Held open by cloth across the seams: a side is let through it, and the
                // seams have another window before a pull at its strongest gives up.
                stall_catches += 1;
            } else if !stalls
                .iter()
                .any(|s: &SeamStall| s.then == StallThen::FrictionReleased)
            {
                // Held by the body's friction where the panels press on it, which a
                // stronger pull only presses harder, and at their placed height: let go,
                // for them to slide round. Once, over both attempts: a start over keeps
                // its hold to the end, the seams it draws shut first already round the
                // body. Let go again at its own first stall, GarmentCode's rand_1_094 slid
                // its sleeves' cloth between a cuff's sides and stopped 22.9 mm open (at
                // rest with it held; rand_1_088's cuffs came 8.8 % stretched, p99 weft,
                // instead of 11.7 %).
                sim.scale_body_friction(0.0)?;
                sim.set_attachments(attachments.clone())?;
                stalls.push(stall_at(
                    steps,
                    seam,
                    gap,
                    pull_level.boost,
                    StallThen::FrictionReleased,
                ));
            } else if pull_level.at_most() {
                // Held open against any pull: welded where they stand, or zipped shut, as
                // far as what lies between allows (see `AtStrongest`).
                let weld = FORCED_WELD * spacing;
                // Pairs within a weld of closing would be welded where they stand, whatever
                // lies between (weld_crossings clears what that crosses): only the wider
                // ones are looked between. GarmentCode's rand_1_094 stopped with a cuff's
                // seam to its sleeve 10 mm open, nothing between, and the sleeve's gathers
                // folded between the sides of pairs beside it a few mm apart.
                let wide = if gap <= weld {
                    Vec::new()
                } else {
                    zip::open_pairs(garment, sim.positions(), weld)
                };
                // Cloth found across any pair hides whether the body lies across another.
                let (cloth, body) = match zip::held_open(garment, &sim, bodies.as_ref(), &wide) {
                    HeldOpen::Cloth(_) => (true, zip::through_body(&sim, bodies.as_ref(), &wide)),
                    HeldOpen::Body => (false, true),
                    HeldOpen::Nothing => (false, false),
                };
                // What closing asks of the cloth round the body: said with the zip, and
                // with the failure.
                let ring = if gap > weld {
                    ring_of(garment, &sim, bodies.as_ref(), seam)
                } else {
                    None
                };
                match AtStrongest::choose(gap, weld, CLOTH_WELD * spacing, cloth, body) {
                    AtStrongest::Weld => {
                        stalls.push(stall_at(steps, seam, gap, pull_level.boost, StallThen::Welded));
                        break;
                    }
                    AtStrongest::Zip => {
                        let open = zip::open_pairs(garment, sim.positions(), settings.gap_tolerance);
                        zip = Some(zip::Zip::new(open, sim.positions(), stall.window));
                        let mut zipped = stall_at(steps, seam, gap, pull_level.boost, StallThen::Zipped);
                        zipped.ring_asks = ring.as_ref().map(Ring::closing_strain);
                        stalls.push(zipped);
                    }
                    AtStrongest::Fail { reach } => {
                        // Said seam by seam: what lies between the named seam's own sides,
                        // and between the other open seams' (GarmentCode's rand_1_088 was
                        // said to have its right cuff held open by the left sleeve, which
                        // lay across the left cuff's seam).
                        let (own, others): (Vec<[usize; 2]>, Vec<[usize; 2]>) =
                            wide.iter().partition(|p| garment.seams[seam].pairs.contains(p));
                        let own = zip::held_open(garment, &sim, bodies.as_ref(), &own);
                        if own == HeldOpen::Body {
                            *held = Some(HeldByBody {
                                seam,
                                gap,
                                pull_factor: pull_level.boost,
                                steps,
                                cg,
                                stalls: stalls.clone(),
                            });
                        }
                        return Err(GarmentError::Stalled {
                            steps: attempt.steps + steps,
                            seam: garment.seams[seam].name.clone(),
                            gap_mm: 1e3 * gap,
                            pull_factor: pull_level.boost,
                            weld_mm: 1e3 * reach,
                            held_by: own,
                            others_held_by: zip::held_open(garment, &sim, bodies.as_ref(), &others),
                            ring: ring.map(Box::new),
                        });
                    }
                }
            } else {
                pull_level.raise();
                stalls.push(stall_at(steps, seam, gap, pull_level.boost, StallThen::Pulled));
            }
        }
        let force = pull * pull_level.boost * ramp.max(1e-3);
        // Past STIFF_BOOST the spring's reach grows instead of its stiffness, so its pull
        // at a wide gap keeps growing while the system's conditioning does not.
        let reach = settings.reach * (pull_level.boost / STIFF_BOOST).max(1.0);
        sim.set_seam_pull(SeamPull {
            stiffness: force / reach,
            reach,
            damping: settings.closing_speed.map_or(0.0, |v| force / v),
        })?;
        catcher.drive(&mut sim, bodies.as_ref());
        if let Some(zip) = zip.as_mut() {
            zip.draw(&mut sim)?;
        }
        if let Some(first) = draw_first.as_mut() {
            first.draw(&mut sim)?;
        }
        let stats = match sim.step() {
            Ok(stats) => stats,
            Err(SimError::Interrupted { .. }) => {
                return Err(GarmentError::Stopped {
                    stage: "sewing",
                    steps: attempt.steps + steps,
                })
            }
            // A raised pull the cloth cannot follow even in the shortest steps: the state
            // is that of the last whole step, and the pull goes back to the last level
            // that held, for good; stalled there, the seams are welded if near or the
            // sewing fails naming the seam.
            Err(_) if zip.is_none() && pull_level.lower() => {
                stalls.push(stall_at(steps, seam, gap, pull_level.boost, StallThen::Pulled));
                continue;
            }
            Err(source) => {
                return Err(GarmentError::Sim {
                    stage: "sewing",
                    source,
                })
            }
        };
        steps += 1;
        cg += stats.cg_iterations;
        (seam, gap) = garment.widest_gap(sim.positions());
        if let Some(ends) = from_ends.as_mut() {
            // A pair handed the pull is progress: the window starts again.
            if ends.advance(sim.positions(), spacing) {
                sim.set_seam_weights(&ends.weights())?;
                stall.restart();
            }
        }
        // A raised pull that tears the cloth without diverging goes back as one that
        // diverges does: GarmentCode's rand_1_022 was stretched to 470 % (p99) by pulls
        // of 64 and 256 times, and every step from there diverged, down to the pull's own.
        if zip.is_none() && pull_level.boost > 1.0 && torn(sim.mesh(), sim.positions()) && pull_level.lower()
        {
            stalls.push(stall_at(steps, seam, gap, pull_level.boost, StallThen::Pulled));
        }
        let progress = SewingProgress {
            gap,
            seam: &garment.seams[seam].name,
            stalls: &stalls,
            caught: catcher.update(&sim),
        };
        if observe(&sim, &stats, &progress).is_break() {
            return Err(GarmentError::Stopped {
                stage: "sewing",
                steps: attempt.steps + steps,
            });
        }
    }
    let caught = catcher.update(&sim).to_vec();
    let mut welded = garment.weld(sim.positions())?;
    let weld_crossings = weld_crossings::clear(
        &mut welded,
        &cloth_core::Neighbours::of(&garment.mesh),
        bodies.as_ref(),
        sim.time(),
        sim.self_exemption_radius(),
        spacing,
    );
    let map = |ids: &[usize]| {
        let mut out: Vec<usize> = ids.iter().map(|&i| welded.particle_of[i]).collect();
        out.sort_unstable();
        out.dedup();
        out
    };
    let attachments = attachments
        .iter()
        .map(|a| Attachment {
            particle: welded.particle_of[a.particle],
            ..*a
        })
        .collect();
    let passing = sim
        .passing()
        .iter()
        .map(|p| PassThrough {
            members: map(&p.members),
            until_out: p.until_out,
        })
        .collect();
    let pins = map(&garment.pinned);
    Ok(Some(Sewn {
        welded,
        passing,
        attachments,
        pins,
        fabrics,
        triangle_fabric,
        report: SewingReport {
            steps: attempt.steps + steps,
            seconds: attempt.began.elapsed().as_secs_f64(),
            cg_iterations: attempt.cg + cg,
            max_gap: gap,
            pull,
            stalls,
            caught,
            weld_crossings,
        },
        bending_calibration: sim.bending_calibration().to_vec(),
    }))
}

/// The pieces passing the body's thin parts while sewn: the panels dressing the legs for
/// the whole simulation, and the other panels placed through a thin part until they are
/// out of it (see [`Garment::move_out_of`]).
///
/// GarmentCode places skirts round a body in an A pose whose hands hang inside their
/// panels: sewn round the hips they gathered on the hands, and draped a circle skirt hung
/// from the wrists. GarmentCode's own simulator lets the cloth it labels as dressing the
/// legs pass the arms (its "arm filter for the skirts"); so do we, and the report counts
/// the crossings so allowed apart from the body intersections.
fn sewing_passes(garment: &Garment) -> Vec<PassThrough> {
    let members = garment.panel_members();
    let mut pieces: Vec<PassThrough> = (0..garment.panel_names.len())
        .filter(|&p| garment.panel_dresses[p] == Some(BodyPart::Legs))
        .map(|p| PassThrough {
            members: members[p].clone(),
            until_out: false,
        })
        .collect();
    pieces.extend(
        garment
            .passing
            .iter()
            .filter(|piece| {
                !pieces
                    .iter()
                    .any(|leg| leg.members.first() == piece.members.first())
            })
            .cloned()
            .collect::<Vec<_>>(),
    );
    pieces
}

/// Every particle of the panels not dressing the legs held above the level `slack`
/// below where it was placed, if set, until the seams first stall (see
/// [`SewingSettings::height_slack`], `StallThen::FrictionReleased`): the straps climb onto
/// the shoulders and the sleeves close over the arms. Panels dressing the legs hang from
/// the waist and rise to it (a tiered skirt's tiers placed below): they are not held.
fn height_holds(garment: &Garment, slack: Option<f64>) -> Vec<Attachment> {
    let Some(slack) = slack else {
        return Vec::new();
    };
    let placed = garment.mesh.positions();
    let members = garment.panel_members();
    (0..members.len())
        .filter(|&p| garment.panel_dresses[p] != Some(BodyPart::Legs))
        .flat_map(|p| &members[p])
        .map(|&particle| Attachment {
            particle,
            point: placed[particle] - slack * Vec3::z(),
            direction: Vec3::z(),
        })
        .collect()
}

/// How far back past where it was placed an attached edge may go, m: GarmentCode places
/// a garment's components this far apart (`place_by_interface`, `gap=5`), and closing
/// such a gap moves either side. Held at the placed level itself, trousers' waistband
/// (rand_1_002) held their legs up into the crotch, caught there between the seams'
/// sides (24 crossings when welded; none with the slack).
const ATTACHMENT_SLACK: f64 = 0.05;

/// Each attached edge held on the side of the plane [`ATTACHMENT_SLACK`] behind its placed
/// point farthest back along its direction: the edge as a whole may not move far back
/// past where it was placed. GarmentCode places skirt tiers and flounces far out, hanging
/// below the waist, and a pull that meets in the middle drew a tiered skirt's waist
/// (rand_1_072) 60 cm down to its tiers and off the hips. Each point held where it was
/// placed instead fought the seams: a peplum's waist, placed curving 5 cm above the hem of
/// the crop top it is sewn to (rand_1_057), pushed the top up into the armpits.
fn attachments_as_placed(garment: &Garment) -> Vec<Attachment> {
    let placed = garment.mesh.positions();
    let mut attachments = Vec::new();
    for (particles, direction) in &garment.attached {
        let level = particles
            .iter()
            .map(|&i| placed[i].dot(direction))
            .fold(f64::INFINITY, f64::min);
        attachments.extend(particles.iter().map(|&particle| Attachment {
            particle,
            point: (level - ATTACHMENT_SLACK) * direction,
            direction: *direction,
        }));
    }
    attachments
}

/// The draped garment and how its run ended.
#[derive(Debug)]
pub struct Draped {
    pub simulation: Simulation,
    pub outcome: RestOutcome,
    pub seconds: f64,
    pub cg_iterations: usize,
    /// What was done with a garment at rest through itself, if it was (see
    /// `untangling_at_rest`).
    pub untangling: Option<UntanglingAtRest>,
}

/// A simulation of the sewn garment on the bodies with the solver settings given
/// (gravity on, normally), ready to drape, with air drag of at least `drag`
/// (kg/(m^2 s); 0 keeps the fabrics' own).
pub fn drape_simulation(
    sewn: &Sewn,
    collider: Arc<dyn Collider>,
    solver: SolverSettings,
    drag: f64,
) -> Result<Simulation, GarmentError> {
    let fabrics = sewn
        .fabrics
        .iter()
        .map(|f| f.clone().with_drag(f.drag.max(drag)))
        .collect();
    Ok(
        SimulationBuilder::new(sewn.welded.mesh.clone(), sewn.fabrics[0].clone())
            .fabrics(fabrics, sewn.triangle_fabric.clone())
            .settings(solver)
            .bending_calibration(sewn.bending_calibration.clone())
            .pass_through(sewn.passing.clone())
            .attachments(sewn.attachments.clone())
            .pins(sewn.pins.iter().map(|&i| Pin::fixed(i)))
            .collider(collider)
            .build()?,
    )
}

/// Drapes the sewn garment until at rest (the source's stopping mechanism) or the step
/// limit; at rest through itself, it is smoothed apart where it crosses and draped on
/// (again while that is kept and still crosses), and if it still crosses, draped again,
/// loose where it crosses, and the drape crossing least kept (see `untangling_at_rest`).
/// `observe` sees every step and may stop it ([`cloth_core::StopReason::Stopped`]), as may
/// `interrupt` inside a step; a drape after the first stopped so ends the drape as
/// stopped, at the rest kept before it.
pub fn drape(
    sewn: &Sewn,
    collider: Arc<dyn Collider>,
    settings: &DrapeSettings,
    interrupt: &Interrupt,
    mut observe: impl FnMut(&Simulation, &StepStats) -> ControlFlow<()>,
) -> Result<Draped, GarmentError> {
    settings.validate()?;
    let start = Instant::now();
    let rest = settings.rest();
    let mut simulation = drape_simulation(sewn, collider.clone(), settings.solver(), settings.drag)?;
    simulation.set_interrupt(interrupt.clone());
    let mut cg = 0;
    // Whether `observe` stopped a drape after the first, which ends as that drape failing.
    let mut stopped = false;
    let mut watch = |sim: &Simulation, stats: &StepStats| {
        cg += stats.cg_iterations;
        let flow = observe(sim, stats);
        stopped |= flow.is_break();
        flow
    };
    let failed = |source| GarmentError::Sim {
        stage: "draping",
        source,
    };
    let mut outcome = simulation.run_to_rest_with(&rest, &mut watch).map_err(failed)?;
    let mut untangling = None;
    let first_crossed = crossed(&simulation);
    let before = first_crossed.cloth;
    if outcome.reason == cloth_core::StopReason::AtRest && before > 0 {
        // Through itself at rest: smoothed apart there and draped on, again while the
        // drape on is kept and still crosses; if it still crosses, draped again from where
        // it was sewn, loose where it crosses (see `untangling_at_rest`). A drape after
        // the first that fails loses nothing: the rest kept before it stands.
        let mut draping = Draping {
            simulation: &mut simulation,
            bodies: collider.as_ref(),
            rest: &rest,
            watch: &mut watch,
        };
        let done = smooth_and_drape_on(&mut draping, first_crossed).map_err(failed)?;
        if let Some(last) = done.last {
            outcome = RestOutcome {
                steps: outcome.steps + done.steps(),
                ..last
            };
        }
        let best = done.crossed;
        let smoothed = done.smoothed;
        let mut loose = None;
        if best.cloth > 0 {
            let mut again = drape_simulation(sewn, collider, settings.solver(), settings.drag)?;
            again.set_interrupt(interrupt.clone());
            again.set_loose_pull(true);
            if let Ok(second) = again.run_to_rest_with(&rest, &mut watch) {
                let report = DrapedAgain::new(best, crossed(&again), &second);
                if report.kept {
                    simulation = again;
                    outcome = RestOutcome {
                        steps: outcome.steps + second.steps,
                        ..second
                    };
                }
                loose = Some(report);
            }
        }
        untangling = Some(UntanglingAtRest {
            before,
            smoothed,
            loose,
        });
        // A drape after the first that the caller stopped (a time limit, Ctrl-C, the
        // observer) leaves the rest kept before it, but the drape was stopped, not done.
        if stopped || interrupt.is_raised() {
            outcome = RestOutcome {
                reason: cloth_core::StopReason::Stopped,
                ..outcome
            };
        }
    }
    Ok(Draped {
        simulation,
        outcome,
        seconds: start.elapsed().as_secs_f64(),
        cg_iterations: cg,
        untangling,
    })
}

/// How `simulation`'s cloth crosses itself and the bodies.
fn crossed(simulation: &Simulation) -> Crossed {
    Crossed {
        cloth: simulation.self_intersections().count,
        body: simulation.body_intersections(),
    }
}

/// The drape's simulation at rest through itself, smoothed apart and draped on to the
/// drape's rest, every step watched.
struct Draping<'a, W> {
    simulation: &'a mut Simulation,
    bodies: &'a dyn Collider,
    rest: &'a RestCriteria,
    watch: &'a mut W,
}

impl<W: FnMut(&Simulation, &StepStats) -> ControlFlow<()>> AtRest for Draping<'_, W> {
    type Error = SimError;

    fn smoothed(&self) -> (Smoothing, Vec<Vec3>) {
        smoothed_apart(self.simulation, self.bodies)
    }

    fn drape_on(&mut self, x: &[Vec3]) -> (Result<RestOutcome, SimError>, Crossed) {
        let sim = &mut *self.simulation;
        let on = sim
            .set_positions(x)
            .and_then(|()| sim.set_velocities(&vec![Vec3::zeros(); x.len()]))
            .map_err(SimError::from)
            .and_then(|()| sim.run_to_rest_with(self.rest, &mut *self.watch));
        (on, crossed(sim))
    }

    fn state(&self) -> (Vec<Vec3>, Vec<Vec3>) {
        (
            self.simulation.positions().to_vec(),
            self.simulation.velocities().to_vec(),
        )
    }

    fn set_state(&mut self, state: &(Vec<Vec3>, Vec<Vec3>)) -> Result<(), SimError> {
        let sim = &mut *self.simulation;
        sim.set_positions(&state.0)
            .and_then(|()| sim.set_velocities(&state.1))
            .map_err(SimError::from)
    }
}

/// The positions of `simulation`'s cloth smoothed apart where it passes through itself
/// (see `smoothing_apart`), pinned particles staying, none let into `bodies`.
fn smoothed_apart(simulation: &Simulation, bodies: &dyn Collider) -> (Smoothing, Vec<Vec3>) {
    let mut pinned = vec![false; simulation.positions().len()];
    for pin in simulation.pins() {
        pinned[pin.particle] = true;
    }
    let passes = simulation.passes_thin_parts();
    let t = simulation.time();
    let mut x = simulation.positions().to_vec();
    let smoothing = smoothing_apart::smooth_apart(
        simulation.mesh(),
        simulation.seams(),
        simulation.self_exemption_radius(),
        &mut x,
        |i| pinned[i],
        |i, from, to| smoothing_apart::kept_out(bodies, t, passes[i], from, to),
    );
    (smoothing, x)
}

/// The most the pull is raised for seams that stall, over its full strength: far past
/// what any fabric gives, so that a seam the body holds open (a skirt cut tighter than the
/// hips it is sewn round) is closed however much the cloth has to stretch, its dashpot
/// keeping it to the closing speed, and the drape then shows the stretch.
const MAX_BOOST: f64 = 1024.0;

/// Each stall raises the pull this many times.
const BOOST_STEP: f64 = 4.0;

/// Seams still open when the pull at its strongest stalls are welded where they stand if
/// no pair is farther apart than this fraction of the pairs' spacing: each particle then
/// moves at most a quarter of a cell, and the drape takes up the jump. GarmentCode's
/// pencil skirts have no ease at the hips, and in cotton poplin, stiffening fast past 3 %,
/// a side seam stayed 4.2 mm open with the pull at 1,024 times its strength (the cloth
/// beside it at 31 % weft).
pub const FORCED_WELD: f64 = 0.5;

/// Seams still open wider than [`FORCED_WELD`] when the pull at its strongest stalls,
/// with only cloth between their open pairs' sides, are welded where they stand when no
/// pair is farther apart than this fraction of the pairs' spacing: each particle then
/// moves at most half a cell, and the weld's crossings are let through in the drape.
/// Wider, the sewing fails naming the seam and the cloth between. (With nothing between,
/// they are zipped however far apart; see `zip`.)
pub const CLOTH_WELD: f64 = 1.0;

/// How many stalls that let cloth found across the seams through put off the end of a
/// pull at its strongest (a weld where they stand, or the sewing's failure). GarmentCode's
/// rand_1_022, a waistband 13 cm short of closing over a flounced skirt, found new cloth
/// across its seams at every stall and sewed 369 steps (510 s) before failing.
const STALL_CATCHES: usize = 2;

/// How many windows closed seams are sewn on for cloth across them before they are
/// welded: each time cloth is found across them, or is still on its way through at a
/// window's end, it is let through for another stall's window.
const CLOSING_CATCHES: usize = 3;

/// The pull raised up to this many times its strength is a stiffer spring within the same
/// reach; beyond, a spring of that stiffness over a longer reach.
const STIFF_BOOST: f64 = 16.0;

/// A raised pull that stretches the cloth's most stretched hundredth past this (in
/// percent, warp or weft) tears it instead of closing a seam: GarmentCode's pencil skirts,
/// closed at 1,024 times the pull round hips as wide as them, keep under 20 %.
const TORN_P99: f64 = 50.0;

/// The ring round the body through the widest pair of seam `seam` in `sim` (see
/// [`crate::garment::Ring`]).
fn ring_of(garment: &Garment, sim: &Simulation, bodies: &dyn Collider, seam: usize) -> Option<Ring> {
    let x = sim.positions();
    let gap = |&[a, b]: &[usize; 2]| (x[a] - x[b]).norm();
    let widest = garment.seams[seam]
        .pairs
        .iter()
        .max_by(|p, q| gap(p).total_cmp(&gap(q)))?;
    garment.ring_through(x, seam, *widest, |points| {
        zip::goes_round(bodies, sim.time(), points)
    })
}

/// Whether the cloth at `x` is torn (see [`TORN_P99`]).
fn torn(mesh: &cloth_core::ClothMesh, x: &[Vec3]) -> bool {
    let strain = cloth_core::StrainReport::new(mesh, x);
    strain.p99_warp.max(strain.p99_weft) > TORN_P99
}

/// How long the widest gap may take to narrow by a tenth before the seams count as
/// stalled, s: a pair closing freely does so at the closing speed, a tenth of any gap in
/// far less.
const STALL_WINDOW: f64 = 0.5;

/// How far the pull is raised over its full strength, and how far it may be.
struct PullLevel {
    boost: f64,
    /// [`MAX_BOOST`], or the last level that held once a raised pull tore the cloth
    /// apart faster than any step could follow.
    ceiling: f64,
}

impl PullLevel {
    fn new() -> Self {
        Self {
            boost: 1.0,
            ceiling: MAX_BOOST,
        }
    }

    fn at_most(&self) -> bool {
        self.boost >= self.ceiling
    }

    fn raise(&mut self) {
        self.boost = (BOOST_STEP * self.boost).min(self.ceiling);
    }

    /// Back to the level before the last raise, for good; false if the pull was not
    /// raised (there is nothing to go back to).
    fn lower(&mut self) -> bool {
        if self.boost <= 1.0 {
            return false;
        }
        self.ceiling = (self.boost / BOOST_STEP).max(1.0);
        self.boost = self.ceiling;
        true
    }
}

/// Watches the widest gap once the pull is at full strength: when [`STALL_WINDOW`] of
/// sewing has not narrowed it by a tenth, the seams have stalled (held open by cloth that
/// will not give at the pull's strength: unbuckled cells beside a gather, a fold pressed on
/// the body, a panel too tight for the body), and the pull doubles.
struct Stall {
    window: u64,
    /// The step and widest gap the window started at.
    since: Option<(u64, f64)>,
}

impl Stall {
    fn new(settings: &SewingSettings) -> Self {
        Self {
            window: (STALL_WINDOW / settings.time_step).ceil().max(1.0) as u64,
            since: None,
        }
    }

    /// Starts the window again at the next step watched.
    fn restart(&mut self) {
        self.since = None;
    }

    fn stalled(&mut self, gap: f64, step: u64) -> bool {
        let (start, start_gap) = *self.since.get_or_insert((step, gap));
        if gap < 0.9 * start_gap {
            self.since = Some((step, gap));
            return false;
        }
        if step - start >= self.window {
            self.since = Some((step, gap));
            return true;
        }
        false
    }
}

/// Gives the gathered triangles (see [`Garment::gathered`]) a fabric of their own: their
/// fabric's, slack in compression. A cell of length `cell` buckles under `pi^2 B / cell^2`
/// per unit width (Euler, ends pinned; B the stiffer rigidity), so that is their
/// compressive stiffness: squeezed by the whole gather they push back with at most what
/// it takes to pleat them (cotton poplin at 2 cm: 0.24 N/m, against 1,226 N/m unpleated),
/// and their shear the same.
/// They keep it in the drape, being pleated still.
fn slacken_gathers(garment: &Garment, cell: f64, fabrics: &mut Vec<Fabric>, triangle_fabric: &mut [usize]) {
    let own = fabrics.len();
    let mut slack: Vec<Option<usize>> = vec![None; own];
    for &t in &garment.gathered {
        let k = triangle_fabric[t];
        let variant = *slack[k].get_or_insert_with(|| {
            let f = &fabrics[k];
            let buckling = std::f64::consts::PI.powi(2) * f.bending.warp.max(f.bending.weft) / (cell * cell);
            // A fabric without bending would have no compressive stiffness at all; keep a
            // trace of its own so the membrane stays well posed.
            let mut pleated = f.clone();
            pleated.compression_warp = f.compression_warp.min(buckling.max(1e-6 * f.compression_warp));
            pleated.compression_weft = f.compression_weft.min(buckling.max(1e-6 * f.compression_weft));
            // Pleats fold over one another as the cell shears: no more shear stiffness
            // than compressive.
            pleated.shear_modulus = f.shear_modulus.min(buckling);
            fabrics.push(pleated);
            fabrics.len() - 1
        });
        triangle_fabric[t] = variant;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pull_that_tears_the_cloth_goes_back_to_the_last_level_that_held_for_good() {
        let mut level = PullLevel::new();
        for _ in 0..3 {
            level.raise();
        }
        assert_eq!(level.boost, 64.0);
        assert!(!level.at_most());
        // Torn at 64 times: back to 16, and no higher from then on.
        assert!(level.lower());
        assert_eq!(level.boost, 16.0);
        assert!(level.at_most());
        level.raise();
        assert_eq!(level.boost, 16.0);
        // Down to the pull's own strength, then nothing is left to lower: the step's
        // failure is the sewing's.
        assert!(level.lower() && level.lower());
        assert_eq!(level.boost, 1.0);
        assert!(!level.lower());
        // Untorn, it rises to the most there is.
        let mut level = PullLevel::new();
        while !level.at_most() {
            level.raise();
        }
        assert_eq!(level.boost, MAX_BOOST);
    }

    #[test]
    fn cloth_stretched_past_half_its_length_in_a_hundredth_of_it_is_torn() {
        // A strip of 100 cells along the warp, `stretched` of them drawn out by 60 %.
        let strip = |stretched: usize| {
            let mesh = cloth_core::GridBuilder::new(101, 2)
                .size(1.0, 0.01)
                .build()
                .unwrap();
            let mut x = mesh.positions().to_vec();
            let mut shift = 0.0;
            for i in 0..101 {
                if i > 0 && i <= stretched {
                    shift += 0.6 * 0.01;
                }
                for j in 0..2 {
                    x[j * 101 + i].x += shift;
                }
            }
            torn(&mesh, &x)
        };
        assert!(!strip(0));
        // One cell is 2 of the 200 triangles: under the 99th percentile; two are over.
        assert!(!strip(1));
        assert!(strip(2));
        assert!(strip(3));
        assert!(strip(100));
    }

    #[test]
    fn a_gap_that_does_not_narrow_for_half_a_second_is_a_stall() {
        let settings = SewingSettings::default();
        let mut stall = Stall::new(&settings);
        let window = stall.window;
        assert_eq!(window, (STALL_WINDOW / settings.time_step).ceil() as u64);
        // Narrowing by a fifth each window: never a stall.
        let per_step = 0.8f64.powf(1.0 / window as f64);
        let mut gap = 0.01;
        for step in 0..20 * window {
            assert!(!stall.stalled(gap, step), "step {step}");
            gap *= per_step;
        }
        // Stuck: a stall within a window, then one every window, not in between.
        let stuck = 20 * window;
        let stalls: Vec<u64> = (stuck..stuck + 6 * window)
            .filter(|&step| stall.stalled(gap, step))
            .collect();
        assert!(stalls[0] <= stuck + window, "{stalls:?}");
        assert!(stalls.len() >= 5, "{stalls:?}");
        assert!(stalls.windows(2).all(|w| w[1] - w[0] == window), "{stalls:?}");
        // Creeping by under a tenth each half second is stalled too.
        let mut creeping = Stall::new(&settings);
        let stalled = (0..10 * window)
            .filter(|&step| creeping.stalled(0.01 * (1.0 - 0.02 * step as f64 / window as f64), step))
            .count();
        assert!(stalled >= 8, "{stalled}");
    }
}
