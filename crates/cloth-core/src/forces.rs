//! Where a force evaluation writes: the cloth's elements, the bodies' sharp features and
//! the cloth's contacts with itself alike add their forces, `K v`, and for an implicit
//! step their Jacobian terms.

use crate::linalg::BlockSparse;
use crate::math::Vec3;

/// The implicit step's matrix and its length `h`: each writer adds its own terms (the
/// elements `(h^2 + h beta) K` with their fabric's Rayleigh damping `beta`, a contact its
/// spring's `h^2 K` and its friction's `h` times the drag).
pub(crate) struct StiffnessTarget<'a> {
    pub matrix: &'a mut BlockSparse,
    pub h: f64,
}

/// The forces, `K v`, and for an implicit step the matrix.
pub(crate) struct ForceOutputs<'a, 'm> {
    pub force: &'a mut [Vec3],
    pub hv: &'a mut [Vec3],
    pub stiffness: Option<StiffnessTarget<'m>>,
}
