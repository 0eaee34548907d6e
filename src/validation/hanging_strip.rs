//! A strip hanging from its top edge under its own weight: at rest the tension at the
//! top carries the weight below, so the strain there is the tensile law's inverse at that
//! tension, whatever the law's shape.

use super::{settle, ValidationError};
use cloth_core::{math::Vec3, Fabric, GridBuilder, Pin, RestCriteria, SimulationBuilder};

/// A strip of `length` x `width` (m) hanging along the weft (v) from pins on its top row.
#[derive(Debug, Clone)]
pub struct HangingStrip {
    pub fabric: Fabric,
    pub length: f64,
    pub width: f64,
    /// Rows of particles along the length.
    pub rows: usize,
}

/// The strip at rest: the strain of its top row of cells and the law's answer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HangingRest {
    pub top_strain: f64,
    /// Tension at the top, N/m: the weight of all but the pinned row's share.
    pub top_tension: f64,
    /// The weft law's strain at that tension.
    pub expected_strain: f64,
    pub steps: u64,
}

impl HangingStrip {
    pub fn run(&self) -> Result<HangingRest, ValidationError> {
        let columns = 6;
        let mesh = GridBuilder::new(columns, self.rows)
            .size(self.width, self.length)
            .axes(Vec3::x(), -Vec3::z())
            .build()?;
        let g = mesh.grid().expect("a grid mesh");
        let fabric = self.fabric.clone().with_damping(self.fabric.damping + 0.01);
        let mut sim = SimulationBuilder::new(mesh, fabric)
            .pins((0..columns).map(|i| Pin::fixed(g.index(i, 0))))
            .build()?;
        let criteria = RestCriteria {
            max_time_step: None,
            tolerance: 1e-8,
            consecutive_steps: 20,
            max_steps: 20_000,
            moving_fraction: 0.0,
        };
        let steps = settle(&mut sim, &criteria, "hanging strip")?;
        let x = sim.positions();
        let dv = self.length / (self.rows - 1) as f64;
        let top_strain = (0..columns)
            .map(|i| (x[g.index(i, 1)] - x[g.index(i, 0)]).norm() / dv - 1.0)
            .sum::<f64>()
            / columns as f64;
        // Lumped masses: the pinned row holds half a row of cells, the rest hangs.
        let top_tension = self.fabric.area_density * 9.81 * (self.length - 0.5 * dv);
        Ok(HangingRest {
            top_strain,
            top_tension,
            expected_strain: self.fabric.weft.strain_at(top_tension),
            steps,
        })
    }
}
