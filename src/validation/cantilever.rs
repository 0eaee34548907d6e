//! The cantilever bending test (Peirce; ASTM D1388): a 2.5 cm strip over the edge of a
//! platform, bending under its own weight.
//!
//! The part of the strip on the platform is held flat there, as under the test's ruler:
//! its particles are pinned, and the overhang starts at the platform's edge, the last
//! pinned column. The strip runs along the warp, so the warp rigidity bends it.

use super::elastica::elastica_tip;
use super::{settle, ValidationError};
use cloth_core::{math::Vec3, Fabric, GridBuilder, GridShape, Pin, RestCriteria, SimulationBuilder};

/// Width of the test strip, m.
pub const STRIP_WIDTH: f64 = 0.025;
/// Fixed-angle test: the chord to the tip reaches this angle below the edge at an
/// overhang of twice the bending length.
pub const FIXED_ANGLE_DEGREES: f64 = 41.5;

/// One cantilever: a fabric, the overhang, and the mesh's cells along the overhang.
#[derive(Debug, Clone)]
pub struct Cantilever {
    pub fabric: Fabric,
    /// Overhang, m.
    pub overhang: f64,
    /// Square cells along the overhang (the width gets as many as fit).
    pub cells: usize,
}

/// The strip at rest.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CantileverRest {
    /// Drop of the tip below the platform, m (mean over the tip's particles).
    pub drop: f64,
    /// Horizontal reach of the tip beyond the edge, m.
    pub reach: f64,
    pub steps: u64,
}

impl CantileverRest {
    /// Angle of the chord from the edge to the tip below the horizontal, rad.
    pub fn chord_angle(&self) -> f64 {
        self.drop.atan2(self.reach)
    }
}

/// Weight per unit area, N/m^2.
fn weight(fabric: &Fabric) -> f64 {
    fabric.area_density * 9.81
}

/// The bending length `(B/w)^(1/3)` of the fabric's warp, m.
pub fn bending_length(fabric: &Fabric) -> f64 {
    (fabric.bending.warp / weight(fabric)).cbrt()
}

impl Cantilever {
    /// The overhang at which the fabric's `Gamma = w L^3 / B` takes the given value.
    pub fn at_gamma(fabric: Fabric, gamma: f64, cells: usize) -> Self {
        let overhang = bending_length(&fabric) * gamma.cbrt();
        Self {
            fabric,
            overhang,
            cells,
        }
    }

    pub fn gamma(&self) -> f64 {
        weight(&self.fabric) * self.overhang.powi(3) / self.fabric.bending.warp
    }

    /// The inextensible elastica's tip drop / L at this Gamma.
    pub fn reference_drop(&self) -> f64 {
        elastica_tip(self.gamma()).drop
    }

    /// Runs the strip to rest (1 nm per step for 20 steps).
    pub fn run(&self) -> Result<CantileverRest, ValidationError> {
        let (builder, grid) = self.simulation_builder()?;
        let mut sim = builder.build()?;
        let criteria = RestCriteria {
            max_time_step: None,
            tolerance: 1e-9,
            consecutive_steps: 20,
            max_steps: 5000,
            moving_fraction: 0.0,
        };
        let steps = settle(&mut sim, &criteria, "cantilever")?;
        let (drop, reach) = tip(sim.positions(), grid);
        Ok(CantileverRest { drop, reach, steps })
    }

    /// The strip, flat, its platform part pinned, and its grid (for [`tip`]).
    pub fn simulation_builder(&self) -> Result<(SimulationBuilder, GridShape), ValidationError> {
        let d = self.overhang / self.cells as f64;
        let across = ((STRIP_WIDTH / d).round() as usize).max(2);
        // Column 0 and 1 are on the platform (two columns fix the slope at the edge).
        let (nx, ny) = (self.cells + 2, across + 1);
        let mesh = GridBuilder::new(nx, ny)
            .spacing(d, STRIP_WIDTH / across as f64)
            .build()?;
        let g = mesh.grid().expect("a grid mesh");
        let pins = (0..ny).flat_map(|j| [Pin::fixed(g.index(0, j)), Pin::fixed(g.index(1, j))]);
        Ok((SimulationBuilder::new(mesh, self.fabric.clone()).pins(pins), g))
    }
}

/// The tip's drop below the platform and its reach beyond the edge, m (means over the tip's
/// particles), of a strip made by [`Cantilever::simulation_builder`].
pub fn tip(x: &[Vec3], g: GridShape) -> (f64, f64) {
    let edge = x[g.index(1, 0)];
    let last = g.nx - 1;
    let mean = |f: &dyn Fn(usize) -> f64| (0..g.ny).map(f).sum::<f64>() / g.ny as f64;
    (
        mean(&|j| edge.z - x[g.index(last, j)].z),
        mean(&|j| x[g.index(last, j)].x - edge.x),
    )
}

/// The fixed-angle test's result.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixedAngle {
    /// Overhang at which the chord to the tip is at 41.5 degrees, m.
    pub overhang: f64,
    /// Half of it: the test's bending length, m.
    pub bending_length: f64,
    /// Strips run to rest in the search.
    pub runs: usize,
}

/// The fixed-angle test: the strip is pushed over the edge a cell of `cell` (m) at a
/// time until the chord to its tip passes 41.5 degrees; the overhang at that angle is
/// interpolated between the last two, and the bending length is half of it. The search
/// starts near twice the bending length `(B/w)^(1/3)`, which only saves runs.
pub fn fixed_angle(fabric: &Fabric, cell: f64) -> Result<FixedAngle, ValidationError> {
    let target = FIXED_ANGLE_DEGREES.to_radians();
    let mut runs = 0;
    let mut angle = |cells: usize| {
        runs += 1;
        Cantilever {
            fabric: fabric.clone(),
            overhang: cells as f64 * cell,
            cells,
        }
        .run()
        .map(|r| r.chord_angle())
    };
    let mut k = ((2.0 * bending_length(fabric) / cell).round() as usize).max(2);
    let mut a = angle(k)?;
    // Walk towards the crossing until it lies between k and its neighbour.
    let step_up = a < target;
    loop {
        let next = if step_up { k + 1 } else { k - 1 };
        if !(1..=10_000).contains(&next) {
            return Err(ValidationError::NoCrossing { cells: next });
        }
        let b = angle(next)?;
        if (b >= target) == step_up {
            let (k0, a0, k1, a1) = if step_up { (k, a, next, b) } else { (next, b, k, a) };
            let overhang = cell * (k0 as f64 + (target - a0) / (a1 - a0) * (k1 - k0) as f64);
            return Ok(FixedAngle {
                overhang,
                bending_length: 0.5 * overhang,
                runs,
            });
        }
        (k, a) = (next, b);
    }
}
