use crate::contact_scene::{ContactScene, ContactSceneError};
use crate::sheets::{scene_fabric, two_sheets};
use cloth_collide::{Body, TriSurface};
use cloth_core::{math::Vec3, SimulationBuilder};

/// Two square sheets, one a little above the other and turned against it, dropped
/// together onto a sphere: the upper one drapes over the lower.
#[derive(Debug, Clone)]
pub struct StackedSheets {
    pub particles_per_side: usize,
    pub sheet_size: f64,
    pub radius: f64,
    /// Gap between the two sheets at the start, m.
    pub gap: f64,
    /// Turn of the upper sheet about the vertical, degrees.
    pub turn: f64,
    /// Height of the lower sheet above the sphere's contact layer, m.
    pub drop_height: f64,
    pub friction: f64,
    /// The sphere's contact thickness, m.
    pub thickness: f64,
    pub time_step: f64,
}

impl Default for StackedSheets {
    fn default() -> Self {
        Self {
            particles_per_side: 25,
            sheet_size: 0.6,
            radius: 0.15,
            gap: 0.002,
            turn: 15.0,
            drop_height: 0.01,
            friction: 0.5,
            thickness: 0.003,
            time_step: 1.0 / 60.0,
        }
    }
}

impl StackedSheets {
    /// Particles of the lower sheet come first, then those of the upper.
    pub fn build(&self) -> Result<ContactScene, ContactSceneError> {
        let sphere = TriSurface::sphere(self.radius, 48, 24)?;
        let body = Body::new("sphere", sphere)
            .with_thickness(self.thickness)?
            .with_friction(self.friction)?;
        let (mesh, _) = two_sheets(
            self.particles_per_side,
            self.sheet_size,
            Vec3::new(0.0, 0.0, self.radius + self.thickness + self.drop_height),
            Vec3::new(0.0, 0.0, self.gap),
            self.turn,
        )?;
        ContactScene::new(
            body,
            SimulationBuilder::new(mesh, scene_fabric()).time_step(self.time_step),
        )
    }
}
