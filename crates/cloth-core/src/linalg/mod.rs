//! Block-sparse linear algebra for the implicit step: the 3x3-block matrix, the
//! constraint filter, and preconditioned conjugate gradients on faer.

mod block_sparse;
mod filter;
mod multigrid;
mod pcg;
mod row_chunks;

pub use block_sparse::BlockSparse;
pub use filter::{Constraint, ConstraintKind, Filter};
pub use multigrid::Multigrid;
pub use pcg::{Pcg, PcgOutcome, PcgSettings, Preconditioner};
