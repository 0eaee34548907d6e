//! The Cusick drape test (BS 5058, ISO 9073-9): a 30 cm disk of fabric held between two
//! 18 cm support disks drapes under its own weight.
//!
//! The specimen's central 18 cm is clamped, as between the standard's two support disks
//! (its particles are pinned, with a ring of vertices on the disks' edge); the rest falls
//! from flat and comes to rest. The drape coefficient is read from the area of the
//! vertical projection, and the folds (nodes) from the outline of that projection.

use super::{settle, ValidationError};
use cloth_core::{math::Vec3, Fabric, Pin, RestCriteria, SimulationBuilder, SolverSettings};
use cloth_garment::meshing::{circle, triangulate_polygon};
use nalgebra::Vector2;
use std::f64::consts::PI;

/// The standard's usual specimen and support radii, m.
pub const SPECIMEN_RADIUS: f64 = 0.15;
pub const SUPPORT_RADIUS: f64 = 0.09;

/// A Cusick drape test of one fabric.
#[derive(Debug, Clone)]
pub struct CusickTest {
    pub fabric: Fabric,
    /// Target edge length of the specimen's mesh, m.
    pub edge_length: f64,
    /// Rayleigh damping added to the fabric's own while it settles, s.
    pub damping: f64,
    pub time_step: f64,
    /// When the specimen counts as at rest.
    pub rest: RestCriteria,
}

/// The draped specimen.
#[derive(Debug, Clone)]
pub struct CusickResult {
    /// Drape coefficient, %.
    pub drape_coefficient: f64,
    /// Number of folds (nodes) around the outline.
    pub folds: usize,
    /// Radius of the projected outline by angle (one per degree), m.
    pub outline: Vec<f64>,
    pub steps: u64,
    /// Positions at rest and the mesh's triangles, for pictures.
    pub positions: Vec<Vec3>,
    pub triangles: Vec<[usize; 3]>,
}

impl CusickTest {
    pub fn new(fabric: Fabric) -> Self {
        Self {
            fabric,
            edge_length: 0.0075,
            damping: 0.01,
            time_step: 1.0 / 60.0,
            rest: RestCriteria {
                max_time_step: None,
                tolerance: 1e-6,
                consecutive_steps: 20,
                max_steps: 4000,
                moving_fraction: 0.0,
            },
        }
    }

    pub fn run(&self) -> Result<CusickResult, ValidationError> {
        let mut sim = self.simulation_builder()?.build()?;
        let steps = settle(&mut sim, &self.rest, "Cusick drape")?;
        let positions = sim.positions().to_vec();
        let measure = measure(&positions, sim.mesh().triangles());
        Ok(CusickResult {
            drape_coefficient: measure.drape_coefficient,
            folds: measure.folds,
            outline: measure.outline,
            steps,
            positions,
            triangles: sim.mesh().triangles().to_vec(),
        })
    }

    /// The specimen, flat, its centre clamped, ready to drape (with the settling damping
    /// and time step; the rest criteria are the caller's).
    pub fn simulation_builder(&self) -> Result<SimulationBuilder, ValidationError> {
        let h = self.edge_length;
        let segments = |r: f64| ((2.0 * PI * r / h).ceil() as usize).max(12);
        let centre = Vector2::zeros();
        let outline = circle(centre, SPECIMEN_RADIUS, segments(SPECIMEN_RADIUS));
        let support = circle(centre, SUPPORT_RADIUS, segments(SUPPORT_RADIUS));
        let mesh = triangulate_polygon(&outline, &support, h)?;
        let clamp = SUPPORT_RADIUS * (1.0 + 1e-9);
        let pins: Vec<Pin> = (0..mesh.vertex_count())
            .filter(|&i| mesh.uv()[i].norm() <= clamp)
            .map(Pin::fixed)
            .collect();
        let fabric = self
            .fabric
            .clone()
            .with_damping(self.fabric.damping + self.damping);
        Ok(SimulationBuilder::new(mesh, fabric)
            .settings(SolverSettings {
                time_step: self.time_step,
                ..SolverSettings::default()
            })
            .pins(pins))
    }
}

/// What the test reads from a draped specimen.
#[derive(Debug, Clone)]
pub struct CusickMeasure {
    /// Drape coefficient, %.
    pub drape_coefficient: f64,
    /// Number of folds (nodes) around the outline.
    pub folds: usize,
    /// Radius of the projected outline by angle (one per degree), m.
    pub outline: Vec<f64>,
}

/// Reads the drape coefficient and the folds from the specimen's shadow.
pub fn measure(positions: &[Vec3], triangles: &[[usize; 3]]) -> CusickMeasure {
    let shadow = Shadow::new(positions, triangles);
    let a_disk = PI * SUPPORT_RADIUS * SUPPORT_RADIUS;
    let a_specimen = PI * SPECIMEN_RADIUS * SPECIMEN_RADIUS;
    let outline = shadow.outline(360);
    CusickMeasure {
        drape_coefficient: 100.0 * (shadow.area() - a_disk) / (a_specimen - a_disk),
        folds: count_folds(&outline, FOLD_DEPTH),
        outline,
    }
}

