//! The fabric: everything the energies need, in SI.

use super::{BendingLaw, BendingRigidity, SourceCoefficients, TensileLaw};
use crate::error::ParamError;
use serde::{Deserialize, Serialize};

/// A fabric's mechanical parameters in SI units.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Fabric {
    /// Mass per unit area, kg/m^2.
    pub area_density: f64,
    /// Thickness, m (KES-F T). The mid-surface is the simulated one; the thickness is the
    /// fabric's own half-gap to other layers of cloth.
    #[serde(default = "default_thickness")]
    pub thickness: f64,
    /// Tension against strain along the warp (u).
    pub warp: TensileLaw,
    /// Tension against strain along the weft (v).
    pub weft: TensileLaw,
    /// Stiffness in compression along the warp, N/m (small: cloth buckles).
    pub compression_warp: f64,
    /// Stiffness in compression along the weft, N/m.
    pub compression_weft: f64,
    /// Shear rigidity G, N/m per radian: energy density `G/2 phi^2`, i.e. the source's
    /// `T = mu_s (l1 l2 / 2) phi^2` with `mu_s = G/2` and phi in radians (the source's
    /// own phi is in degrees: see [`SourceCoefficients`]).
    pub shear_modulus: f64,
    pub bending: BendingRigidity,
    #[serde(default)]
    pub bending_law: BendingLaw,
    /// Stiffness-proportional (Rayleigh) damping coefficient beta, s: `F = -beta K v`.
    #[serde(default)]
    pub damping: f64,
    /// Viscous air drag per unit area, kg/(m^2 s): `F = -drag * area * (v - wind)`.
    #[serde(default)]
    pub drag: f64,
    /// Coulomb coefficient of the fabric on a body (KES-F MIU where measured); a body
    /// that sets its own coefficient overrides it. Infinite: no slip.
    #[serde(default = "default_friction")]
    pub friction: f64,
}

/// Thickness of a fabric that does not state one, m: a light woven's.
pub const DEFAULT_THICKNESS: f64 = 5e-4;
/// Coulomb coefficient of a fabric that does not state one: cloth on skin or a dress
/// form is about 0.3 to 0.6.
pub const DEFAULT_FRICTION: f64 = 0.5;

fn default_thickness() -> f64 {
    DEFAULT_THICKNESS
}
fn default_friction() -> f64 {
    DEFAULT_FRICTION
}

/// Strain at which [`Fabric::membrane_stiffness`] reads the tensile laws' secants: on a
/// J-shaped curve the slope at rest is zero, and a percent is where draped cloth sits.
const MEMBRANE_STRAIN: f64 = 0.01;

fn membrane_secant(law: &TensileLaw) -> f64 {
    law.extension(MEMBRANE_STRAIN).tension / MEMBRANE_STRAIN
}

impl Fabric {
    /// A fabric with the same linear law along warp and weft, compression at a tenth of the
    /// tensile stiffness, and isotropic bending: the simplest fully specified fabric.
    pub fn isotropic_linear(
        area_density: f64,
        tensile_stiffness: f64,
        shear_modulus: f64,
        bending_rigidity: f64,
    ) -> Self {
        let law = TensileLaw::Linear {
            stiffness: tensile_stiffness,
        };
        Self {
            area_density,
            thickness: DEFAULT_THICKNESS,
            warp: law.clone(),
            weft: law,
            compression_warp: 0.1 * tensile_stiffness,
            compression_weft: 0.1 * tensile_stiffness,
            shear_modulus,
            bending: BendingRigidity::isotropic(bending_rigidity),
            bending_law: BendingLaw::Quadratic,
            damping: 0.0,
            drag: 0.0,
            friction: DEFAULT_FRICTION,
        }
    }

    /// Cotton-like values used by the benchmarks: 0.15 kg/m^2, 1000 N/m, 20 N/m shear,
    /// 1e-5 N*m bending.
    pub fn cotton_like() -> Self {
        Self::isotropic_linear(0.15, 1000.0, 20.0, 1e-5)
    }

    /// The source's fabric: its bending (with its cosine hinge law) and shear from
    /// `mu_b` and `mu_s`, isotropic, with the area density and tensile law the source does
    /// not give; compression is a tenth of the tensile secant stiffness at 1%.
    pub fn from_source(coefficients: SourceCoefficients, area_density: f64, tensile: TensileLaw) -> Self {
        let compression = 0.1 * membrane_secant(&tensile);
        Self {
            area_density,
            thickness: DEFAULT_THICKNESS,
            warp: tensile.clone(),
            weft: tensile,
            compression_warp: compression,
            compression_weft: compression,
            shear_modulus: coefficients.shear_modulus(),
            bending: BendingRigidity::isotropic(coefficients.bending_rigidity()),
            bending_law: BendingLaw::SourceCosine,
            damping: 0.0,
            drag: 0.0,
            friction: DEFAULT_FRICTION,
        }
    }

    pub fn with_damping(mut self, beta: f64) -> Self {
        self.damping = beta;
        self
    }
    pub fn with_drag(mut self, drag: f64) -> Self {
        self.drag = drag;
        self
    }
    pub fn with_bending_law(mut self, law: BendingLaw) -> Self {
        self.bending_law = law;
        self
    }
    pub fn with_friction(mut self, friction: f64) -> Self {
        self.friction = friction;
        self
    }

    /// A representative in-plane stiffness, N/m: the larger of the warp and weft secant
    /// stiffnesses at 1% strain (the stiffness itself for linear laws).
    pub fn membrane_stiffness(&self) -> f64 {
        membrane_secant(&self.warp).max(membrane_secant(&self.weft))
    }

    /// Checks every field; the error names the field.
    pub fn validate(&self) -> Result<(), ParamError> {
        let check = |name: &'static str, value: f64, positive: bool| {
            let ok = value.is_finite() && if positive { value > 0.0 } else { value >= 0.0 };
            let expected = if positive {
                "a positive finite number"
            } else {
                "a finite number >= 0"
            };
            ParamError::check(ok, name, value, expected)
        };
        check("area_density", self.area_density, true)?;
        check("thickness", self.thickness, true)?;
        self.warp.validate("warp")?;
        self.weft.validate("weft")?;
        check("compression_warp", self.compression_warp, true)?;
        check("compression_weft", self.compression_weft, true)?;
        check("shear_modulus", self.shear_modulus, false)?;
        check("bending.warp", self.bending.warp, false)?;
        check("bending.weft", self.bending.weft, false)?;
        if let Some(b) = self.bending.bias {
            check("bending.bias", b, false)?;
        }
        check("damping", self.damping, false)?;
        check("drag", self.drag, false)?;
        ParamError::check(
            self.friction >= 0.0,
            "friction",
            self.friction,
            "a coefficient >= 0 (infinity for no slip)",
        )
    }
}
