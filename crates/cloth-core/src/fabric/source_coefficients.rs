//! The source paper's fabric coefficients: `mu_b` for bending and `mu_s` for shear.
//!
//! The source writes the energy of a hinge as `mu_b cos^2(theta/2)` (N*m, theta the
//! angle between the two halves, pi when flat) and that of a cell's triangle as
//! `mu_s (l1 l2 / 2) phi^2` (N*m, phi the shear angle in degrees). Read in SI:
//! - bending: `mu_b cos^2(theta/2) = k (1 - cos psi)` with `k = mu_b / 2` per hinge. On the
//!   source's square thread grid a hinge's `|e|^2 / (A1 + A2)` is 1, so the continuum
//!   rigidity is `B = mu_b / 2` (N*m), whatever the spacing;
//! - shear: the energy per rest area is `mu_s phi_deg^2 = (G/2) phi_rad^2`, so
//!   `G = 2 mu_s (180/pi)^2` (N/m per radian).

use serde::{Deserialize, Serialize};

/// The source's `mu_b` (N*m per hinge) and `mu_s` (J/m^2 per square degree).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SourceCoefficients {
    pub mu_b: f64,
    pub mu_s: f64,
}

impl SourceCoefficients {
    /// The source's 100% cotton: `mu_b = 0.214e-4`, `mu_s = 1.9576`.
    pub const COTTON: Self = Self {
        mu_b: 0.214e-4,
        mu_s: 1.9576,
    };

    /// Continuum bending rigidity, N*m.
    pub fn bending_rigidity(&self) -> f64 {
        0.5 * self.mu_b
    }

    /// Shear rigidity, N/m per radian.
    pub fn shear_modulus(&self) -> f64 {
        let per_degree = 180.0 / std::f64::consts::PI;
        2.0 * self.mu_s * per_degree * per_degree
    }
}
