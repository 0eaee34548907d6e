//! The report's plots: how the final strain is spread over the cloth (`strain.png`), and
//! how the solve converged and the cloth came to rest, step by step (`convergence.png`).

use crate::scene_file::HistoryRow;
use cloth_core::{math::Vec3, ClothMesh, StrainReport};
use cloth_render::{charts, Chart, Image, Series, Style};

const WARP: [u8; 3] = [44, 102, 190];
const WEFT: [u8; 3] = [230, 126, 34];

/// Bins of the strain histogram.
const BINS: usize = 30;

/// How the strain is spread: `BINS` bins of `width` % from `lo` %, and the share of the
/// cloth's rest area (%) whose warp, and whose weft, strain falls in each.
#[derive(Debug, Clone, PartialEq)]
struct StrainShares {
    lo: f64,
    width: f64,
    warp: Vec<f64>,
    weft: Vec<f64>,
}

impl StrainShares {
    /// `None` for a cloth with no area or no finite strain.
    fn of(mesh: &ClothMesh, positions: &[Vec3]) -> Option<Self> {
        let strain = StrainReport::new(mesh, positions);
        let areas: Vec<f64> = (0..mesh.triangles().len()).map(|t| mesh.rest_area(t)).collect();
        let total: f64 = areas.iter().sum();
        let all = strain
            .warp
            .iter()
            .chain(&strain.weft)
            .copied()
            .filter(|s| s.is_finite());
        let (lo, hi) = all.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), s| {
            (a.min(s), b.max(s))
        });
        if lo > hi || total <= 0.0 {
            return None;
        }
        let width = ((hi - lo) / BINS as f64).max(1e-6);
        let shares = |values: &[f64]| {
            let mut share = vec![0.0; BINS];
            for (s, a) in values.iter().zip(&areas).filter(|(s, _)| s.is_finite()) {
                share[(((s - lo) / width) as usize).min(BINS - 1)] += 100.0 * a / total;
            }
            share
        };
        Some(Self {
            lo,
            width,
            warp: shares(&strain.warp),
            weft: shares(&strain.weft),
        })
    }
}

/// The share of the cloth's area (%) at each warp and weft strain (%), side by side in
/// each bin; compression is negative strain.
pub fn strain_histogram(mesh: &ClothMesh, positions: &[Vec3], width: u32, height: u32) -> Image {
    let mut series = Vec::new();
    if let Some(h) = StrainShares::of(mesh, positions) {
        for (name, share, colour, side) in [("warp", &h.warp, WARP, -0.25), ("weft", &h.weft, WEFT, 0.25)] {
            series.push(Series {
                name: name.into(),
                points: (0..BINS)
                    .map(|k| (h.lo + (k as f64 + 0.5) * h.width, share[k]))
                    .collect(),
                colour,
                style: Style::Bars {
                    width: 0.45 * h.width,
                    offset: side * h.width,
                },
            });
        }
    }
    let chart = Chart {
        title: "final strain over the cloth".into(),
        x_label: "strain, % (compression below 0)".into(),
        y_label: "% of the cloth's area".into(),
        log_y: false,
        series,
        marks: Vec::new(),
    };
    charts(&[chart], width, height)
}

/// Over the run's steps (numbered through the stages, each stage's start marked): the
/// kinetic energy above, the linear solve's relative residual below.
pub fn convergence(history: &[HistoryRow], width: u32, height: u32) -> Image {
    let mut marks = Vec::new();
    let mut last_stage = "";
    for (k, row) in history.iter().enumerate() {
        if row.stage != last_stage {
            marks.push(((k + 1) as f64, row.stage.to_string()));
            last_stage = row.stage;
        }
    }
    let over_steps = |value: fn(&HistoryRow) -> f64| -> Vec<(f64, f64)> {
        history
            .iter()
            .enumerate()
            .map(|(k, row)| ((k + 1) as f64, value(row)))
            .collect()
    };
    let chart = |title: &str, y_label: &str, name: &str, colour, value: fn(&HistoryRow) -> f64| Chart {
        title: title.into(),
        x_label: "step".into(),
        y_label: y_label.into(),
        log_y: true,
        series: vec![Series {
            name: name.into(),
            points: over_steps(value),
            colour,
            style: Style::Line,
        }],
        marks: marks.clone(),
    };
    charts(
        &[
            chart("kinetic energy", "J", "", WARP, |r| r.kinetic_energy),
            chart("linear solve", "relative residual |r|/|b|", "", WEFT, |r| {
                r.cg_residual
            }),
        ],
        width,
        height,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use cloth_core::GridBuilder;

    #[test]
    fn a_sheet_stretched_two_percent_along_the_warp_over_three_fifths_shows_so() {
        let mesh = GridBuilder::new(6, 5).size(0.5, 0.4).build().unwrap();
        // Three of the five columns of cells (x to 0.3 m) stretched 2 % along the warp (x),
        // the other two not at all.
        let stretched: Vec<Vec3> = mesh
            .positions()
            .iter()
            .map(|p| Vec3::new(1.02 * p.x.min(0.3) + (p.x - 0.3).max(0.0), p.y, p.z))
            .collect();
        let h = StrainShares::of(&mesh, &stretched).unwrap();
        let bin_of = |s: f64| (((s - h.lo) / h.width) as usize).min(BINS - 1);
        let total: f64 = h.warp.iter().sum();
        assert!((total - 100.0).abs() < 1e-9 && (h.weft.iter().sum::<f64>() - 100.0).abs() < 1e-9);
        assert!((h.warp[bin_of(2.0)] - 60.0).abs() < 1e-6, "{:?}", h.warp);
        assert!((h.warp[bin_of(0.0)] - 40.0).abs() < 1e-6, "{:?}", h.warp);
        assert!((h.weft[bin_of(0.0)] - 100.0).abs() < 1e-6, "{:?}", h.weft);
    }
}
