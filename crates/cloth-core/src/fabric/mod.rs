//! Fabric parameters in SI units, as the energies consume them.

mod bending_params;
mod fabric;
mod tensile_law;

pub use bending_params::{BendingLaw, BendingRigidity};
pub use fabric::Fabric;
pub use tensile_law::{TensileLaw, TensileResponse};
