//! The strain of a cloth state in a report: its maxima and 99th percentiles, %.

use cloth_core::{math::Vec3, ClothMesh, StrainReport};
use serde::Serialize;

/// The strain of a cloth state, %.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StrainSummary {
    pub max_warp: f64,
    pub max_weft: f64,
    pub p99_warp: f64,
    pub p99_weft: f64,
}

impl StrainSummary {
    pub fn of(mesh: &ClothMesh, positions: &[Vec3]) -> Self {
        Self::from_report(&StrainReport::new(mesh, positions))
    }

    /// The larger of the p99 warp and weft strain, and which thread it is.
    pub fn p99(&self) -> (f64, &'static str) {
        if self.p99_weft >= self.p99_warp {
            (self.p99_weft, "weft")
        } else {
            (self.p99_warp, "warp")
        }
    }

    pub fn from_report(s: &StrainReport) -> Self {
        Self {
            max_warp: s.max_warp,
            max_weft: s.max_weft,
            p99_warp: s.p99_warp,
            p99_weft: s.p99_weft,
        }
    }
}
