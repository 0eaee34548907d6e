use crate::contact_scene::{ContactScene, ContactSceneError};
use crate::sheets::{scene_fabric, two_sheets};
use cloth_collide::{Body, TriSurface};
use cloth_core::{math::Vec3, SimulationBuilder};
use nalgebra::Isometry3;

/// A sheet lying on a block, and a second sheet thrown down onto it fast: it travels
/// several times the cloth's thickness every step.
#[derive(Debug, Clone)]
pub struct SheetOntoSheet {
    pub particles_per_side: usize,
    pub sheet_size: f64,
    /// The block's top is this wide and at z = 0.
    pub block_size: f64,
    /// Height of the falling sheet above the lying one at the start, m.
    pub height: f64,
    /// Its downward speed at the start, m/s.
    pub speed: f64,
    /// Turn of the falling sheet about the vertical, degrees.
    pub turn: f64,
    pub friction: f64,
    /// The block's contact thickness, m.
    pub thickness: f64,
    pub time_step: f64,
}

impl Default for SheetOntoSheet {
    fn default() -> Self {
        Self {
            particles_per_side: 21,
            sheet_size: 0.4,
            block_size: 0.6,
            height: 0.05,
            speed: 5.0,
            turn: 20.0,
            friction: 0.5,
            thickness: 0.003,
            time_step: 1.0 / 60.0,
        }
    }
}

impl SheetOntoSheet {
    /// Particles of the lying sheet come first, then those of the falling one.
    pub fn build(&self) -> Result<ContactScene, ContactSceneError> {
        let half = 0.5 * self.block_size;
        let block = Body::new("block", TriSurface::cuboid(Vec3::new(half, half, 0.05))?)
            .with_pose(Isometry3::translation(0.0, 0.0, -0.05))?
            .with_thickness(self.thickness)?
            .with_friction(self.friction)?;
        let (mesh, count) = two_sheets(
            self.particles_per_side,
            self.sheet_size,
            Vec3::new(0.0, 0.0, self.thickness),
            Vec3::new(0.02, 0.01, self.height),
            self.turn,
        )?;
        let velocities = (0..mesh.vertex_count())
            .map(|i| {
                if i < count {
                    Vec3::zeros()
                } else {
                    Vec3::new(0.0, 0.0, -self.speed)
                }
            })
            .collect();
        ContactScene::new(
            block,
            SimulationBuilder::new(mesh, scene_fabric())
                .time_step(self.time_step)
                .velocities(velocities),
        )
    }
}
