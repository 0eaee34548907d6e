use crate::contact_scene::{ContactScene, ContactSceneError};
use crate::sheets::scene_fabric;
use cloth_collide::{Body, TriSurface};
use cloth_core::{math::Vec3, GridBuilder, SimulationBuilder};
use nalgebra::Isometry3;

/// A long strip of cloth standing on its end just above the floor, leaning, let fall: it
/// crumples onto the floor and folds over itself, layer on layer.
#[derive(Debug, Clone)]
pub struct FoldingStrip {
    pub width: f64,
    pub length: f64,
    pub particles_across: usize,
    pub particles_along: usize,
    /// Lean of the strip from the vertical, degrees.
    pub lean: f64,
    /// Height of its lower end above the floor's contact layer, m.
    pub drop_height: f64,
    pub friction: f64,
    /// The floor's contact thickness, m.
    pub thickness: f64,
    pub time_step: f64,
}

impl Default for FoldingStrip {
    fn default() -> Self {
        Self {
            width: 0.2,
            length: 1.0,
            particles_across: 9,
            particles_along: 41,
            lean: 8.0,
            drop_height: 0.01,
            friction: 0.5,
            thickness: 0.003,
            time_step: 1.0 / 60.0,
        }
    }
}

impl FoldingStrip {
    pub fn build(&self) -> Result<ContactScene, ContactSceneError> {
        let floor = Body::new("floor", TriSurface::cuboid(Vec3::new(1.5, 1.5, 0.05))?)
            .with_pose(Isometry3::translation(0.0, 0.0, -0.05))?
            .with_thickness(self.thickness)?
            .with_friction(self.friction)?;
        let lean = self.lean.to_radians();
        // Leaning across its own plane, so it falls over and buckles.
        let along = Vec3::new(0.0, lean.sin(), lean.cos());
        let origin = Vec3::new(
            -0.5 * self.width,
            -0.5 * self.length * lean.sin(),
            self.thickness + self.drop_height,
        );
        let mesh = GridBuilder::new(self.particles_across, self.particles_along)
            .size(self.width, self.length)
            .origin(origin)
            .axes(Vec3::x(), along)
            .build()?;
        ContactScene::new(
            floor,
            SimulationBuilder::new(mesh, scene_fabric()).time_step(self.time_step),
        )
    }
}
