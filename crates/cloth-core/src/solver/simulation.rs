//! The Simulation: owns the state and all scratch, and steps.

use super::assembly::{ForceModel, Materials, SeamPairs, SeamPull};
use super::error::{DivergenceReason, SimError, SolveFailure};
use super::rest::MIN_WINDOW;
use super::{
    Integrator, Interrupt, Pin, PinMotion, RestCriteria, RestOutcome, SolverSettings, StepStats, StopReason,
};
use crate::contact::{Collider, Contacts, PassThrough, StepEnd, StepStart};
use crate::energy::attachment::Attachment;
use crate::error::ParamError;
use crate::fabric::Fabric;
use crate::linalg::{BlockSparse, Constraint, ConstraintError, ConstraintKind, Filter, Pcg};
use crate::math::Vec3;
use crate::mesh::ClothMesh;
use crate::self_contact::{Intersections, LayerFabric, LayerPass, LayerPassing, SelfContacts, Tangle};
use std::ops::ControlFlow;
use std::sync::Arc;
use std::time::Instant;

/// Sets up a [`Simulation`].
#[derive(Debug, Clone)]
pub struct SimulationBuilder {
    mesh: ClothMesh,
    fabrics: Vec<Fabric>,
    triangle_fabric: Vec<usize>,
    settings: SolverSettings,
    pins: Vec<Pin>,
    velocities: Option<Vec<Vec3>>,
    collider: Option<Arc<dyn Collider>>,
    seams: Vec<[usize; 2]>,
    seam_weights: Option<Vec<f64>>,
    touching: Vec<[usize; 2]>,
    attachments: Vec<Attachment>,
    pass_through: Vec<PassThrough>,
    bending_calibration: Option<Vec<[f64; 2]>>,
}

impl SimulationBuilder {
    pub fn new(mesh: ClothMesh, fabric: Fabric) -> Self {
        Self {
            triangle_fabric: vec![0; mesh.triangles().len()],
            mesh,
            fabrics: vec![fabric],
            settings: SolverSettings::default(),
            pins: Vec::new(),
            velocities: None,
            collider: None,
            seams: Vec::new(),
            seam_weights: None,
            touching: Vec::new(),
            attachments: Vec::new(),
            pass_through: Vec::new(),
            bending_calibration: None,
        }
    }
    pub fn settings(mut self, settings: SolverSettings) -> Self {
        self.settings = settings;
        self
    }
    pub fn integrator(mut self, integrator: Integrator) -> Self {
        self.settings.integrator = integrator;
        self
    }
    pub fn time_step(mut self, h: f64) -> Self {
        self.settings.time_step = h;
        self
    }
    pub fn pin(mut self, pin: Pin) -> Self {
        self.pins.push(pin);
        self
    }
    pub fn pins(mut self, pins: impl IntoIterator<Item = Pin>) -> Self {
        self.pins.extend(pins);
        self
    }
    /// The rigid bodies the cloth collides with.
    pub fn collider(mut self, collider: Arc<dyn Collider>) -> Self {
        self.collider = Some(collider);
        self
    }
    /// Particle pairs that seam forces pull together while a garment is sewn; how hard
    /// is set on the simulation ([`Simulation::set_seam_pull`]), zero at first.
    pub fn seams(mut self, pairs: Vec<[usize; 2]>) -> Self {
        self.seams = pairs;
        self
    }
    /// How much of the seam pull each pair of [`seams`](Self::seams) takes (1 each by
    /// default): its share of the seam's length, so that a pair on a short piece of seam,
    /// whose particles are light, is not pulled as hard as one on a long piece.
    pub fn seam_weights(mut self, weights: Vec<f64>) -> Self {
        self.seam_weights = Some(weights);
        self
    }
    /// Particle pairs of different pieces that touch at the start with no seam joining
    /// them: GarmentCode lays the godets of a skirt side by side, each meeting the next at
    /// a hem corner. Self-collision counts each pair as one particle, as it does seam
    /// partners, so the cloth round the point is not held there by its own contact (the
    /// corners, glued, were drawn out to three times their length while the rest of the
    /// godets was sewn); nothing pulls them.
    pub fn touching(mut self, pairs: Vec<[usize; 2]>) -> Self {
        self.touching = pairs;
        self
    }
    /// Particles held on one side of a plane each (see [`Attachment`]), by a penalty ten
    /// times as stiff as the stiffest fabric's membrane.
    pub fn attachments(mut self, attachments: Vec<Attachment>) -> Self {
        self.attachments = attachments;
        self
    }
    /// Cloth of several fabrics (a garment's panels): triangle `t` is of
    /// `fabrics[triangle_fabric[t]]`. Replaces the fabric given to [`new`](Self::new).
    pub fn fabrics(mut self, fabrics: Vec<Fabric>, triangle_fabric: Vec<usize>) -> Self {
        self.fabrics = fabrics;
        self.triangle_fabric = triangle_fabric;
        self
    }
    /// Pieces of the cloth that pass through the bodies they start in, untouched by them,
    /// until they are out (see [`PassThrough`]); other particles inside a body are
    /// carried out to its nearest side.
    pub fn pass_through(mut self, pieces: Vec<PassThrough>) -> Self {
        self.pass_through = pieces;
        self
    }
    /// Uses these bending calibration factors, one pair per fabric, instead of computing
    /// them (see [`crate::energy::bending::calibration`]): a garment keeps its panels'
    /// factors when its seams are welded.
    pub fn bending_calibration(mut self, kappa: Vec<[f64; 2]>) -> Self {
        self.bending_calibration = Some(kappa);
        self
    }
    /// Initial velocities (zero by default).
    pub fn velocities(mut self, v: Vec<Vec3>) -> Self {
        self.velocities = Some(v);
        self
    }

