use crate::contact_scene::{ContactScene, ContactSceneError};
use crate::sheets::{scene_fabric, square_sheet};
use cloth_collide::{Body, TriSurface};
use cloth_core::{math::Vec3, SimulationBuilder};
use nalgebra::{Isometry3, Translation3, UnitQuaternion};

/// A sheet lying on a large plate tilted by `angle` about the x axis (downhill is -y).
#[derive(Debug, Clone)]
pub struct TiltedPlane {
    pub particles_per_side: usize,
    pub sheet_size: f64,
    /// Tilt, rad.
    pub angle: f64,
    pub friction: f64,
    pub thickness: f64,
    pub time_step: f64,
}

impl Default for TiltedPlane {
    fn default() -> Self {
        Self {
            particles_per_side: 11,
            sheet_size: 0.2,
            angle: 0.3,
            friction: 0.5,
            thickness: 0.003,
            time_step: 1.0 / 120.0,
        }
    }
}

impl TiltedPlane {
    /// Unit vector down the slope, in the plate's plane.
    pub fn downhill(&self) -> Vec3 {
        self.tilt() * -Vec3::y()
    }
    /// The plate's outward normal (its top face).
    pub fn normal(&self) -> Vec3 {
        self.tilt() * Vec3::z()
    }
    fn tilt(&self) -> UnitQuaternion<f64> {
        UnitQuaternion::from_axis_angle(&Vec3::x_axis(), self.angle)
    }

    pub fn build(&self) -> Result<ContactScene, ContactSceneError> {
        // A 4 m plate 10 cm thick whose top face passes through the origin.
        let plate = TriSurface::cuboid(Vec3::new(2.0, 2.0, 0.05))?;
        let pose = Isometry3::from_parts(Translation3::from(-0.05 * self.normal()), self.tilt());
        let body = Body::new("tilted plate", plate)
            .with_pose(pose)?
            .with_thickness(self.thickness)?
            .with_friction(self.friction)?;
        let (u, v) = (self.tilt() * Vec3::x(), self.tilt() * Vec3::y());
        let mesh = square_sheet(
            self.particles_per_side,
            self.sheet_size,
            self.thickness * self.normal(),
            u,
            v,
        )?;
        ContactScene::new(
            body,
            SimulationBuilder::new(mesh, scene_fabric().with_drag(0.0)).time_step(self.time_step),
        )
    }
}
