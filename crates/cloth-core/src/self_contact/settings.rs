//! How the cloth's contact with itself is set up.

use crate::error::ParamError;
use serde::{Deserialize, Serialize};

/// Self-collision: layers and folds of the cloth kept from passing through each other.
/// Values left `None` come from the fabrics.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SelfCollision {
    /// Whether the cloth collides with itself.
    pub enabled: bool,
    /// Distance kept between the mid-surfaces of two layers, m. By default half of each
    /// layer's fabric thickness: two layers lying on each other.
    pub thickness: Option<f64>,
    /// Coulomb coefficient between layers. By default the mean of the two fabrics'.
    pub friction: Option<f64>,
    /// Stiffness of the repulsion between layers closer than the thickness, N/m. By
    /// default a tenth of the stiffest fabric's membrane stiffness (see
    /// [`crate::Fabric::membrane_stiffness`]).
    pub stiffness: Option<f64>,
}

impl Default for SelfCollision {
    fn default() -> Self {
        Self {
            enabled: true,
            thickness: None,
            friction: None,
            stiffness: None,
        }
    }
}

impl SelfCollision {
    /// No self-collision.
    pub fn off() -> Self {
        Self {
            enabled: false,
            ..Self::default()
        }
    }

    pub fn validate(&self) -> Result<(), ParamError> {
        let positive = |value: Option<f64>, name: &'static str, expected: &'static str| match value {
            Some(v) => ParamError::check(v.is_finite() && v > 0.0, name, v, expected),
            None => Ok(()),
        };
        positive(
            self.thickness,
            "self_collision.thickness",
            "a positive distance in m",
        )?;
        positive(
            self.stiffness,
            "self_collision.stiffness",
            "a positive stiffness in N/m",
        )?;
        match self.friction {
            Some(mu) => ParamError::check(
                mu.is_finite() && mu >= 0.0,
                "self_collision.friction",
                mu,
                "a finite Coulomb coefficient >= 0",
            ),
            None => Ok(()),
        }
    }
}

/// What the fabric gives each particle's layer: its thickness (m) and friction
/// coefficient, particle by particle, and the stiffest membrane of the fabrics (N/m),
/// from which the contact springs' stiffness is set.
pub struct LayerFabric<T, F> {
    pub thickness: T,
    pub friction: F,
    pub membrane_stiffness: f64,
}