    /// Validates the fabric, settings and pins, then builds the model, the matrix
    /// pattern and every buffer a step needs.
    pub fn build(self) -> Result<Simulation, ParamError> {
        if self.fabrics.is_empty() {
            return Err(ParamError::OutOfRange {
                name: "fabrics",
                value: 0.0,
                expected: "at least one fabric",
            });
        }
        for f in &self.fabrics {
            f.validate()?;
        }
        let triangles = self.mesh.triangles().len();
        if self.triangle_fabric.len() != triangles {
            return Err(ParamError::OutOfRange {
                name: "triangle_fabric",
                value: self.triangle_fabric.len() as f64,
                expected: "one fabric index per triangle",
            });
        }
        if let Some(&k) = self.triangle_fabric.iter().find(|&&k| k >= self.fabrics.len()) {
            return Err(ParamError::OutOfRange {
                name: "triangle_fabric",
                value: k as f64,
                expected: "indices of the fabrics given",
            });
        }
        self.settings.validate()?;
        let n = self.mesh.vertex_count();
        let x: Vec<Vec3> = self.mesh.positions().to_vec();
        let mut pinned = vec![false; n];
        let mut pins = Vec::with_capacity(self.pins.len());
        for mut pin in self.pins {
            if pin.particle >= n {
                return Err(ParamError::PinOutOfRange {
                    particle: pin.particle,
                    count: n,
                });
            }
            if std::mem::replace(&mut pinned[pin.particle], true) {
                return Err(ParamError::OutOfRange {
                    name: "pins",
                    value: pin.particle as f64,
                    expected: "each particle pinned at most once",
                });
            }
            if let PinMotion::Fixed = pin.motion {
                pin.motion = PinMotion::At(x[pin.particle]);
            }
            pins.push(pin);
        }
        let v = match self.velocities {
            Some(v) => {
                per_particle("velocities", &v, n)?;
                v
            }
            None => vec![Vec3::zeros(); n],
        };
        let collider_thickness = self.collider.as_ref().map(|c| c.max_thickness());
        if let Some(d) = collider_thickness {
            ParamError::check(
                d > 0.0 && d.is_finite(),
                "contact thickness",
                d,
                "a positive thickness in m",
            )?;
        }
        for (name, pairs) in [("seams", &self.seams), ("touching", &self.touching)] {
            if let Some(&[a, b]) = pairs.iter().find(|&&[a, b]| a >= n || b >= n || a == b) {
                return Err(ParamError::OutOfRange {
                    name,
                    value: a.max(b) as f64,
                    expected: "pairs of two different particles of the mesh",
                });
            }
        }
        particles_of_cloth(
            "pass_through",
            self.pass_through.iter().flat_map(|p| &p.members),
            n,
        )?;
        check_attachments(&self.attachments, n)?;
        let seam_weights = self.seam_weights.unwrap_or_else(|| vec![1.0; self.seams.len()]);
        check_seam_weights(&seam_weights, self.seams.len())?;
        if let Some(kappa) = &self.bending_calibration {
            ParamError::check(
                kappa.len() == self.fabrics.len(),
                "bending_calibration",
                kappa.len() as f64,
                "one pair of factors per fabric",
            )?;
            let smallest = kappa.iter().flatten().copied().fold(f64::INFINITY, f64::min);
            ParamError::check(
                kappa.iter().flatten().all(|k| k.is_finite() && *k > 0.0),
                "bending_calibration",
                smallest,
                "positive finite factors",
            )?;
        }
        let materials = Materials {
            fabrics: self.fabrics,
            triangle_fabric: &self.triangle_fabric,
            calibration: self.bending_calibration,
        };
        let seams = SeamPairs {
            pairs: &self.seams,
            weights: &seam_weights,
        };
        let (model, matrix) = ForceModel::new(&self.mesh, materials, seams, &self.attachments, &pinned);
        let contacts = self.collider.map(|collider| {
            let fabrics = model.fabrics();
            let stiffness = model.penalty_stiffness();
            let friction = model
                .particle_fabrics()
                .iter()
                .map(|&f| fabrics[f].friction)
                .collect();
            let mut c = Contacts::new(collider, model.masses(), &pinned, stiffness, friction);
            c.particles
                .refresh(c.collider.as_ref(), 0.0, &x, self.settings.parallelism());
            c.particles.set_pass_through(self.pass_through.clone());
            c
        });
        let joined: Vec<[usize; 2]> = self.seams.iter().chain(&self.touching).copied().collect();
        let mut self_contacts = self_contacts_for(&self.mesh, &joined, &self.settings, &model, &pinned);
        let tangles = self_contacts.as_mut().map_or_else(Vec::new, |sc| sc.untangle(&x));
        let pin_count = pins.len();
        let filter_capacity = if contacts.is_some() { n } else { pin_count };
        let zeros = vec![Vec3::zeros(); n];
        Ok(Simulation {
            mesh: self.mesh,
            model,
            matrix,
            settings: self.settings,
            pins,
            pinned,
            contacts,
            seams: self.seams,
            joined,
            self_contacts,
            tangles,
            passes: Vec::new(),
            x,
            v,
            time: 0.0,
            steps: 0,
            ws: Workspace {
                force: zeros.clone(),
                hv: zeros.clone(),
                b: zeros.clone(),
                rhs: zeros.clone(),
                z: zeros.clone(),
                az: zeros.clone(),
                y: zeros.clone(),
                dv: zeros.clone(),
                support: zeros.clone(),
                x_new: zeros.clone(),
                v_new: zeros.clone(),
                x_start: zeros.clone(),
                v_start: zeros.clone(),
                rest_anchor: zeros,
                filter: Filter::new(n, filter_capacity),
                pcg: Pcg::new(n),
                pin_targets: Vec::with_capacity(pin_count),
            },
            interrupt: Interrupt::default(),
            level: 0,
            easy: 0,
        })
    }
}

