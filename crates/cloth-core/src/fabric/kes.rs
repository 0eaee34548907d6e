//! Kawabata (KES-F) measurements and their conversion to an SI [`Fabric`].
//!
//! KES-F reports each property in its own units (see `fabrics.md`); the conversions are
//! exact from the unit definitions. The tensile curve of each direction is fitted
//! through the end point of the KES test, (EMT, 500 gf/cm), with the measured energy
//! WT: the power law `T = Fm (e/EMT)^p` has linearity `LT = 2/(p+1)`, so
//! `p = 2/LT - 1` with `LT = WT / (Fm EMT / 2)`. A curve with LT above 1 (stiffer at the
//! start than at the end) is fitted by two straight segments instead.

use super::{BendingLaw, BendingRigidity, Fabric, TensileLaw};
use crate::error::ParamError;
use serde::{Deserialize, Serialize};

/// 1 gf = this many newtons.
const GRAM_FORCE: f64 = 9.80665e-3;
/// KES tensile test end point, gf/cm.
pub const KES_MAX_TENSION_GF_CM: f64 = 500.0;
/// gf/cm to N/m.
pub const GF_PER_CM: f64 = GRAM_FORCE / 1e-2;
/// gf*cm/cm^2 to J/m^2 (tensile energy).
pub const GF_CM_PER_CM2: f64 = GRAM_FORCE * 1e-2 / 1e-4;
/// gf*cm^2/cm to N*m (bending rigidity per unit width).
pub const GF_CM2_PER_CM: f64 = GRAM_FORCE * 1e-4 / 1e-2;
/// gf/(cm*degree) to N/m per radian (shear rigidity).
pub const GF_PER_CM_DEGREE: f64 = GF_PER_CM * 180.0 / std::f64::consts::PI;
/// mg/cm^2 to kg/m^2.
pub const MG_PER_CM2: f64 = 1e-6 / 1e-4;
/// How far the stated LT may be from the one WT and EMT imply (rounding of published
/// tables) before the record is refused as inconsistent.
pub const LT_TOLERANCE: f64 = 0.05;

/// One direction of a KES-F record, in KES units.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KesDirection {
    /// Strain at 500 gf/cm, %.
    #[serde(rename = "EMT")]
    pub emt: f64,
    /// Tensile linearity, -.
    #[serde(rename = "LT")]
    pub lt: f64,
    /// Tensile energy to 500 gf/cm, gf*cm/cm^2.
    #[serde(rename = "WT")]
    pub wt: f64,
    /// Tensile resilience, %.
    #[serde(rename = "RT", default, skip_serializing_if = "Option::is_none")]
    pub rt: Option<f64>,
    /// Shear rigidity, gf/(cm*degree).
    #[serde(rename = "G")]
    pub g: f64,
    /// Shear hysteresis at 0.5 degrees, gf/cm.
    #[serde(rename = "2HG", default, skip_serializing_if = "Option::is_none")]
    pub two_hg: Option<f64>,
    /// Shear hysteresis at 5 degrees, gf/cm.
    #[serde(rename = "2HG5", default, skip_serializing_if = "Option::is_none")]
    pub two_hg5: Option<f64>,
    /// Bending rigidity, gf*cm^2/cm.
    #[serde(rename = "B")]
    pub b: f64,
    /// Bending hysteresis, gf*cm/cm.
    #[serde(rename = "2HB", default, skip_serializing_if = "Option::is_none")]
    pub two_hb: Option<f64>,
}

/// A KES-F record: per direction (warp = 1, weft = 2) and for the whole fabric.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KesMeasurement {
    /// Weight, mg/cm^2.
    #[serde(rename = "W")]
    pub w: f64,
    /// Thickness, mm.
    #[serde(rename = "T")]
    pub t: f64,
    /// Surface friction coefficient (KES-FB4), where measured.
    #[serde(rename = "MIU", default, skip_serializing_if = "Option::is_none")]
    pub miu: Option<f64>,
    pub warp: KesDirection,
    pub weft: KesDirection,
}

/// A KES value the SI fabric does not use, and why.
#[derive(Debug, Clone, PartialEq)]
pub struct UnusedKes {
    /// The field, as `warp.2HB`.
    pub field: &'static str,
    pub value: f64,
    pub reason: &'static str,
}

/// The SI fabric from a KES record, with what of the record it leaves unused.
#[derive(Debug, Clone, PartialEq)]
pub struct KesConversion {
    pub fabric: Fabric,
    pub unused: Vec<UnusedKes>,
}

