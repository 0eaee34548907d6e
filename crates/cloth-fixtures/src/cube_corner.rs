use crate::contact_scene::{ContactScene, ContactSceneError};
use crate::sheets::horizontal_sheet;
use cloth_collide::{Body, TriSurface};
use cloth_core::math::Vec3;
use nalgebra::{Isometry3, Translation3, UnitQuaternion};

/// A coarse sheet dropped onto a cube standing on one corner, so the top corner meets the
/// middle of a cloth triangle, not a particle.
#[derive(Debug, Clone)]
pub struct CubeCorner {
    pub particles_per_side: usize,
    pub sheet_size: f64,
    pub cube_size: f64,
    pub drop_height: f64,
    pub friction: f64,
    pub thickness: f64,
    /// Fold angle above which the cube's edges and corners are sharp features, rad
    /// (beyond pi: none, so only the particles collide).
    pub sharp_angle: f64,
    pub time_step: f64,
}

impl Default for CubeCorner {
    fn default() -> Self {
        Self {
            particles_per_side: 11,
            sheet_size: 0.6,
            cube_size: 0.3,
            drop_height: 0.05,
            friction: 0.5,
            thickness: 0.003,
            sharp_angle: cloth_collide::DEFAULT_SHARP_ANGLE,
            time_step: 1.0 / 120.0,
        }
    }
}

impl CubeCorner {
    /// The cube's pose: its (1, 1, 1) corner turned straight up, that corner at the origin.
    pub fn cube_pose(&self) -> Isometry3<f64> {
        let h = 0.5 * self.cube_size;
        let up = UnitQuaternion::rotation_between(&Vec3::new(1.0, 1.0, 1.0), &Vec3::z())
            .unwrap_or_else(UnitQuaternion::identity);
        let corner = up * Vec3::new(h, h, h);
        Isometry3::from_parts(Translation3::from(-corner), up)
    }

    pub fn build(&self) -> Result<ContactScene, ContactSceneError> {
        let h = 0.5 * self.cube_size;
        let cube = TriSurface::cuboid(Vec3::new(h, h, h))?;
        let body = Body::new("cube", cube)
            .with_pose(self.cube_pose())?
            .with_thickness(self.thickness)?
            .with_friction(self.friction)?
            .with_sharp_angle(self.sharp_angle)?;
        // Shift the sheet by a third of a cell so the corner is inside a triangle.
        let cell = self.sheet_size / (self.particles_per_side - 1) as f64;
        let centre = Vec3::new(cell / 3.0, cell / 5.0, self.thickness + self.drop_height);
        let sheet = horizontal_sheet(self.particles_per_side, self.sheet_size, centre, self.time_step)?;
        ContactScene::new(body, sheet)
    }
}
