//! Block-sparse linear algebra for the implicit step: the 3x3-block matrix, the
//! constraint filter, preconditioned conjugate gradients on faer, and the multigrid
//! preconditioner.

mod block_sparse;
mod filter;
mod multigrid;
mod pcg;
mod row_chunks;
mod transient;

pub use block_sparse::BlockSparse;
pub use filter::{Constraint, ConstraintKind, Filter};
pub use multigrid::Multigrid;
pub(crate) use pcg::inverse_diagonal;
pub use pcg::{Pcg, PcgOutcome, PcgSettings, Preconditioner, Setup};