/// Scratch reused by every step.
#[derive(Debug)]
pub(super) struct Workspace {
    pub force: Vec<Vec3>,
    pub hv: Vec<Vec3>,
    /// Right-hand side `h F0 - h^2 K v0` of the unfiltered system.
    pub b: Vec<Vec3>,
    pub rhs: Vec<Vec3>,
    pub z: Vec<Vec3>,
    pub az: Vec<Vec3>,
    /// Last solution of the filtered system, the next solve's initial guess.
    pub y: Vec<Vec3>,
    /// `y + z`: the velocity change of the last solve.
    pub dv: Vec<Vec3>,
    /// The outward normal of the body holding each particle at the end of the step (zero
    /// for free particles): it does not yield to the cloth's impacts into the body.
    pub support: Vec<Vec3>,
    pub x_new: Vec<Vec3>,
    pub v_new: Vec<Vec3>,
    /// The state at the start of the step, to take it again in shorter substeps.
    pub x_start: Vec<Vec3>,
    pub v_start: Vec<Vec3>,
    /// Where the particles were at the start of a run to rest's window.
    pub rest_anchor: Vec<Vec3>,
    pub filter: Filter,
    pub pcg: Pcg,
    /// Where each pin wants its particle at the end of the step (its path is asked once).
    pub pin_targets: Vec<Vec3>,
}

/// A cloth simulation: the mesh, its fabric, the state and the integrator.
#[derive(Debug)]
pub struct Simulation {
    pub(super) mesh: ClothMesh,
    pub(super) model: ForceModel,
    pub(super) matrix: BlockSparse,
    pub(super) settings: SolverSettings,
    pub(super) pins: Vec<Pin>,
    pub(super) pinned: Vec<bool>,
    pub(super) contacts: Option<Contacts>,
    /// The seams' particle pairs (exempt from self-collision until welded).
    pub(super) seams: Vec<[usize; 2]>,
    /// The seams' pairs and those touching at the start (see
    /// [`SimulationBuilder::touching`]): one particle each to the self-collision.
    pub(super) joined: Vec<[usize; 2]>,
    pub(super) self_contacts: Option<SelfContacts>,
    /// The pieces of the cloth found passing through each other at the start.
    pub(super) tangles: Vec<Tangle>,
    /// The layers of cloth let through other cloth (see [`LayerPass`]), ended or not.
    pub(super) passes: Vec<LayerPassing>,
    pub(super) x: Vec<Vec3>,
    pub(super) v: Vec<Vec3>,
    pub(super) time: f64,
    pub(super) steps: u64,
    pub(super) ws: Workspace,
    pub(super) interrupt: Interrupt,
    /// Steps are taken as substeps of `time_step / 2^level` (see `step_to`) ...
    pub(super) level: u32,
    /// ... of which this many in a row have succeeded.
    pub(super) easy: u32,
}

impl Simulation {
    pub fn mesh(&self) -> &ClothMesh {
        &self.mesh
    }
    pub fn fabrics(&self) -> &[Fabric] {
        self.model.fabrics()
    }
    pub fn settings(&self) -> &SolverSettings {
        &self.settings
    }
    pub fn positions(&self) -> &[Vec3] {
        &self.x
    }
    pub fn velocities(&self) -> &[Vec3] {
        &self.v
    }
    pub fn masses(&self) -> &[f64] {
        self.model.masses()
    }
    pub fn pins(&self) -> &[Pin] {
        &self.pins
    }
    pub fn time(&self) -> f64 {
        self.time
    }
    /// Steps taken so far.
    pub fn step_count(&self) -> u64 {
        self.steps
    }
    /// The factors scaling the warp and weft bending rigidities into hinge stiffnesses
    /// (see [`crate::energy::bending::calibration`]), one pair per fabric.
    pub fn bending_calibration(&self) -> &[[f64; 2]] {
        self.model.bending_calibration()
    }
    /// Lets a flag or deadline stop the run inside a step, not only between steps: a
    /// step interrupted is undone and fails with [`SimError::Interrupted`]
    /// ([`Simulation::run_to_rest_with`] reports it as [`StopReason::Stopped`]).
    pub fn set_interrupt(&mut self, interrupt: Interrupt) {
        self.interrupt = interrupt;
    }

    /// Lets only `scale` of the friction between the cloth and the bodies act (1 all, as
    /// built; 0 none), the bodies' own coefficients and the fabrics' alike. The sewing lets
    /// go of it when seams stall, for the panels to slide round the body to meet.
    pub fn scale_body_friction(&mut self, scale: f64) -> Result<(), ParamError> {
        ParamError::check(
            scale.is_finite() && scale >= 0.0,
            "body friction scale",
            scale,
            "a finite factor >= 0",
        )?;
        if let Some(contacts) = self.contacts.as_mut() {
            contacts.scale_friction(scale);
        }
        Ok(())
    }

    /// Holds the cloth by `attachments` from the next step on, in place of those given
    /// before (to the builder or here). The sewing holds the panels at their placed height
    /// until the seams first stall, then keeps only the garment's attached edges.
    pub fn set_attachments(&mut self, attachments: Vec<Attachment>) -> Result<(), ParamError> {
        check_attachments(&attachments, self.x.len())?;
        self.model.set_attachments(&attachments, &self.matrix);
        Ok(())
    }

    /// How hard the seams given to the builder pull (zero: not at all).
    pub fn set_seam_pull(&mut self, pull: SeamPull) -> Result<(), ParamError> {
        ParamError::check(
            pull.stiffness.is_finite() && pull.stiffness >= 0.0,
            "seam stiffness",
            pull.stiffness,
            "a finite stiffness >= 0 N/m",
        )?;
        ParamError::check(
            pull.reach.is_finite() && pull.reach > 0.0,
            "seam reach",
            pull.reach,
            "a positive distance in m",
        )?;
        ParamError::check(
            pull.damping.is_finite() && pull.damping >= 0.0,
            "seam damping",
            pull.damping,
            "a finite damping >= 0 N s/m",
        )?;
        self.model.set_seam_pull(pull);
        Ok(())
    }
    pub fn seam_pull(&self) -> SeamPull {
        self.model.seam_pull()
    }

