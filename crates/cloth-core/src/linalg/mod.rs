//! Block-sparse linear algebra for the implicit step: the 3x3-block matrix, the
//! constraint filter, preconditioned conjugate gradients on faer, and the multigrid
//! preconditioner.

mod row_chunks;
mod filter;
mod transient;
mod block_sparse;
mod diagonal_inverse;
mod multigrid;
mod pcg;

pub use block_sparse::BlockSparse;
pub(crate) use diagonal_inverse::inverse_diagonal;
pub use filter::{Constraint, ConstraintError, ConstraintKind, Filter};
pub use multigrid::{Multigrid, MultigridError};
pub use pcg::{FilteredSystem, Pcg, PcgError, PcgOutcome, PcgSettings, Preconditioner, Setup};
