//! Panels that touch at the start where no seam joins them. GarmentCode lays the godets
//! of a skirt side by side in the skirt's plane, each meeting the next at a hem corner,
//! and sews each into its own slit: the corners must part. Coincident, the cloth's
//! collision with itself held them together (a corner drawn out to three times its length
//! while the rest of its godet was sewn, the seam held 5 cm open at 1,024 times the pull);
//! so such points count as one to the self-collision while sewn, as seam partners do (see
//! `cloth_core::SimulationBuilder::touching`).

use super::Garment;
use cloth_core::math::Vec3;
use std::collections::HashMap;

/// Particles of different panels nearer than this touch, m. GarmentCode's touching corners
/// coincide to its coordinates' precision (under a micrometre); a tenth of a millimetre is
/// under any fabric's thickness, so points this near were in contact from the start.
pub const TOUCH: f64 = 1e-4;

/// Two panels touching at points no seam joins.
#[derive(Debug, Clone, PartialEq)]
pub struct Touching {
    pub panels: [String; 2],
    pub points: usize,
}

impl std::fmt::Display for Touching {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let [a, b] = &self.panels;
        write!(
            f,
            "panels '{a}' and '{b}' touch at {} point{} where no seam joins them: there they do not collide with each other while sewn",
            self.points,
            if self.points == 1 { "" } else { "s" }
        )
    }
}

impl Garment {
    /// Finds the particles of different panels within [`TOUCH`] of each other that no seam
    /// joins (directly or through other pairs), keeps them in [`Garment::touching`] for
    /// the sewing, and returns each pair of panels so touching.
    pub fn find_touching(&mut self) -> Vec<Touching> {
        let x = self.mesh.positions();
        let panel = self.particle_panels();
        let joined = self.seam_groups();
        let cell = |p: &Vec3| (p / TOUCH).map(|c| c.floor() as i64);
        let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
        for (i, p) in x.iter().enumerate() {
            let c = cell(p);
            grid.entry([c.x, c.y, c.z]).or_default().push(i);
        }
        let mut pairs = Vec::new();
        for (i, p) in x.iter().enumerate() {
            let c = cell(p);
            for d in 0..27i64 {
                let key = [c.x + d % 3 - 1, c.y + (d / 3) % 3 - 1, c.z + d / 9 - 1];
                for &j in grid.get(&key).into_iter().flatten() {
                    if j > i && panel[i] != panel[j] && joined[i] != joined[j] && (x[j] - p).norm() < TOUCH {
                        pairs.push([i, j]);
                    }
                }
            }
        }
        let mut found: Vec<Touching> = Vec::new();
        for &[i, j] in &pairs {
            let names = [panel[i], panel[j]].map(|p| self.panel_names[p].clone());
            match found.iter_mut().find(|t| t.panels == names) {
                Some(t) => t.points += 1,
                None => found.push(Touching {
                    panels: names,
                    points: 1,
                }),
            }
        }
        self.touching = pairs;
        found
    }
}
