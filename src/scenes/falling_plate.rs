use super::{scene_fabric, square_sheet, Scene, SceneError};
use crate::collide::{Body, TriSurface};
use cloth_core::{SimulationBuilder, Vec3};

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
    pub fn build(&self) -> Result<Scene, SceneError> {
        let half = 0.5 * self.plate_size;
        let plate = TriSurface::cuboid(Vec3::new(half, half, 0.5 * self.plate_thickness))?;
        let pose = nalgebra::Isometry3::translation(0.0, 0.0, -0.5 * self.plate_thickness);
        let body = Body::new("plate", plate)
            .with_pose(pose)?
            .with_thickness(self.thickness)?;
        let centre = Vec3::new(0.0, 0.0, self.drop_height);
        let mesh = square_sheet(
            self.particles_per_side,
            self.sheet_size,
            centre,
            Vec3::x(),
            Vec3::y(),
        )?;
        let n = mesh.vertex_count();
        Scene::new(
            body,
            SimulationBuilder::new(mesh, scene_fabric())
                .time_step(self.time_step)
                .velocities(vec![Vec3::new(0.0, 0.0, -self.speed); n]),
        )
    }
}
