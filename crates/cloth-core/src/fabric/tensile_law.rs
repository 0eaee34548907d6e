//! Tension per unit width as a function of strain along one thread direction.

use crate::error::ParamError;
use serde::{Deserialize, Serialize};

/// Tension (N/m, force per unit width) against strain in extension. Compression is
/// separate (see [`Fabric`](super::Fabric)): cloth buckles rather than compresses.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "law", rename_all = "snake_case")]
pub enum TensileLaw {
    /// `T = stiffness * strain`.
    Linear { stiffness: f64 },
    /// Straight segments through `(0, 0)` and the given `(strain, tension)` points,
    /// extended past the last point with the last segment's slope.
    PiecewiseLinear { points: Vec<[f64; 2]> },
    /// `T = tension_ref * (strain / strain_ref)^exponent`, the J-shaped fabric curve
    /// (exponent >= 1). A KES curve through (EMT, Fm) with linearity LT has exponent 2/LT - 1.
    PowerLaw {
        strain_ref: f64,
        tension_ref: f64,
        exponent: f64,
    },
}

/// Energy density, tension and slope at one strain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TensileResponse {
    /// Energy per unit rest area, J/m^2.
    pub energy: f64,
    /// Tension, N/m.
    pub tension: f64,
    /// dT/dstrain, N/m.
    pub slope: f64,
}

impl TensileLaw {
    pub fn validate(&self, name: &'static str) -> Result<(), ParamError> {
        let positive = |field: &'static str, value: f64| {
            if value > 0.0 && value.is_finite() {
                Ok(())
            } else {
                Err(ParamError::OutOfRange {
                    name: field,
                    value,
                    expected: "a positive finite number",
                })
            }
        };
        match self {
            Self::Linear { stiffness } => positive(name, *stiffness),
            Self::PiecewiseLinear { points } => {
                if points.is_empty() {
                    return Err(ParamError::BadCurve {
                        name,
                        reason: "no points".into(),
                    });
                }
                let mut prev = [0.0, 0.0];
                for (k, p) in points.iter().enumerate() {
                    if !(p[0] > prev[0]) || !p[0].is_finite() {
                        return Err(ParamError::BadCurve {
                            name,
                            reason: format!(
                                "point {k}: strain {} must be finite and exceed {}",
                                p[0], prev[0]
                            ),
                        });
                    }
                    if !(p[1] >= prev[1]) || !p[1].is_finite() {
                        return Err(ParamError::BadCurve {
                            name,
                            reason: format!(
                                "point {k}: tension {} must be finite and not below {}",
                                p[1], prev[1]
                            ),
                        });
                    }
                    prev = *p;
                }
                if prev[1] <= 0.0 {
                    return Err(ParamError::BadCurve {
                        name,
                        reason: "tension never rises above zero".into(),
                    });
                }
                Ok(())
            }
            Self::PowerLaw {
                strain_ref,
                tension_ref,
                exponent,
            } => {
                positive(name, *strain_ref)?;
                positive(name, *tension_ref)?;
                if !(*exponent >= 1.0) || !exponent.is_finite() {
                    return Err(ParamError::OutOfRange {
                        name,
                        value: *exponent,
                        expected:
                            "a power-law exponent >= 1 (an exponent below 1 has infinite stiffness at rest)",
                    });
                }
                Ok(())
            }
        }
    }

    /// Response at `strain >= 0`.
    pub fn extension(&self, strain: f64) -> TensileResponse {
        debug_assert!(strain >= 0.0);
        match self {
            Self::Linear { stiffness } => TensileResponse {
                energy: 0.5 * stiffness * strain * strain,
                tension: stiffness * strain,
                slope: *stiffness,
            },
            Self::PiecewiseLinear { points } => {
                let (mut s0, mut t0, mut energy) = (0.0, 0.0, 0.0);
                let last = points.len() - 1;
                for (k, p) in points.iter().enumerate() {
                    let slope = (p[1] - t0) / (p[0] - s0);
                    if strain <= p[0] || k == last {
                        let ds = strain - s0;
                        return TensileResponse {
                            energy: energy + t0 * ds + 0.5 * slope * ds * ds,
                            tension: t0 + slope * ds,
                            slope,
                        };
                    }
                    energy += 0.5 * (t0 + p[1]) * (p[0] - s0);
                    (s0, t0) = (p[0], p[1]);
                }
                unreachable!("validated curves have at least one point")
            }
            Self::PowerLaw {
                strain_ref,
                tension_ref,
                exponent,
            } => {
                let r = strain / strain_ref;
                let rp = r.powf(*exponent);
                TensileResponse {
                    energy: tension_ref * strain_ref * rp * r / (exponent + 1.0),
                    tension: tension_ref * rp,
                    slope: if *exponent == 1.0 {
                        tension_ref / strain_ref
                    } else {
                        tension_ref * exponent * r.powf(exponent - 1.0) / strain_ref
                    },
                }
            }
        }
    }

    /// Strain at which the tension equals `tension` (>= 0): the inverse of the curve.
    pub fn strain_at(&self, tension: f64) -> f64 {
        match self {
            Self::Linear { stiffness } => tension / stiffness,
            Self::PowerLaw {
                strain_ref,
                tension_ref,
                exponent,
            } => strain_ref * (tension / tension_ref).powf(1.0 / exponent),
            Self::PiecewiseLinear { points } => {
                let (mut s0, mut t0) = (0.0, 0.0);
                for (k, p) in points.iter().enumerate() {
                    if tension <= p[1] || k == points.len() - 1 {
                        let slope = (p[1] - t0) / (p[0] - s0);
                        return if slope > 0.0 {
                            s0 + (tension - t0) / slope
                        } else {
                            s0
                        };
                    }
                    (s0, t0) = (p[0], p[1]);
                }
                unreachable!("validated curves have at least one point")
            }
        }
    }
}
