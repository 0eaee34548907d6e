//! Linearised backward Euler (Baraff & Witkin 1998):
//! `(M - h dF/dv - h^2 dF/dx) dv = h (F0 + h dF/dx v0)`, `dx = h (v0 + dv)`,
//! with the constraint filter in projected form.

use super::assembly::Loads;
use super::error::SolveFailure;
use super::{Simulation, StepStats};
use crate::forces::{ForceOutputs, StiffnessTarget};
use crate::linalg::{BlockSparse, FilteredSystem, Setup};
use crate::math::{Mat3, Vec3};
use std::time::Instant;

impl Simulation {
    /// Assembles, at the current state, the forces and the unfiltered system matrix
    /// `A = M + h C_drag + (h^2 + h beta) K` of an implicit step (K the PSD stiffness).
    /// Returns the potential energy. The step itself calls this; it is public for
    /// diagnostics and benchmarks.
    pub fn assemble_system(&mut self) -> f64 {
        self.evaluate(self.settings.time_step, true)
    }

    /// The forces on every particle at the current state (elastic, damping, gravity, drag).
    pub fn forces(&mut self) -> &[Vec3] {
        self.evaluate(self.settings.time_step, false);
        &self.ws.force
    }

    /// Forces (and `K v`) into the workspace, and with `with_stiffness` the system matrix
    /// of a step of length `h`; returns the potential energy.
    pub(super) fn evaluate(&mut self, h: f64, with_stiffness: bool) -> f64 {
        let s = &self.settings;
        let target = if with_stiffness {
            let model = &self.model;
            self.matrix.reset(s.parallelism(), |i| {
                Mat3::from_diagonal_element(model.masses()[i] + h * model.drag_coefficient(i))
            });
            Some(StiffnessTarget {
                matrix: &mut self.matrix,
                h,
            })
        } else {
            None
        };
        let ws = &mut self.ws;
        let mut energy = self.model.evaluate(
            &self.x,
            &self.v,
            &Loads {
                gravity: s.gravity,
                wind: s.wind,
            },
            ForceOutputs {
                force: &mut ws.force,
                hv: &mut ws.hv,
                stiffness: target,
            },
            s.parallelism(),
        );
        if let Some(contacts) = &self.contacts {
            let out = ForceOutputs {
                force: &mut ws.force,
                hv: &mut ws.hv,
                stiffness: with_stiffness.then_some(StiffnessTarget {
                    matrix: &mut self.matrix,
                    h,
                }),
            };
            energy += contacts.add_feature_penalty(&self.x, &self.v, out);
        }
        if let Some(sc) = &mut self.self_contacts {
            // An implicit step sets the friction between layers after a scouting solve;
            // an explicit one predicts it from the forces so far.
            if with_stiffness {
                sc.no_friction();
            } else {
                sc.explicit_friction(&self.v, &ws.force, h);
            }
            energy += sc.add_forces(&self.x, &self.v, &mut ws.force, &mut ws.hv);
            if with_stiffness {
                sc.couple(&mut self.matrix, h);
            }
        }
        energy
    }

    /// The system matrix of the last implicit step (unfiltered).
    pub fn system_matrix(&self) -> &BlockSparse {
        &self.matrix
    }

