//! Fabric parameters in SI units, as the energies consume them.

mod bending_params;
mod parameters;
mod tensile_law;

pub use bending_params::{BendingLaw, BendingRigidity};
pub use parameters::Fabric;
pub use tensile_law::{TensileLaw, TensileResponse};
