//! Deformation measures: warp and weft strain per triangle, and the source's
//! "maximum stretch between neighbouring points" on grids.

use crate::energy::TriangleRest;
use crate::math::Vec3;
use crate::mesh::ClothMesh;
use serde::Serialize;

/// Warp and weft strain of every triangle, in percent (positive = stretched).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StrainReport {
    pub warp: Vec<f64>,
    pub weft: Vec<f64>,
    pub max_warp: f64,
    pub max_weft: f64,
    pub p99_warp: f64,
    pub p99_weft: f64,
}

impl StrainReport {
    /// Strains of `mesh` at `positions`: `100 (|w_u| - 1)` and `100 (|w_v| - 1)`.
    pub fn new(mesh: &ClothMesh, positions: &[Vec3]) -> Self {
        let (mut warp, mut weft) = (Vec::new(), Vec::new());
        for (k, t) in mesh.triangles().iter().enumerate() {
            let rest =
                TriangleRest::new(mesh.corner_uv(k)).expect("validated mesh has no degenerate triangle");
            let (wu, wv) = rest.deformation(&t.map(|i| positions[i]));
            warp.push(100.0 * (wu.norm() - 1.0));
            weft.push(100.0 * (wv.norm() - 1.0));
        }
        Self::from_strains(warp, weft)
    }

    /// The report of some of the triangles (a garment's panel), by their indices here.
    pub fn of_triangles(&self, triangles: &[usize]) -> Self {
        let warp: Vec<f64> = triangles.iter().map(|&t| self.warp[t]).collect();
        let weft: Vec<f64> = triangles.iter().map(|&t| self.weft[t]).collect();
        Self::from_strains(warp, weft)
    }

    fn from_strains(warp: Vec<f64>, weft: Vec<f64>) -> Self {
        Self {
            max_warp: max(&warp),
            max_weft: max(&weft),
            p99_warp: percentile(&warp, 0.99),
            p99_weft: percentile(&weft, 0.99),
            warp,
            weft,
        }
    }
}

/// The source's table entry: the largest stretch between neighbouring grid points,
/// horizontally (along the warp) and vertically (along the weft), in percent.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GridStretch {
    pub horizontal: f64,
    pub vertical: f64,
}

impl GridStretch {
    /// `None` when the mesh is not a grid.
    pub fn new(mesh: &ClothMesh, positions: &[Vec3]) -> Option<Self> {
        let g = mesh.grid()?;
        let uv = mesh.uv();
        let stretch = |a: usize, b: usize| {
            100.0 * ((positions[a] - positions[b]).norm() / (uv[a] - uv[b]).norm() - 1.0)
        };
        let (mut horizontal, mut vertical) = (f64::NEG_INFINITY, f64::NEG_INFINITY);
        for j in 0..g.ny {
            for i in 0..g.nx {
                if i + 1 < g.nx {
                    horizontal = horizontal.max(stretch(g.index(i, j), g.index(i + 1, j)));
                }
                if j + 1 < g.ny {
                    vertical = vertical.max(stretch(g.index(i, j), g.index(i, j + 1)));
                }
            }
        }
        Some(Self { horizontal, vertical })
    }
}

fn max(values: &[f64]) -> f64 {
    values.iter().copied().fold(f64::NEG_INFINITY, f64::max)
}

/// Nearest-rank percentile (of none, as [`max`] of none).
fn percentile(values: &[f64], q: f64) -> f64 {
    if values.is_empty() {
        return f64::NEG_INFINITY;
    }
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let rank = ((q * v.len() as f64).ceil() as usize).clamp(1, v.len());
    v[rank - 1]
}