/// Field names of the two directions, for errors and reports.
struct Names {
    emt: &'static str,
    lt: &'static str,
    wt: &'static str,
    g: &'static str,
    b: &'static str,
    rt: &'static str,
    two_hg: &'static str,
    two_hg5: &'static str,
    two_hb: &'static str,
}

const WARP: Names = Names {
    emt: "warp.EMT",
    lt: "warp.LT",
    wt: "warp.WT",
    g: "warp.G",
    b: "warp.B",
    rt: "warp.RT",
    two_hg: "warp.2HG",
    two_hg5: "warp.2HG5",
    two_hb: "warp.2HB",
};
const WEFT: Names = Names {
    emt: "weft.EMT",
    lt: "weft.LT",
    wt: "weft.WT",
    g: "weft.G",
    b: "weft.B",
    rt: "weft.RT",
    two_hg: "weft.2HG",
    two_hg5: "weft.2HG5",
    two_hb: "weft.2HB",
};

const HYSTERESIS: &str = "hysteresis is a rate-independent (frictional) loss; the model's \
                          damping is viscous and is not derived from it";

fn positive(name: &'static str, value: f64, unit: &'static str) -> Result<(), ParamError> {
    ParamError::check(value > 0.0 && value.is_finite(), name, value, unit)
}

impl KesDirection {
    /// The tensile law through (EMT, 500 gf/cm) with energy WT, in SI.
    fn tensile_law(&self, n: &Names) -> Result<TensileLaw, ParamError> {
        self.check(n)?;
        let strain = self.emt / 100.0;
        let tension = KES_MAX_TENSION_GF_CM * GF_PER_CM;
        let linearity = self.wt * GF_CM_PER_CM2 / (0.5 * tension * strain);
        if (linearity - self.lt).abs() > LT_TOLERANCE * self.lt {
            return Err(ParamError::Inconsistent {
                name: n.lt,
                value: self.lt,
                reason: format!(
                    "WT / (Fm EMT / 2) = {linearity:.3} from {} and {}; they must agree within {:.0}%",
                    n.wt,
                    n.emt,
                    100.0 * LT_TOLERANCE
                ),
            });
        }
        if linearity <= 1.0 {
            return Ok(TensileLaw::PowerLaw {
                strain_ref: strain,
                tension_ref: tension,
                exponent: 2.0 / linearity - 1.0,
            });
        }
        // Two segments meeting at half EMT: the area under them is WT when the knee is at
        // Fm (LT - 1/2), which stays below Fm (a rising curve) for LT < 3/2.
        if linearity >= 1.5 {
            return Err(ParamError::Inconsistent {
                name: n.lt,
                value: self.lt,
                reason: format!(
                    "a linearity of {linearity:.3} (from WT and EMT) is above 1.5: no rising \
                     tensile curve through (EMT, 500 gf/cm) has that much energy"
                ),
            });
        }
        Ok(TensileLaw::PiecewiseLinear {
            points: vec![[0.5 * strain, tension * (linearity - 0.5)], [strain, tension]],
        })
    }

    fn check(&self, n: &Names) -> Result<(), ParamError> {
        positive(n.emt, self.emt, "a positive strain at 500 gf/cm, %")?;
        positive(n.lt, self.lt, "a positive tensile linearity")?;
        positive(n.wt, self.wt, "a positive tensile energy, gf*cm/cm^2")?;
        positive(n.g, self.g, "a positive shear rigidity, gf/(cm*degree)")?;
        positive(n.b, self.b, "a positive bending rigidity, gf*cm^2/cm")
    }

    fn unused(&self, n: &Names, out: &mut Vec<UnusedKes>) {
        let mut push = |field, value: Option<f64>, reason| {
            if let Some(value) = value {
                out.push(UnusedKes { field, value, reason });
            }
        };
        push(n.rt, self.rt, "tensile recovery is a hysteresis (see 2HB, 2HG)");
        push(n.two_hg, self.two_hg, HYSTERESIS);
        push(n.two_hg5, self.two_hg5, HYSTERESIS);
        push(n.two_hb, self.two_hb, HYSTERESIS);
    }
}