    /// Weighs each seam pair's pull from the next step on, in place of the weights given
    /// before (to the builder or here): one finite weight >= 0 per pair given to
    /// [`SimulationBuilder::seams`], in its order; zero leaves a pair unpulled.
    pub fn set_seam_weights(&mut self, weights: &[f64]) -> Result<(), ParamError> {
        check_seam_weights(weights, self.seams.len())?;
        self.model.set_seam_weights(weights);
        Ok(())
    }
    /// Changes the integrator or its settings between steps.
    pub fn set_settings(&mut self, settings: SolverSettings) -> Result<(), ParamError> {
        settings.validate()?;
        if settings.self_collision != self.settings.self_collision {
            self.self_contacts =
                self_contacts_for(&self.mesh, &self.joined, &settings, &self.model, &self.pinned);
            // The new self-collision finds again what still passes through itself.
            let now = self
                .self_contacts
                .as_mut()
                .map_or_else(Vec::new, |sc| sc.untangle(&self.x));
            for t in self.tangles.iter_mut().filter(|t| t.released.is_none()) {
                if !now.iter().any(|n| n.triangles == t.triangles) {
                    t.released = Some(self.steps);
                }
            }
            for n in now {
                if !self
                    .tangles
                    .iter()
                    .any(|t| t.triangles == n.triangles && t.released.is_none())
                {
                    self.tangles.push(n);
                }
            }
        }
        self.settings = settings;
        self.exempt_passes();
        Ok(())
    }
    /// Pulls the cloth out of itself again where it crosses itself now, the two pieces of
    /// each crossing loose round it (exempt from each other there), or, off, stops pulling
    /// and holds what crosses as it is (see `SelfContacts::set_loose_pull`). Nothing
    /// without self-collision.
    pub fn set_loose_pull(&mut self, on: bool) {
        if let Some(sc) = self.self_contacts.as_mut() {
            sc.set_loose_pull(on);
        }
    }
    /// Replaces the velocities (one finite vector per particle).
    pub fn set_velocities(&mut self, v: &[Vec3]) -> Result<(), ParamError> {
        per_particle("velocities", v, self.v.len())?;
        self.v.copy_from_slice(v);
        // Friction predicts from the last step's forces, which were of the old motion.
        if let Some(c) = &mut self.contacts {
            c.particles.forget_demand();
        }
        Ok(())
    }
    /// Moves the particles (one finite point per particle). Pins keep their targets, so a
    /// pinned particle moved here goes back to its pin in the next step. Pieces that began
    /// through each other and are apart where moved collide again from the next step on
    /// (else the step would let them pass back through each other).
    pub fn set_positions(&mut self, x: &[Vec3]) -> Result<(), ParamError> {
        per_particle("positions", x, self.x.len())?;
        self.x.copy_from_slice(x);
        self.release_untangled();
        // The warm start and the contact states were of the old configuration.
        self.ws.y.iter_mut().for_each(|y| *y = Vec3::zeros());
        if let Some(c) = &mut self.contacts {
            c.particles.refresh(
                c.collider.as_ref(),
                self.time,
                &self.x,
                self.settings.parallelism(),
            );
        }
        Ok(())
    }
    pub fn kinetic_energy(&self) -> f64 {
        kinetic_energy(self.model.masses(), &self.v)
    }

    /// Advances one time step. On divergence the state stays at the last good step.
    pub fn step(&mut self) -> Result<StepStats, SimError> {
        self.step_to(0.0)
    }

    /// One step of the set time step, whose implicit solves may also stop at an RMS
    /// velocity error of `velocity_accuracy` (m/s).
    ///
    /// The step is taken as substeps of `h / 2^level`. A substep that diverges, whose
    /// solve fails or does not converge, or whose impact passes go over their budget is
    /// undone and taken again at half the length, down to `h / 2^max_halvings`; below
    /// that the step fails, the state of the last whole step kept. The level stays for the
    /// next step and comes down one after [`EASY_SUBSTEPS`] substeps in a row succeed, so
    /// a hard stretch is crossed at the length it needs and an easy one at the full step.
    /// At the floor the impact passes have no budget (they end in freezing particles
    /// where they started, which never lets layers cross) and an unconverged solve is
    /// kept, as the floor is where the step stops being made smaller.
    fn step_to(&mut self, velocity_accuracy: f64) -> Result<StepStats, SimError> {
        let h = self.settings.time_step;
        let floor = self.settings.max_halvings;
        let ticks: u64 = 1 << floor;
        let start_time = self.time;
        self.ws.x_start.copy_from_slice(&self.x);
        self.ws.v_start.copy_from_slice(&self.v);
        let mut total = StepStats {
            cg_converged: true,
            ..StepStats::default()
        };
        let (mut done, mut finest): (u64, u32) = (0, 0);
        while done < ticks {
            let level = self.level.min(floor);
            finest = finest.max(level);
            let length = (ticks >> level).min(ticks - done);
            let dt = h * length as f64 / ticks as f64;
            let at_floor = level == floor;
            let stats = match self.try_step(dt, velocity_accuracy, at_floor) {
                Ok(stats) => stats,
                Err(e) => {
                    let retry = !at_floor && matches!(e, SimError::Diverged { .. } | SimError::Solver { .. });
                    if !retry && done > 0 {
                        // Failing, the step keeps the last whole step's state.
                        self.x.copy_from_slice(&self.ws.x_start);
                        self.v.copy_from_slice(&self.ws.v_start);
                        self.time = start_time;
                    }
                    // The warm start and the contact states were of the rejected substep.
                    self.ws.y.iter_mut().for_each(|y| *y = Vec3::zeros());
                    if let Some(c) = &mut self.contacts {
                        c.particles.rewind_passing();
                        c.particles.refresh(
                            c.collider.as_ref(),
                            self.time,
                            &self.x,
                            self.settings.parallelism(),
                        );
                    }
                    if !retry {
                        return Err(e);
                    }
                    total.retries += 1;
                    self.level = level + 1;
                    self.easy = 0;
                    continue;
                }
            };
            total.add_substep(&stats);
            done += length;
            self.easy += 1;
            // Back up a level once the substeps have gone well and the coarser grid fits.
            if self.easy >= EASY_SUBSTEPS && level > 0 && done % (ticks >> (level - 1)) == 0 {
                self.level = level - 1;
                self.easy = 0;
            }
        }
        self.time = start_time + h;
        self.steps += 1;
        self.release_tangles();
        self.end_passed();
        total.step = self.steps;
        total.time = self.time;
        total.smallest_substep = h / (1u64 << finest) as f64;
        total.max_displacement = self
            .x
            .iter()
            .zip(&self.ws.x_start)
            .map(|(a, b)| (a - b).norm())
            .fold(0.0, f64::max);
        Ok(total)
    }

