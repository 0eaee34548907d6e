use crate::contact_scene::{ContactScene, ContactSceneError};
use crate::sheets::horizontal_sheet;
use cloth_collide::{Body, TriSurface};
use cloth_core::math::Vec3;

/// A square sheet dropped flat onto a sphere at the origin, centred over it.
#[derive(Debug, Clone)]
pub struct SphereDrop {
    pub particles_per_side: usize,
    pub sheet_size: f64,
    pub radius: f64,
    /// Longitudes of the UV sphere (a multiple of 8 keeps the scene's symmetries).
    pub segments: usize,
    pub rings: usize,
    /// Height of the sheet above the sphere's top at the start, m.
    pub drop_height: f64,
    pub friction: f64,
    pub thickness: f64,
    pub time_step: f64,
}

impl Default for SphereDrop {
    fn default() -> Self {
        Self {
            particles_per_side: 41,
            sheet_size: 1.0,
            radius: 0.25,
            segments: 64,
            rings: 32,
            drop_height: 0.02,
            friction: 0.5,
            thickness: 0.003,
            time_step: 1.0 / 60.0,
        }
    }
}

impl SphereDrop {
    pub fn build(&self) -> Result<ContactScene, ContactSceneError> {
        let sphere = TriSurface::sphere(self.radius, self.segments, self.rings)?;
        let body = Body::new("sphere", sphere)
            .with_thickness(self.thickness)?
            .with_friction(self.friction)?;
        let top = Vec3::new(0.0, 0.0, self.radius + self.thickness + self.drop_height);
        let sheet = horizontal_sheet(self.particles_per_side, self.sheet_size, top, self.time_step)?;
        ContactScene::new(body, sheet)
    }
}