impl KesMeasurement {
    /// The SI fabric. Compression is a tenth of each direction's secant stiffness at EMT
    /// (KES has no in-plane compression test); shear rigidity is the mean of the two
    /// directions' G (the model has one); friction is MIU where given, else
    /// [`super::parameters::DEFAULT_FRICTION`]; damping is left at zero (see
    /// [`KesConversion::unused`]).
    pub fn to_fabric(&self) -> Result<KesConversion, ParamError> {
        positive("W", self.w, "a positive weight, mg/cm^2")?;
        positive("T", self.t, "a positive thickness, mm")?;
        if let Some(miu) = self.miu {
            ParamError::check(
                miu >= 0.0 && miu.is_finite(),
                "MIU",
                miu,
                "a friction coefficient >= 0",
            )?;
        }
        let warp = self.warp.tensile_law(&WARP)?;
        let weft = self.weft.tensile_law(&WEFT)?;
        let secant = |d: &KesDirection| KES_MAX_TENSION_GF_CM * GF_PER_CM / (d.emt / 100.0);
        let mut fabric = Fabric {
            area_density: self.w * MG_PER_CM2,
            thickness: self.t * 1e-3,
            warp,
            weft,
            compression_warp: 0.1 * secant(&self.warp),
            compression_weft: 0.1 * secant(&self.weft),
            shear_modulus: 0.5 * (self.warp.g + self.weft.g) * GF_PER_CM_DEGREE,
            bending: BendingRigidity {
                warp: self.warp.b * GF_CM2_PER_CM,
                weft: self.weft.b * GF_CM2_PER_CM,
                bias: None,
            },
            bending_law: BendingLaw::Quadratic,
            damping: 0.0,
            drag: 0.0,
            friction: super::parameters::DEFAULT_FRICTION,
        };
        if let Some(miu) = self.miu {
            fabric.friction = miu;
        }
        fabric.validate()?;
        let mut unused = Vec::new();
        self.warp.unused(&WARP, &mut unused);
        self.weft.unused(&WEFT, &mut unused);
        Ok(KesConversion { fabric, unused })
    }

    /// The KES-F values of an SI fabric, as the instruments would read them off the model:
    /// EMT where the tensile curve reaches 500 gf/cm, WT the energy under it to there, LT
    /// their ratio to the linear curve's, G from the one shear modulus in both directions,
    /// B, W, T and MIU converted. The inverse of [`to_fabric`](Self::to_fabric) on the
    /// values it uses (G comes back as the mean of the two directions').
    pub fn from_fabric(fabric: &Fabric) -> KesMeasurement {
        let tension = KES_MAX_TENSION_GF_CM * GF_PER_CM;
        let direction = |law: &TensileLaw, b: f64| {
            let strain = law.strain_at(tension);
            let wt = law.extension(strain).energy;
            KesDirection {
                emt: 100.0 * strain,
                lt: wt / (0.5 * tension * strain),
                wt: wt / GF_CM_PER_CM2,
                rt: None,
                g: fabric.shear_modulus / GF_PER_CM_DEGREE,
                two_hg: None,
                two_hg5: None,
                b: b / GF_CM2_PER_CM,
                two_hb: None,
            }
        };
        KesMeasurement {
            w: fabric.area_density / MG_PER_CM2,
            t: fabric.thickness * 1e3,
            miu: Some(fabric.friction),
            warp: direction(&fabric.warp, fabric.bending.warp),
            weft: direction(&fabric.weft, fabric.bending.weft),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn direction(emt: f64, lt: f64, g: f64, b: f64) -> KesDirection {
        KesDirection {
            emt,
            lt,
            // WT consistent with LT: LT * Fm * EMT / 2.
            wt: lt * KES_MAX_TENSION_GF_CM * emt / 100.0 / 2.0,
            rt: None,
            g,
            two_hg: None,
            two_hg5: None,
            b,
            two_hb: None,
        }
    }

    #[test]
    fn from_fabric_reads_back_the_record_it_was_made_from() {
        // A power-law warp (LT < 1) and a two-segment weft (LT > 1).
        let kes = KesMeasurement {
            w: 13.2,
            t: 0.31,
            miu: Some(0.21),
            warp: direction(4.1, 0.72, 0.9, 0.084),
            weft: direction(7.9, 1.12, 0.7, 0.052),
        };
        let back = KesMeasurement::from_fabric(&kes.to_fabric().unwrap().fabric);
        let close =
            |a: f64, b: f64, what: &str| assert!((a - b).abs() <= 1e-9 * b.abs(), "{what}: {a} vs {b}");
        close(back.w, kes.w, "W");
        close(back.t, kes.t, "T");
        close(back.miu.unwrap(), 0.21, "MIU");
        for (b, k, name) in [(&back.warp, &kes.warp, "warp"), (&back.weft, &kes.weft, "weft")] {
            close(b.emt, k.emt, &format!("{name} EMT"));
            close(b.lt, k.lt, &format!("{name} LT"));
            close(b.wt, k.wt, &format!("{name} WT"));
            close(b.b, k.b, &format!("{name} B"));
            close(b.g, 0.8, &format!("{name} G (the mean)"));
        }
    }
}
