use crate::contact_scene::{ContactScene, ContactSceneError};
use crate::sheets::horizontal_sheet;
use cloth_collide::{Body, Motion, TriSurface};
use cloth_core::math::Vec3;
use nalgebra::{Isometry3, Unit};

/// A small sheet lying on top of a sphere that turns about the vertical axis: friction
/// makes the sheet turn with it.
#[derive(Debug, Clone)]
pub struct TurningSphere {
    pub particles_per_side: usize,
    pub sheet_size: f64,
    pub radius: f64,
    /// Turning rate, rad/s (about +z).
    pub rate: f64,
    pub friction: f64,
    pub thickness: f64,
    pub time_step: f64,
}

impl Default for TurningSphere {
    fn default() -> Self {
        Self {
            particles_per_side: 21,
            sheet_size: 0.3,
            radius: 0.25,
            rate: 1.0,
            friction: 1.0,
            thickness: 0.003,
            time_step: 1.0 / 60.0,
        }
    }
}

impl TurningSphere {
    pub fn build(&self) -> Result<ContactScene, ContactSceneError> {
        let sphere = TriSurface::sphere(self.radius, 64, 32)?;
        let body = Body::new("turning sphere", sphere)
            .with_motion(Motion::Spin {
                pose: Isometry3::identity(),
                center: Vec3::zeros(),
                axis: Unit::new_normalize(Vec3::z()),
                rate: self.rate,
            })?
            .with_thickness(self.thickness)?
            .with_friction(self.friction)?;
        let top = Vec3::new(0.0, 0.0, self.radius + self.thickness);
        let sheet = horizontal_sheet(self.particles_per_side, self.sheet_size, top, self.time_step)?;
        ContactScene::new(body, sheet)
    }
}
