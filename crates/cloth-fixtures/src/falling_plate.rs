use crate::contact_scene::{ContactScene, ContactSceneError};
use crate::sheets::horizontal_sheet;
use cloth_collide::{Body, TriSurface};
use cloth_core::math::Vec3;

/// A sheet thrown down fast onto a thin plate: the tunnelling test.
#[derive(Debug, Clone)]
pub struct FallingPlate {
    pub particles_per_side: usize,
    pub sheet_size: f64,
    /// Downward speed at the start, m/s.
    pub speed: f64,
    /// Plate thickness, m (its top face at z = 0).
    pub plate_thickness: f64,
    pub plate_size: f64,
    pub drop_height: f64,
    pub thickness: f64,
    pub time_step: f64,
}

impl Default for FallingPlate {
    fn default() -> Self {
        Self {
            particles_per_side: 26,
            sheet_size: 0.5,
            speed: 10.0,
            plate_thickness: 0.002,
            plate_size: 1.0,
            drop_height: 0.1,
            thickness: 0.001,
            time_step: 1.0 / 60.0,
        }
    }
}

impl FallingPlate {
    pub fn build(&self) -> Result<ContactScene, ContactSceneError> {
        let half = 0.5 * self.plate_size;
        let plate = TriSurface::cuboid(Vec3::new(half, half, 0.5 * self.plate_thickness))?;
        let pose = nalgebra::Isometry3::translation(0.0, 0.0, -0.5 * self.plate_thickness);
        let body = Body::new("plate", plate)
            .with_pose(pose)?
            .with_thickness(self.thickness)?;
        let centre = Vec3::new(0.0, 0.0, self.drop_height);
        let n = self.particles_per_side;
        let sheet = horizontal_sheet(n, self.sheet_size, centre, self.time_step)?.velocities(vec![
            Vec3::new(
                0.0,
                0.0,
                -self.speed
            );
            n * n
        ]);
        ContactScene::new(body, sheet)
    }
}
