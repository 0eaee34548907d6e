//! What each step reports.

use serde::Serialize;

/// Statistics of one step.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct StepStats {
    /// Number of this step (1 for the first).
    pub step: u64,
    /// Simulation time at its end, s.
    pub time: f64,
    /// PCG iterations (0 for explicit integrators).
    pub cg_iterations: usize,
    /// Final relative PCG residual |r|/|b|.
    pub cg_residual: f64,
    /// Whether PCG met its tolerance (true for explicit integrators).
    pub cg_converged: bool,
    /// Wall time assembling forces and Jacobians, s.
    pub assembly_seconds: f64,
    /// Wall time in the linear solve (with filtering), s.
    pub solve_seconds: f64,
    /// Largest particle speed at the end of the step, m/s.
    pub max_speed: f64,
    /// Largest particle displacement during the step, m.
    pub max_displacement: f64,
    /// Kinetic energy at the end of the step, J.
    pub kinetic_energy: f64,
    /// Elastic plus gravitational energy at the start of the step, J.
    pub potential_energy: f64,
    /// Particles constrained by a body contact during the step.
    pub contacts: usize,
    /// Particles put back out to the contact thickness at the end of the step.
    pub contact_corrections: usize,
    /// Of those, particles whose path entered a body within the step.
    pub crossings: usize,
    /// Sharp body features under cloth triangles, held off by the feature penalty.
    pub feature_contacts: usize,
    /// Cloth triangles found pierced by a sharp feature at the end of the step and pushed
    /// back out.
    pub feature_corrections: usize,
    /// Wall time in the end-of-step contact passes, s.
    pub contact_seconds: f64,
    /// Pairs of the cloth closer than their contact distance, repelled in the step.
    pub self_contacts: usize,
    /// Pairs of the cloth found passing through each other in the step and turned back
    /// by impulses.
    pub self_impacts: usize,
    /// Particles moved as impact zones (pairs the impulses did not separate).
    pub self_zone_particles: usize,
    /// Particles stopped where they started the step, as the impact zones did not
    /// separate their pairs (the last resort).
    pub self_frozen: usize,
    /// Pairs found passing through each other that nothing could stop (pinned particles
    /// moved through the cloth).
    pub self_unresolved: usize,
    /// Wall time finding the cloth's contacts with itself and resolving its impacts, s.
    pub self_collision_seconds: f64,
    /// Substeps the step was taken in (1 at the full time step).
    pub substeps: u32,
    /// Substeps undone and taken again at half the length (diverged, solve failed or
    /// unconverged, impact passes over budget).
    pub retries: u32,
    /// The shortest substep taken, s.
    pub smallest_substep: f64,
}

impl StepStats {
    /// Adds a substep's work and counts to the step's; the state figures (speed, energy,
    /// residual) become the substep's, the last.
    pub(crate) fn add_substep(&mut self, s: &StepStats) {
        let first = self.substeps == 0;
        self.substeps += 1;
        self.cg_iterations += s.cg_iterations;
        self.cg_residual = s.cg_residual;
        self.cg_converged &= s.cg_converged;
        self.assembly_seconds += s.assembly_seconds;
        self.solve_seconds += s.solve_seconds;
        self.max_speed = s.max_speed;
        self.kinetic_energy = s.kinetic_energy;
        if first {
            self.potential_energy = s.potential_energy;
        }
        self.contacts = self.contacts.max(s.contacts);
        self.contact_corrections += s.contact_corrections;
        self.crossings += s.crossings;
        self.feature_contacts = self.feature_contacts.max(s.feature_contacts);
        self.feature_corrections += s.feature_corrections;
        self.contact_seconds += s.contact_seconds;
        self.self_contacts = self.self_contacts.max(s.self_contacts);
        self.self_impacts += s.self_impacts;
        self.self_zone_particles += s.self_zone_particles;
        self.self_frozen += s.self_frozen;
        self.self_unresolved += s.self_unresolved;
        self.self_collision_seconds += s.self_collision_seconds;
    }
}