    /// One substep of length `h`, committed only if it passes every check. Above the
    /// floor an unconverged solve and impact passes over their budget fail it; `at_floor`
    /// lifts both.
    fn try_step(&mut self, h: f64, velocity_accuracy: f64, at_floor: bool) -> Result<StepStats, SimError> {
        let interrupted = SimError::Interrupted {
            step: self.steps + 1,
            last_good: self.steps,
        };
        if self.interrupt.is_raised() {
            return Err(interrupted);
        }
        self.ws.pin_targets.clear();
        for pin in &self.pins {
            let target = pin.target(self.time + h);
            if !target.iter().all(|c| c.is_finite()) {
                return Err(SimError::InvalidPin {
                    step: self.steps + 1,
                    particle: pin.particle,
                });
            }
            self.ws.pin_targets.push(target);
        }
        // Parallel work started from outside rayon's pool goes through its global injector,
        // which allocates a block every 63 jobs; run the whole step as one job inside the
        // pool instead, so the many parallel loops of a step use a worker's own queue.
        let integrate = |sim: &mut Self| {
            let detection = sim.start_contacts(h);
            sim.refill_filter(h)?;
            let mut stats = match sim.settings.integrator {
                Integrator::ImplicitEuler => sim.implicit_step(h, velocity_accuracy)?,
                Integrator::ExplicitEuler => sim.explicit_step(h, false)?,
                Integrator::SymplecticEuler => sim.explicit_step(h, true)?,
            };
            let over = sim.finish_contacts(h, at_floor, &mut stats);
            stats.self_collision_seconds += detection;
            Ok((stats, over))
        };
        let result = if self.settings.parallel && rayon::current_thread_index().is_none() {
            rayon::scope(|_| integrate(self))
        } else {
            integrate(self)
        };
        // The impact passes stop early when interrupted: their state is not the step's.
        if self.interrupt.is_raised() {
            return Err(interrupted);
        }
        let (mut stats, over) = result.map_err(|reason| SimError::Solver {
            step: self.steps + 1,
            last_good: self.steps,
            reason,
        })?;
        if !stats.cg_converged && !at_floor {
            return Err(SimError::Solver {
                step: self.steps + 1,
                last_good: self.steps,
                reason: SolveFailure::NotConverged {
                    iterations: stats.cg_iterations,
                    residual: stats.cg_residual,
                },
            });
        }
        if let Some(budget) = over {
            return Err(SimError::Diverged {
                step: self.steps + 1,
                last_good: self.steps,
                reason: DivergenceReason::ImpactBudget {
                    found: stats.self_impacts,
                    budget,
                },
            });
        }
        // Land pinned particles on their targets exactly, not to rounding.
        for (pin, target) in self.pins.iter().zip(&self.ws.pin_targets) {
            self.ws.x_new[pin.particle] = *target;
        }

        let masses = self.model.masses();
        let mut max_speed: f64 = 0.0;
        for (i, (xn, vn)) in self.ws.x_new.iter().zip(&self.ws.v_new).enumerate() {
            let speed = vn.norm();
            let bad = if !(xn.iter().all(|c| c.is_finite()) && speed.is_finite()) {
                Some(DivergenceReason::NonFinite { particle: i })
            } else if speed > self.settings.max_speed {
                Some(DivergenceReason::SpeedLimit {
                    particle: i,
                    speed,
                    limit: self.settings.max_speed,
                })
            } else {
                None
            };
            if let Some(reason) = bad {
                return Err(SimError::Diverged {
                    step: self.steps + 1,
                    last_good: self.steps,
                    reason,
                });
            }
            max_speed = max_speed.max(speed);
        }
        let ke = kinetic_energy(masses, &self.ws.v_new);
        if ke > self.settings.max_kinetic_energy {
            return Err(SimError::Diverged {
                step: self.steps + 1,
                last_good: self.steps,
                reason: DivergenceReason::EnergyLimit {
                    energy: ke,
                    limit: self.settings.max_kinetic_energy,
                },
            });
        }
        std::mem::swap(&mut self.x, &mut self.ws.x_new);
        std::mem::swap(&mut self.v, &mut self.ws.v_new);
        self.time += h;
        stats.max_speed = max_speed;
        stats.kinetic_energy = ke;
        Ok(stats)
    }

    /// Steps until at rest (every particle moved less than the tolerance per step over a
    /// window of the given number of steps; see [`RestCriteria`]) or the step limit, and
    /// says which.
    pub fn run_to_rest(&mut self, criteria: &RestCriteria) -> Result<RestOutcome, SimError> {
        self.run_to_rest_with(criteria, |_, _| ControlFlow::Continue(()))
    }

    /// As [`run_to_rest`](Self::run_to_rest), calling `observe` with the simulation and the
    /// step's statistics after every step; when it breaks, the run ends there with
    /// [`StopReason::Stopped`].
    ///
    /// Near rest the forces, and with them the right-hand side of the implicit solve,
    /// shrink, and a relative tolerance alone would solve ever more precisely for motion
    /// far below what the rest test can see. So each step here also stops at a velocity
    /// error of a hundredth of `tolerance / h`.
    pub fn run_to_rest_with(
        &mut self,
        criteria: &RestCriteria,
        mut observe: impl FnMut(&Simulation, &StepStats) -> ControlFlow<()>,
    ) -> Result<RestOutcome, SimError> {
        criteria.validate()?;
        // The step may grow on the way (see `RestCriteria::max_time_step`): the solver's
        // own is given back however the run ends.
        let base = self.settings.time_step;
        let outcome = self.steps_to_rest(criteria, &mut observe);
        self.settings.time_step = base;
        outcome
    }
}