    /// Writes the next state into the workspace. Contacts whose body would have to pull
    /// are let go and the step solved again, up to [`RELEASE_PASSES`] times: a contact
    /// never holds the cloth to the body (but for those found pulling in the last solve,
    /// let go from the next step). With contacts, the first solve is a scout, to
    /// [`SCOUT_TOLERANCE`] times the tolerance: it finds most of the contacts to let go,
    /// so the solves to the full tolerance start with the right contacts more often (a
    /// median of 27 rather than 36 CG iterations a step for the sheet on the sphere).
    pub(super) fn implicit_step(
        &mut self,
        h: f64,
        velocity_accuracy: f64,
    ) -> Result<StepStats, SolveFailure> {
        let start = Instant::now();
        let potential = self.evaluate(h, true);
        let assembly_seconds = start.elapsed().as_secs_f64();

        let start = Instant::now();
        // b = h F0 - h^2 K v0 (F0 already holds the damping force -beta K v0).
        for ((b, f), kv) in self.ws.b.iter_mut().zip(&self.ws.force).zip(&self.ws.hv) {
            *b = h * f - (h * h) * kv;
        }
        // A >= M, so a residual of v |m| leaves an RMS velocity error of about v.
        let abs_tolerance = velocity_accuracy * self.model.mass_norm();
        let mut stats = StepStats {
            cg_converged: true,
            assembly_seconds,
            potential_energy: potential,
            ..Default::default()
        };
        if let Some(contacts) = &mut self.contacts {
            let masses = self.model.masses();
            contacts
                .particles
                .set_friction(h, &self.v, masses, &self.ws.force);
        }
        // Friction between layers waits for the scout's motion.
        let mut layer_friction = self.self_contacts.as_ref().is_some_and(|sc| sc.has_friction());
        let mut scouting = self.contacts.is_some() || layer_friction;
        // Solves so far, the scout's included (so a step makes no more solves than without
        // it), and what the next one keeps of the last one's preconditioner.
        let mut pass = 0;
        let mut setup = Setup::Build;
        // Whether the right-hand side changed since the last solve.
        let mut new_rhs = true;
        loop {
            // Going on with the same system (after a scout that let nothing go), the
            // friction, the prescribed velocities and the right-hand side stand.
            if std::mem::take(&mut new_rhs) {
                if let Some(contacts) = &mut self.contacts {
                    // Friction is part of the solve: b += h F_f(v0), A += h dF_f/dv.
                    contacts
                        .particles
                        .apply_friction(&self.v, &mut self.ws.b, &mut self.matrix, h);
                }
                let (s, ws) = (&self.settings, &mut self.ws);
                ws.filter.velocity_change(&self.v, &mut ws.z);
                ws.rhs.copy_from_slice(&ws.b);
                if !ws.filter.is_empty() {
                    self.matrix.mul(&ws.z, &mut ws.az, s.parallelism());
                    for (r, az) in ws.rhs.iter_mut().zip(&ws.az) {
                        *r -= az;
                    }
                    ws.filter.project(&mut ws.rhs);
                }
                ws.filter.project(&mut ws.y);
            }
            let (s, ws) = (&self.settings, &mut self.ws);
            let mut settings = s.pcg;
            if scouting {
                settings.rel_tolerance = (SCOUT_TOLERANCE * settings.rel_tolerance).min(0.5);
            }
            let outcome = ws.pcg.solve_with(
                FilteredSystem {
                    matrix: &self.matrix,
                    filter: &ws.filter,
                    rhs: &ws.rhs,
                },
                &mut ws.y,
                &settings,
                abs_tolerance,
                s.parallelism(),
                setup,
            )?;
            ws.filter.project(&mut ws.y);
            stats.cg_iterations += outcome.iterations;
            stats.cg_residual = outcome.rel_residual;
            stats.cg_converged &= outcome.converged;
            for ((dv, y), z) in ws.dv.iter_mut().zip(&ws.y).zip(&ws.z) {
                *dv = y + z;
            }
            // After the scout the step goes on to the full tolerance in any case: with the
            // same system if it let nothing go, else with the freed contacts (a re-solve
            // only frees directions: the preconditioner mostly serves).
            let last = !scouting && pass >= RELEASE_PASSES;
            let released = match &mut self.contacts {
                Some(contacts) => {
                    contacts.particles.implicit_reactions(
                        &self.matrix,
                        &ws.b,
                        &ws.dv,
                        h,
                        settings.rel_tolerance,
                    );
                    contacts.particles.release_pulling(!last)
                }
                None => 0,
            };
            // After the scout, friction between layers is set from its motion, and the step
            // solves again in any case.
            let friction_set = std::mem::take(&mut layer_friction);
            if friction_set {
                let sc = self.self_contacts.as_mut().expect("layer friction has contacts");
                for ((v_end, v), dv) in ws.v_new.iter_mut().zip(&self.v).zip(&ws.dv) {
                    *v_end = v + dv;
                }
                sc.friction_from_motion(&self.v, &ws.v_new, h, &mut ws.b, &mut self.matrix);
            } else if last || (released == 0 && !scouting) {
                break;
            }
            new_rhs = released > 0 || friction_set;
            if released > 0 {
                self.refill_filter(h)?;
            }
            setup = if friction_set || (released > 0 && self.matrix.has_transient()) {
                // Friction holding layers together couples them stiffly, and directions
                // freed where the cloth lies on itself are tied to the layer above, which
                // only coarse corrections reach: the hierarchy is made again (kept or
                // refreshed only at its finest level, it costs more iterations than the
                // setup saves, or is not even definite).
                Setup::Build
            } else if released == 0 {
                Setup::Keep
            } else {
                // The freed directions are missing from the kept coarse spaces; the cloth
                // alone lets the smoother make them good in a few iterations.
                Setup::RefreshFinest
            };
            scouting = false;
            pass += 1;
        }
        let ws = &mut self.ws;
        if let Some(contacts) = &mut self.contacts {
            // Friction predicts from this step's forces only if the solve found them.
            if stats.cg_converged {
                let (dv, v) = (&ws.dv, &self.v);
                contacts
                    .particles
                    .record_demand(v, |j| v[j] + dv[j], self.model.masses(), h);
            } else {
                contacts.particles.forget_demand();
            }
        }
        for i in 0..self.x.len() {
            let v: Vec3 = self.v[i] + ws.dv[i];
            ws.v_new[i] = v;
            ws.x_new[i] = self.x[i] + h * v;
        }
        stats.solve_seconds = start.elapsed().as_secs_f64();
        Ok(stats)
    }
}

/// Solves a step may make after its first, letting go of pulling contacts.
pub const RELEASE_PASSES: usize = 2;

/// The scouting solve's tolerance over the step's.
pub const SCOUT_TOLERANCE: f64 = 10.0;
