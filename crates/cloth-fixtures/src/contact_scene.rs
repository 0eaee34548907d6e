//! A contact scene: a simulation with the bodies it collides with, and why one cannot be
//! built.

use cloth_collide::{Bodies, Body, BodyError, SurfaceError};
use cloth_core::{MeshError, ParamError, Simulation, SimulationBuilder};
use std::sync::Arc;

/// A simulation with the bodies it collides with (kept to measure penetration).
#[derive(Debug)]
pub struct ContactScene {
    pub simulation: Simulation,
    pub bodies: Arc<Bodies>,
}

impl ContactScene {
    /// A scene of one body: the cloth of `simulation` collides with it.
    pub fn new(body: Body, simulation: SimulationBuilder) -> Result<Self, ContactSceneError> {
        let bodies = Arc::new(Bodies::new(vec![body]));
        let simulation = simulation.collider(bodies.clone()).build()?;
        Ok(Self { simulation, bodies })
    }

    /// How deep the deepest particle is inside a body now, m (0 when none is).
    pub fn deepest_penetration(&self) -> f64 {
        self.bodies
            .deepest_inside(self.simulation.time(), self.simulation.positions())
            .0
    }
}

/// Why a scene could not be built.
#[derive(Debug, thiserror::Error)]
pub enum ContactSceneError {
    #[error(transparent)]
    Surface(#[from] SurfaceError),
    #[error(transparent)]
    Body(#[from] BodyError),
    #[error(transparent)]
    Mesh(#[from] MeshError),
    #[error(transparent)]
    Param(#[from] ParamError),
}
