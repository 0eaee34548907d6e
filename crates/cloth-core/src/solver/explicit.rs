//! Explicit (forward) Euler, as in the source, and symplectic Euler.

use super::error::SolveFailure;
use super::{Simulation, StepStats};
use std::time::Instant;

impl Simulation {
    /// Writes the next state into the workspace. Forward Euler moves with the old
    /// velocity; symplectic Euler with the new one. Pinned components take their
    /// prescribed velocity in both.
    pub(super) fn explicit_step(&mut self, h: f64, symplectic: bool) -> Result<StepStats, SolveFailure> {
        let start = Instant::now();
        let potential = self.evaluate(h, false);
        let assembly_seconds = start.elapsed().as_secs_f64();
        let (masses, ws) = (self.model.masses(), &mut self.ws);
        for i in 0..self.x.len() {
            ws.v_new[i] = self.v[i] + ws.force[i] * (h / masses[i]);
        }
        ws.filter.enforce_velocity(&mut ws.v_new);
        let mut released = 0;
        if let Some(contacts) = &mut self.contacts {
            let c = &mut contacts.particles;
            c.explicit_reactions(masses, &self.v, &ws.force, &ws.v_new, h);
            // A contact the body would have to pull lets go: the particle keeps its free velocity.
            for a in c.active.iter().filter(|a| a.live && a.pulls()) {
                let i = a.particle();
                ws.v_new[i] = self.v[i] + ws.force[i] * (h / masses[i]);
            }
            released = c.release_pulling(true);
            c.explicit_friction(masses, &mut ws.v_new, h);
            c.forget_demand();
        }
        if released > 0 {
            self.refill_filter(h)?;
        }
        let ws = &mut self.ws;
        let moving = if symplectic {
            &ws.v_new
        } else {
            ws.y.copy_from_slice(&self.v);
            ws.filter.enforce_velocity(&mut ws.y);
            &ws.y
        };
        for i in 0..self.x.len() {
            ws.x_new[i] = self.x[i] + h * moving[i];
        }
        Ok(StepStats {
            cg_converged: true,
            assembly_seconds,
            potential_energy: potential,
            ..Default::default()
        })
    }
}