impl Simulation {
    /// The loop of [`Simulation::run_to_rest_with`], from steps of the solver's length.
    fn steps_to_rest(
        &mut self,
        criteria: &RestCriteria,
        observe: &mut impl FnMut(&Simulation, &StepStats) -> ControlFlow<()>,
    ) -> Result<RestOutcome, SimError> {
        let base = self.settings.time_step;
        let accuracy = 0.01 * criteria.tolerance / base;
        let allowed = (criteria.moving_fraction * self.x.len() as f64).floor() as usize;
        // The window's start is in `ws.rest_anchor`; the steps and time into it.
        self.ws.rest_anchor.copy_from_slice(&self.x);
        let (mut window_steps, mut window_time) = (0u32, 0.0);
        let mut last = StepStats::default();
        for k in 1..=criteria.max_steps {
            last = match self.step_to(accuracy) {
                Ok(stats) => stats,
                // Stopped inside the step: the state is the last good step's.
                Err(SimError::Interrupted { .. }) => {
                    return Ok(RestOutcome {
                        reason: StopReason::Stopped,
                        steps: k - 1,
                        last,
                    })
                }
                Err(e) => return Err(e),
            };
            if observe(self, &last).is_break() {
                return Ok(RestOutcome {
                    reason: StopReason::Stopped,
                    steps: k,
                    last,
                });
            }
            let h = self.settings.time_step;
            window_steps += 1;
            window_time += h;
            if window_steps >= criteria.consecutive_steps && window_time >= MIN_WINDOW {
                // The tolerance is per step of the solver's length: the window's budget
                // grows with its time as the steps do.
                let budget = criteria.tolerance * window_time / base;
                // Nor is cloth at rest that is still being pulled out of itself: the few
                // particles moved are within the fraction allowed to move.
                let pulling = self.self_contacts.as_ref().is_some_and(|sc| sc.pulling_apart());
                if !pulling && moved_farther(&self.x, &self.ws.rest_anchor, budget) <= allowed {
                    return Ok(RestOutcome {
                        reason: StopReason::AtRest,
                        steps: k,
                        last,
                    });
                }
                self.ws.rest_anchor.copy_from_slice(&self.x);
                (window_steps, window_time) = (0, 0.0);
            }
            if let Some(most) = criteria.max_time_step {
                self.settings.time_step = next_time_step(h, base, most, &last);
            }
        }
        Ok(RestOutcome {
            reason: StopReason::StepLimit,
            steps: criteria.max_steps,
            last,
        })
    }

    /// The step's constraints: the pins, then the active contacts (a pin wins).
    pub(super) fn refill_filter(&mut self, h: f64) -> Result<(), ConstraintError> {
        let filter = &mut self.ws.filter;
        filter.clear();
        for (pin, target) in self.pins.iter().zip(&self.ws.pin_targets) {
            filter.push(&Constraint {
                particle: pin.particle,
                kind: ConstraintKind::Fixed,
                velocity: (target - self.x[pin.particle]) / h,
            })?;
        }
        if let Some(contacts) = &self.contacts {
            contacts.particles.push_constraints(filter)?;
        }
        Ok(())
    }

    /// The start-of-step contact passes, on one view of the step's start: the cloth's
    /// contacts with itself found, then the bodies' chosen. A particle lying on another
    /// layer of the cloth that lies between it and the body is the other layer's to hold:
    /// held by the body too, at the body's own contact distance, it would be pressed into
    /// that layer. Returns the seconds the cloth's own search took.
    fn start_contacts(&mut self, h: f64) -> f64 {
        let start = StepStart {
            t0: self.time,
            h,
            x: &self.x,
            v: &self.v,
            masses: self.model.masses(),
            pinned: &self.pinned,
            implicit: self.settings.integrator == Integrator::ImplicitEuler,
            par: self.settings.parallelism(),
        };
        let clock = Instant::now();
        if let Some(sc) = &mut self.self_contacts {
            sc.detect(&start);
        }
        let detection = clock.elapsed().as_secs_f64();
        if let Some(contacts) = &mut self.contacts {
            let sc = self.self_contacts.as_ref();
            contacts.particles.constrain(&start, |i, normal| {
                sc.is_some_and(|sc| sc.lies_on_cloth(i, normal))
            });
            contacts.detect_features(&start, self.mesh.triangles());
        }
        detection
    }

    /// The end-of-step contact passes, on one view of the step's end: the bodies' first,
    /// then the cloth's against itself, in which particles pinned or held by a body do
    /// not yield. Unless `unbounded`, the cloth's passes give up past a budget of impacts,
    /// and this returns the budget.
    fn finish_contacts(&mut self, h: f64, unbounded: bool, stats: &mut StepStats) -> Option<usize> {
        let ws = &mut self.ws;
        let mut end = StepEnd {
            t0: self.time,
            h,
            x0: &self.x,
            x1: &mut ws.x_new,
            v1: &mut ws.v_new,
            masses: self.model.masses(),
            pinned: &self.pinned,
            support: &mut ws.support,
            par: self.settings.parallelism(),
        };
        if let Some(contacts) = &mut self.contacts {
            let start = Instant::now();
            stats.contacts = contacts.particles.active.iter().filter(|c| c.live).count();
            stats.feature_contacts = contacts.feature_contacts();
            let counts = contacts.finish_step(&mut end, self.mesh.triangles());
            stats.contact_corrections = counts.corrected;
            stats.crossings = counts.crossings;
            stats.feature_corrections = counts.features;
            stats.contact_seconds = start.elapsed().as_secs_f64();
        } else if self.self_contacts.is_some() {
            // No body holds anything; with bodies, their passes write all of it.
            end.support.fill(Vec3::zeros());
        }
        let sc = self.self_contacts.as_mut()?;
        let budget = (!unbounded).then(|| IMPACTS_PER_PARTICLE * self.x.len());
        let start = Instant::now();
        stats.self_contacts = sc.contacts.len();
        let interrupt = &self.interrupt;
        let counts = sc.resolve(&mut end, budget, || interrupt.is_raised());
        if let Some(contacts) = &mut self.contacts {
            for (i, d) in sc.shifted() {
                contacts.particles.displaced(i, d);
            }
        }
        stats.self_impacts = counts.impacts;
        stats.self_zone_particles = counts.zone_particles;
        stats.self_frozen = counts.frozen;
        stats.self_unresolved = counts.unresolved;
        stats.self_collision_seconds += start.elapsed().as_secs_f64();
        budget.filter(|_| counts.over_budget)
    }