/// Least depth of the outline between two folds for them to count apart, m.
pub const FOLD_DEPTH: f64 = 0.003;
/// Pixel of the projected shadow, m.
const PIXEL: f64 = 5e-4;

/// The vertical projection of the draped specimen, rasterised.
struct Shadow {
    /// Covered pixels, row-major, `size` x `size`, centred on the axis.
    covered: Vec<bool>,
    size: usize,
}

impl Shadow {
    fn new(x: &[Vec3], triangles: &[[usize; 3]]) -> Self {
        let size = (2.0 * SPECIMEN_RADIUS / PIXEL).ceil() as usize + 2;
        let half = size as f64 * PIXEL / 2.0;
        let mut covered = vec![false; size * size];
        let to_pixel = |c: f64| (c + half) / PIXEL - 0.5;
        for t in triangles {
            let p = t.map(|i| Vector2::new(to_pixel(x[i].x), to_pixel(x[i].y)));
            let lo = |k: usize| {
                p.iter()
                    .map(|q| q[k])
                    .fold(f64::INFINITY, f64::min)
                    .floor()
                    .max(0.0) as usize
            };
            let hi = |k: usize| {
                (p.iter().map(|q| q[k]).fold(f64::NEG_INFINITY, f64::max).ceil() as usize).min(size - 1)
            };
            let det = (p[1] - p[0]).perp(&(p[2] - p[0]));
            if det.abs() < 1e-12 {
                continue; // seen edge-on: it covers no area
            }
            for j in lo(1)..=hi(1) {
                for i in lo(0)..=hi(0) {
                    let q = Vector2::new(i as f64, j as f64);
                    let a = (p[1] - q).perp(&(p[2] - q)) / det;
                    let b = (p[2] - q).perp(&(p[0] - q)) / det;
                    if a >= 0.0 && b >= 0.0 && a + b <= 1.0 {
                        covered[j * size + i] = true;
                    }
                }
            }
        }
        Self { covered, size }
    }

    fn area(&self) -> f64 {
        self.covered.iter().filter(|&&c| c).count() as f64 * PIXEL * PIXEL
    }

    /// The farthest covered radius along each of `n` directions, m.
    fn outline(&self, n: usize) -> Vec<f64> {
        let half = self.size as f64 / 2.0;
        (0..n)
            .map(|k| {
                let a = 2.0 * PI * k as f64 / n as f64;
                let (c, s) = (a.cos(), a.sin());
                let steps = (SPECIMEN_RADIUS / PIXEL * 1.1) as usize;
                (0..steps)
                    .rev()
                    .find(|&r| {
                        let (i, j) = (half + r as f64 * c, half + r as f64 * s);
                        let (i, j) = (i as usize, j as usize);
                        i < self.size && j < self.size && self.covered[j * self.size + i]
                    })
                    .map_or(0.0, |r| r as f64 * PIXEL)
            })
            .collect()
    }
}

/// Folds of a closed outline `r(angle)`: its local maxima, after merging any two whose
/// lowest point between them is less than `depth` below the lower of the two.
pub fn count_folds(r: &[f64], depth: f64) -> usize {
    let n = r.len();
    // A little smoothing (5 degrees) so pixel steps make no maxima.
    let smooth: Vec<f64> = (0..n)
        .map(|k| (0..5).map(|j| r[(k + n + j - 2) % n]).sum::<f64>() / 5.0)
        .collect();
    let mut peaks: Vec<usize> = (0..n)
        .filter(|&k| smooth[k] > smooth[(k + n - 1) % n] && smooth[k] >= smooth[(k + 1) % n])
        .collect();
    loop {
        if peaks.len() < 2 {
            return peaks.len();
        }
        // The shallowest separation between neighbouring peaks, going round.
        let valley = |a: usize, b: usize| {
            let len = (b + n - a) % n;
            (0..=len)
                .map(|j| smooth[(a + j) % n])
                .fold(f64::INFINITY, f64::min)
        };
        let (mut worst, mut worst_depth) = (0, f64::INFINITY);
        for k in 0..peaks.len() {
            let (a, b) = (peaks[k], peaks[(k + 1) % peaks.len()]);
            let d = smooth[a].min(smooth[b]) - valley(a, b);
            if d < worst_depth {
                (worst, worst_depth) = (k, d);
            }
        }
        if worst_depth >= depth {
            return peaks.len();
        }
        // Merge: drop the lower of the two.
        let next = (worst + 1) % peaks.len();
        let drop = if smooth[peaks[worst]] < smooth[peaks[next]] {
            worst
        } else {
            next
        };
        peaks.remove(drop);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn folds_of_a_wavy_outline_are_its_waves() {
        for waves in [4usize, 6, 9] {
            let r: Vec<f64> = (0..360)
                .map(|k| 0.12 + 0.01 * (waves as f64 * (k as f64).to_radians()).cos())
                .collect();
            assert_eq!(count_folds(&r, FOLD_DEPTH), waves);
        }
        // Ripples shallower than the depth are not folds.
        let r: Vec<f64> = (0..360)
            .map(|k| {
                let a = (k as f64).to_radians();
                0.12 + 0.01 * (5.0 * a).cos() + 0.0005 * (40.0 * a).cos()
            })
            .collect();
        assert_eq!(count_folds(&r, FOLD_DEPTH), 5);
    }
}
