use crate::contact_scene::{ContactScene, ContactSceneError};
use crate::sheets::horizontal_sheet;
use cloth_collide::{Body, TriSurface};
use cloth_core::math::Vec3;

/// A square tablecloth dropped onto a square table, centred and aligned with it.
#[derive(Debug, Clone)]
pub struct Tablecloth {
    pub particles_per_side: usize,
    pub cloth_size: f64,
    pub table_size: f64,
    pub table_height: f64,
    pub top_thickness: f64,
    pub drop_height: f64,
    pub friction: f64,
    pub thickness: f64,
    pub time_step: f64,
}

impl Default for Tablecloth {
    fn default() -> Self {
        Self {
            particles_per_side: 41,
            cloth_size: 1.2,
            table_size: 0.8,
            table_height: 0.75,
            top_thickness: 0.04,
            drop_height: 0.02,
            friction: 0.5,
            thickness: 0.003,
            time_step: 1.0 / 60.0,
        }
    }
}

impl Tablecloth {
    pub fn build(&self) -> Result<ContactScene, ContactSceneError> {
        let half = 0.5 * self.table_size;
        let table = TriSurface::table(
            Vec3::new(half, half, 0.5 * self.top_thickness),
            self.table_height,
            0.03,
            0.05,
        )?;
        let body = Body::new("table", table)
            .with_thickness(self.thickness)?
            .with_friction(self.friction)?;
        let centre = Vec3::new(0.0, 0.0, self.table_height + self.thickness + self.drop_height);
        let sheet = horizontal_sheet(self.particles_per_side, self.cloth_size, centre, self.time_step)?;
        ContactScene::new(body, sheet)
    }
}