    /// The edge-triangle pairs of the cloth that pass through each other now. Exempt are
    /// the pairs self-collision exempts: those sharing a particle or joined by a seam, and
    /// those within a few thicknesses of each other in the flat cloth (see
    /// [`Simulation::self_exemption_radius`]).
    pub fn self_intersections(&self) -> Intersections {
        match &self.self_contacts {
            Some(sc) => sc.intersections(&self.x),
            None => crate::self_contact::count_self_intersections(
                &self.mesh,
                &self.joined,
                self.self_exemption_radius(),
                &self.x,
            ),
        }
    }

    /// The cloth's edges passing through a body's triangles now, counted edge-triangle pair
    /// by pair as [`Simulation::self_intersections`] counts the cloth's own (0 without
    /// bodies), but for the thin parts that pieces passing them for good cross.
    pub fn body_intersections(&self) -> usize {
        self.body_intersections_apart().crossings
    }

    /// The body intersections, with the crossings of thin parts by pieces passing them for
    /// good apart.
    pub fn body_intersections_apart(&self) -> crate::BodyIntersections {
        self.contacts.as_ref().map_or_else(Default::default, |c| {
            crate::contact::count_body_intersections(
                c.collider.as_ref(),
                self.time,
                &self.mesh,
                &self.x,
                &self.passes_thin_parts(),
            )
        })
    }

    /// Per particle, whether it passes the bodies' thin parts for the whole simulation.
    pub fn passes_thin_parts(&self) -> Vec<bool> {
        let mut flags = vec![false; self.x.len()];
        for piece in self.passing().iter().filter(|p| !p.until_out) {
            for &i in &piece.members {
                if let Some(f) = flags.get_mut(i) {
                    *f = true;
                }
            }
        }
        flags
    }

    /// The pieces still passing through the bodies (see [`SimulationBuilder::pass_through`]).
    pub fn passing(&self) -> Vec<PassThrough> {
        self.contacts
            .as_ref()
            .map_or_else(Vec::new, |c| c.particles.passing().cloned().collect())
    }

    /// The pieces of the cloth that passed through each other at the start (see
    /// [`Tangle`]), and when each came apart.
    pub fn tangles(&self) -> &[Tangle] {
        &self.tangles
    }

    /// Lets each of `passes` through its layer from now on (see [`LayerPass`]); without
    /// self-collision they have nothing to pass. A particle that is not the cloth's is
    /// refused, and no pass is added.
    pub fn add_layer_passes(
        &mut self,
        passes: impl IntoIterator<Item = LayerPass>,
    ) -> Result<(), ParamError> {
        let passes: Vec<LayerPass> = passes.into_iter().collect();
        let all = passes.iter().flat_map(|p| p.layer.iter().chain(&p.side));
        particles_of_cloth("layer_passes", all, self.x.len())?;
        self.passes.extend(passes.into_iter().map(|pass| LayerPassing {
            pass,
            crossed: false,
            ended: None,
        }));
        self.exempt_passes();
        Ok(())
    }

    /// Ends every layer pass still holding: the cloth collides with all of itself again.
    pub fn end_layer_passes(&mut self) {
        for p in self.passes.iter_mut().filter(|p| p.ended.is_none()) {
            p.ended = Some(self.steps);
        }
        self.exempt_passes();
    }

    /// The layer passes given, and how each went.
    pub fn layer_passes(&self) -> &[LayerPassing] {
        &self.passes
    }

    /// The triangles the segment between each of `pairs` (particle pairs, such as a
    /// seam's) passes through now, as (pair, triangle), sorted; triangles near either
    /// particle in the mesh or in the flat cloth are not counted. Empty without
    /// self-collision.
    pub fn cloth_across(&self, pairs: &[[usize; 2]]) -> Result<Vec<(usize, usize)>, ParamError> {
        particles_of_cloth("pairs", pairs.iter().flatten(), self.x.len())?;
        Ok(self
            .self_contacts
            .as_ref()
            .map_or_else(Vec::new, |sc| sc.across_pairs(&self.x, pairs)))
    }

    /// Gives the self-collision the passes still holding.
    fn exempt_passes(&mut self) {
        if let Some(sc) = self.self_contacts.as_mut() {
            sc.set_passes(self.passes.iter().filter(|p| p.ended.is_none()).map(|p| &p.pass));
        }
    }

    /// Ends the layer passes whose sides have passed through each other and are apart.
    fn end_passed(&mut self) {
        let Some(sc) = self.self_contacts.as_ref() else {
            return;
        };
        let mut ended = false;
        // In the order the self-collision was given them (see `exempt_passes`).
        for (k, p) in self.passes.iter_mut().filter(|p| p.ended.is_none()).enumerate() {
            if sc.pass_crossings(k, &self.x) > 0 {
                p.crossed = true;
            } else if p.crossed {
                p.ended = Some(self.steps);
                ended = true;
            }
        }
        if ended {
            self.exempt_passes();
        }
    }

    /// Pulls the cloth out of itself where it passes through itself, and lets the tangled
    /// pieces that have come apart collide again.
    fn release_tangles(&mut self) {
        let Some(sc) = self.self_contacts.as_mut() else {
            return;
        };
        sc.pull_apart(&mut self.x);
        self.release_untangled();
    }

    /// Lets the tangled pieces that no longer pass through each other collide again.
    fn release_untangled(&mut self) {
        let Some(sc) = self.self_contacts.as_mut() else {
            return;
        };
        if !sc.has_tangles() {
            return;
        }
        for pair in sc.release_untangled(&self.x) {
            if let Some(t) = self
                .tangles
                .iter_mut()
                .find(|t| t.triangles == pair && t.released.is_none())
            {
                t.released = Some(self.steps);
            }
        }
    }

    /// The particle pairs the seams given to the builder pull together.
    pub fn seams(&self) -> &[[usize; 2]] {
        &self.seams
    }

