//! Bending rigidity and the hinge law it is applied through.

use serde::{Deserialize, Serialize};

/// The energy of one hinge as a function of its bend angle `psi` (0 when flat).
/// Both laws are scaled so that for small angles `E = k psi^2 / 2`, with `k` from the
/// continuum rigidity (see [`crate::energy::bending`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BendingLaw {
    /// The source's `B = mu_b cos^2(theta/2)`, theta the angle between the two halves
    /// (pi when flat): with `mu_b = 2k` it is `k (1 - cos psi)`.
    SourceCosine,
    /// `k psi^2 / 2`, as in Baraff & Witkin and Discrete Shells.
    #[default]
    Quadratic,
}

/// Continuum bending rigidity per unit width, N*m, by direction of the bent threads:
/// `warp` bends the warp threads (fold line along the weft), `weft` the weft threads.
/// `bias`, where measured, is the rigidity at 45 degrees; otherwise the rigidity is
/// interpolated as `warp cos^2 + weft sin^2`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BendingRigidity {
    pub warp: f64,
    pub weft: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bias: Option<f64>,
}

impl BendingRigidity {
    pub fn isotropic(b: f64) -> Self {
        Self {
            warp: b,
            weft: b,
            bias: None,
        }
    }

    /// Rigidity against a fold whose line runs along the material direction `(tu, tv)`
    /// (a unit vector in (u, v)).
    pub fn along_fold(&self, tu: f64, tv: f64) -> f64 {
        // The bent threads run across the fold: cos^2 of their angle to the warp is tv^2.
        let (c2, s2) = (tv * tv, tu * tu);
        let base = self.warp * c2 + self.weft * s2;
        match self.bias {
            Some(b45) => base + (b45 - 0.5 * (self.warp + self.weft)) * 4.0 * c2 * s2,
            None => base,
        }
    }
}
