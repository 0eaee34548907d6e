//! One preset as the TOML file writes it: a description, where its numbers come from,
//! and the fabric in exactly one of three forms.

use cloth_core::{Fabric, KesMeasurement, SourceCoefficients, TensileLaw};
use serde::Deserialize;

/// A preset table, before conversion.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct PresetRecord {
    pub description: String,
    pub origin: String,
    pub si: Option<Fabric>,
    pub kes: Option<KesMeasurement>,
    pub source: Option<SourceRecord>,
}

/// The source paper's form: its coefficients, with what the paper does not give.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SourceRecord {
    /// N*m per hinge.
    pub mu_b: f64,
    /// J/m^2 per square degree of shear.
    pub mu_s: f64,
    /// kg/m^2.
    pub area_density: f64,
    pub tensile: TensileLaw,
}

impl SourceRecord {
    pub fn to_fabric(&self) -> Fabric {
        let coefficients = SourceCoefficients {
            mu_b: self.mu_b,
            mu_s: self.mu_s,
        };
        Fabric::from_source(coefficients, self.area_density, self.tensile.clone())
    }
}