    /// Pairs of the cloth within this of each other in the flat cloth are exempt from
    /// self-collision and from its measures, m: a few times the contact distance between
    /// layers.
    pub fn self_exemption_radius(&self) -> f64 {
        let thickest = self.settings.self_collision.thickness.unwrap_or_else(|| {
            self.model
                .fabrics()
                .iter()
                .map(|f| f.thickness)
                .fold(0.0, f64::max)
        });
        crate::self_contact::rest_radius(thickest)
    }

    /// The cloth's contacts with itself in the last step (none without self-collision).
    pub fn self_contacts(&self) -> &[crate::self_contact::Contact] {
        self.self_contacts.as_ref().map_or(&[], |sc| &sc.contacts)
    }

    /// The smallest distance of a particle from a triangle of the cloth now (pairs
    /// sharing a particle, or joined by a seam, exempt), if one is under `within` (m).
    pub fn closest_self_approach(&self, within: f64) -> Option<f64> {
        match &self.self_contacts {
            Some(sc) => sc.closest_approach(&self.x, within),
            None => crate::self_contact::closest_self_approach(
                &self.mesh,
                &self.joined,
                self.self_exemption_radius(),
                &self.x,
                within,
            ),
        }
    }

    /// The particles' contact modes in the last step (all `Free` without bodies).
    pub fn contact_modes(&self) -> impl Iterator<Item = crate::contact::ContactMode> + '_ {
        (0..self.x.len()).map(|i| match &self.contacts {
            Some(c) => c.particles.state[i].mode,
            None => crate::contact::ContactMode::Free,
        })
    }
}

/// Substeps in a row that must succeed before the substep length doubles again.
const EASY_SUBSTEPS: u32 = 4;

/// The step after one of length `h` that went as `last`, on the way to rest from steps of
/// `base` that may grow to `most`: [`GROWTH`] times longer after a step taken whole, by
/// an implicit solve that converged, back to `base` after one taken in substeps (a retry
/// always is), so the shortest substep stays what the solver's settings allow.
fn next_time_step(h: f64, base: f64, most: f64, last: &StepStats) -> f64 {
    if last.smallest_substep < h {
        base
    } else if last.cg_converged {
        (GROWTH * h).min(most)
    } else {
        h
    }
}

/// How many particles are `distance` or farther from where they were.
fn moved_farther(x: &[Vec3], before: &[Vec3], distance: f64) -> usize {
    let d2 = distance * distance;
    x.iter()
        .zip(before)
        .filter(|(a, b)| (*a - *b).norm_squared() >= d2)
        .count()
}

/// How much a step taken whole lets the next grow.
const GROWTH: f64 = 1.25;

/// The impacts a substep's passes may find, per particle of the cloth, before the substep
/// is taken again at half the length: a step whose layers rush through each other finds
/// more impacts in each pass than the last (31,000 growing to 249,000 on a GarmentCode
/// skirt, 28 s a pass); a shorter one finds few.
const IMPACTS_PER_PARTICLE: usize = 2;

/// The self-collision of a simulation with these settings, if they enable it.
fn self_contacts_for(
    mesh: &ClothMesh,
    seams: &[[usize; 2]],
    settings: &SolverSettings,
    model: &ForceModel,
    pinned: &[bool],
) -> Option<SelfContacts> {
    let sc = &settings.self_collision;
    if !sc.enabled {
        return None;
    }
    let fabrics = model.fabrics();
    let of = model.particle_fabrics();
    let stiffest = fabrics.iter().map(Fabric::membrane_stiffness).fold(0.0, f64::max);
    Some(SelfContacts::new(
        mesh,
        seams,
        model.masses(),
        pinned,
        sc,
        LayerFabric {
            thickness: |i: usize| fabrics[of[i]].thickness,
            friction: |i: usize| fabrics[of[i]].friction,
            membrane_stiffness: stiffest,
        },
    ))
}

/// Refuses a state array that is not one finite vector per particle.
/// Refuses the first of `particles` that is not one of the `n` particles of the cloth.
fn particles_of_cloth<'a>(
    name: &'static str,
    mut particles: impl Iterator<Item = &'a usize>,
    n: usize,
) -> Result<(), ParamError> {
    match particles.find(|&&i| i >= n) {
        Some(&i) => Err(ParamError::OutOfRange {
            name,
            value: i as f64,
            expected: "particles of the mesh",
        }),
        None => Ok(()),
    }
}

fn per_particle(name: &'static str, values: &[Vec3], n: usize) -> Result<(), ParamError> {
    if values.len() != n {
        return Err(ParamError::OutOfRange {
            name,
            value: values.len() as f64,
            expected: "one vector per particle",
        });
    }
    if let Some(c) = values.iter().flat_map(|v| v.iter()).find(|c| !c.is_finite()) {
        return Err(ParamError::OutOfRange {
            name,
            value: *c,
            expected: "finite components",
        });
    }
    Ok(())
}

fn kinetic_energy(masses: &[f64], v: &[Vec3]) -> f64 {
    0.5 * masses
        .iter()
        .zip(v)
        .map(|(m, vi)| m * vi.norm_squared())
        .sum::<f64>()
}

/// One finite weight >= 0 for each of `pairs` seam pairs.
fn check_seam_weights(weights: &[f64], pairs: usize) -> Result<(), ParamError> {
    ParamError::check(
        weights.len() == pairs,
        "seam_weights",
        weights.len() as f64,
        "one weight per seam pair",
    )?;
    match weights.iter().find(|w| !(w.is_finite() && **w >= 0.0)) {
        Some(&w) => Err(ParamError::OutOfRange {
            name: "seam_weights",
            value: w,
            expected: "finite weights >= 0",
        }),
        None => Ok(()),
    }
}

/// Attachments on particles of a cloth of `n`, with finite points and unit directions.
fn check_attachments(attachments: &[Attachment], n: usize) -> Result<(), ParamError> {
    match attachments.iter().find(|a| {
        a.particle >= n || !a.point.iter().all(|c| c.is_finite()) || (a.direction.norm() - 1.0).abs() > 1e-9
    }) {
        Some(a) => Err(ParamError::OutOfRange {
            name: "attachments",
            value: a.particle as f64,
            expected: "particles of the mesh, finite points and unit directions",
        }),
        None => Ok(()),
    }
}
