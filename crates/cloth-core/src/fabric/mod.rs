//! Fabric parameters in SI units, as the energies consume them, and the conversions from
//! Kawabata (KES-F) records and the source paper's coefficients.

mod bending_params;
mod source_coefficients;
mod tensile_law;
mod parameters;
pub mod kes;

pub use bending_params::{BendingLaw, BendingRigidity};
pub use kes::{KesConversion, KesDirection, KesMeasurement, UnusedKes};
pub use parameters::{Fabric, DEFAULT_FRICTION, DEFAULT_THICKNESS};
pub use source_coefficients::SourceCoefficients;
pub use tensile_law::{TensileLaw, TensileResponse};
