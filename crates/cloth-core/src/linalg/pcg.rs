//! Preconditioned conjugate gradients through faer's matrix-free solver, with our
//! block-sparse operator and the constraint filter inside it, and a multigrid or
//! block-Jacobi preconditioner. All scratch is allocated by the first solve (and again
//! only if the matrix's pattern changes).

use super::{BlockSparse, Filter, Multigrid};
use crate::{Mat3, Vec3};
use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::matrix_free::conjugate_gradient::{
    conjugate_gradient, conjugate_gradient_scratch, CgError, CgInfo, CgParams,
};
use faer::matrix_free::{LinOp, Precond};
use faer::{Mat, MatMut, MatRef, Par};
use serde::{Deserialize, Serialize};

/// What preconditions the conjugate gradients.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Preconditioner {
    /// The inverse of each particle's 3x3 diagonal block: cheap, but the iteration count
    /// grows with the mesh's resolution.
    BlockJacobi,
    /// One V-cycle of smoothed-aggregation multigrid ([`Multigrid`]): an iteration count
    /// that grows far more slowly with the resolution, for a setup of a few matrix
    /// products per solve.
    Multigrid,
}

/// Stopping rule and preconditioner of the linear solve.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PcgSettings {
    /// Stop when `|r| <= rel_tolerance * |b|`.
    pub rel_tolerance: f64,
    pub max_iterations: usize,
    pub preconditioner: Preconditioner,
}

impl Default for PcgSettings {
    fn default() -> Self {
        Self {
            rel_tolerance: 1e-3,
            max_iterations: 1000,
            preconditioner: Preconditioner::Multigrid,
        }
    }
}

/// What one solve did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PcgOutcome {
    pub iterations: usize,
    pub rel_residual: f64,
    /// False when the iteration limit came first (the last iterate is kept).
    pub converged: bool,
}

/// `S A S + I - S` on vectors in the range of `S`, where it is `S A`: every CG vector stays
/// there (the right-hand side and the initial guess are projected, and both
/// preconditioners keep the split), so one product and a projection of the constrained
/// rows in the same pass is the whole filtered operator.
#[derive(Debug, Clone, Copy)]
struct Operator<'a> {
    a: &'a BlockSparse,
    filter: &'a Filter,
    parallel: bool,
}

#[derive(Debug)]
struct BlockJacobi<'a> {
    inv: &'a [Mat3],
}

/// A faer column of length 3n seen as n 3-vectors (no copy).
fn blocks(m: MatRef<'_, f64>) -> &[Vec3] {
    bytemuck::cast_slice(m.col(0).try_as_col_major().expect("contiguous column").as_slice())
}
fn blocks_mut(m: MatMut<'_, f64>) -> &mut [Vec3] {
    bytemuck::cast_slice_mut(
        m.col_mut(0)
            .try_as_col_major_mut()
            .expect("contiguous column")
            .as_slice_mut(),
    )
}

impl LinOp<f64> for Operator<'_> {
    fn apply_scratch(&self, _: usize, _: Par) -> StackReq {
        StackReq::EMPTY
    }
    fn nrows(&self) -> usize {
        3 * self.a.n()
    }
    fn ncols(&self) -> usize {
        3 * self.a.n()
    }
    fn apply(&self, out: MatMut<'_, f64>, rhs: MatRef<'_, f64>, _: Par, _: &mut MemStack) {
        let filter = self.filter;
        self.a
            .mul_then(blocks(rhs), blocks_mut(out), self.parallel, |r, y| {
                filter.project_row(r, y)
            });
    }
    fn conj_apply(&self, out: MatMut<'_, f64>, rhs: MatRef<'_, f64>, par: Par, stack: &mut MemStack) {
        self.apply(out, rhs, par, stack);
    }
}

impl LinOp<f64> for BlockJacobi<'_> {
    fn apply_scratch(&self, _: usize, _: Par) -> StackReq {
        StackReq::EMPTY
    }
    fn nrows(&self) -> usize {
        3 * self.inv.len()
    }
    fn ncols(&self) -> usize {
        3 * self.inv.len()
    }
    fn apply(&self, out: MatMut<'_, f64>, rhs: MatRef<'_, f64>, _: Par, _: &mut MemStack) {
        let (x, y) = (blocks(rhs), blocks_mut(out));
        for ((yk, xk), m) in y.iter_mut().zip(x).zip(self.inv) {
            *yk = m * xk;
        }
    }
    fn conj_apply(&self, out: MatMut<'_, f64>, rhs: MatRef<'_, f64>, par: Par, stack: &mut MemStack) {
        self.apply(out, rhs, par, stack);
    }
}

impl Precond<f64> for BlockJacobi<'_> {}

/// The multigrid V-cycle, for the filter of this solve.
#[derive(Debug)]
struct MultigridCycle<'a> {
    multigrid: &'a Multigrid,
    a: &'a BlockSparse,
    filter: &'a Filter,
    parallel: bool,
}

impl LinOp<f64> for MultigridCycle<'_> {
    fn apply_scratch(&self, _: usize, _: Par) -> StackReq {
        StackReq::EMPTY
    }
    fn nrows(&self) -> usize {
        3 * self.a.n()
    }
    fn ncols(&self) -> usize {
        3 * self.a.n()
    }
    fn apply(&self, out: MatMut<'_, f64>, rhs: MatRef<'_, f64>, _: Par, _: &mut MemStack) {
        self.multigrid
            .apply(self.a, self.filter, blocks(rhs), blocks_mut(out), self.parallel);
    }
    fn conj_apply(&self, out: MatMut<'_, f64>, rhs: MatRef<'_, f64>, par: Par, stack: &mut MemStack) {
        self.apply(out, rhs, par, stack);
    }
}

impl Precond<f64> for MultigridCycle<'_> {}

/// The inverses of the diagonal blocks of `a`, filtered by `filter` if given, or the
/// first block that has none.
pub(crate) fn inverse_diagonal(
    a: &BlockSparse,
    filter: Option<&Filter>,
    out: &mut [Mat3],
) -> Result<(), usize> {
    for (r, inv) in out.iter_mut().enumerate() {
        let d = a.blocks()[a.diag_slot(r)];
        let d = filter.map_or(d, |f| f.filtered_diagonal(r, &d));
        *inv = d.cholesky().ok_or(r)?.inverse();
    }
    Ok(())
}

/// Runs faer's conjugate gradients with `precond`.
fn run_cg(
    sol: MatMut<'_, f64>,
    precond: impl Precond<f64>,
    operator: Operator<'_>,
    rhs: MatRef<'_, f64>,
    params: CgParams<f64>,
    buffer: &mut MemBuffer,
) -> Result<CgInfo<f64>, CgError<f64>> {
    conjugate_gradient(
        sol,
        precond,
        operator,
        rhs,
        params,
        |_| {},
        Par::Seq,
        MemStack::new(buffer),
    )
}

/// Reusable PCG workspace for systems of `n` blocks.
pub struct Pcg {
    inv_diag: Vec<Mat3>,
    /// Made on the first multigrid solve, for the pattern of its matrix.
    multigrid: Option<Multigrid>,
    residual: Vec<Vec3>,
    rhs: Mat<f64>,
    sol: Mat<f64>,
    buffer: MemBuffer,
}

impl std::fmt::Debug for Pcg {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Pcg")
            .field("blocks", &self.inv_diag.len())
            .finish()
    }
}

impl Pcg {
    pub fn new(n: usize) -> Self {
        let inv_diag = vec![Mat3::identity(); n];
        let a = BlockSparse::from_pairs(n.max(1), []);
        let filter = Filter::new(n.max(1), 0);
        let req = conjugate_gradient_scratch(
            BlockJacobi { inv: &inv_diag },
            Operator {
                a: &a,
                filter: &filter,
                parallel: false,
            },
            1,
            Par::Seq,
        );
        Self {
            inv_diag,
            multigrid: None,
            residual: vec![Vec3::zeros(); n],
            rhs: Mat::zeros(3 * n, 1),
            sol: Mat::zeros(3 * n, 1),
            buffer: MemBuffer::new(req),
        }
    }

    /// Solves the filtered system `(S A S + I - S) x = b` for SPD `A` (see [`Filter`]),
    /// starting from the `x` given, to `settings` or to an absolute residual
    /// `abs_tolerance`, whichever is looser. `b` and `x` must be projected (`S b = b`,
    /// `S x = x`). The operator runs in parallel when `parallel`; faer's own vector work
    /// stays sequential so the result does not depend on the number of threads.
    #[allow(clippy::too_many_arguments)]
    pub fn solve(
        &mut self,
        a: &BlockSparse,
        filter: &Filter,
        b: &[Vec3],
        x: &mut [Vec3],
        settings: &PcgSettings,
        abs_tolerance: f64,
        parallel: bool,
    ) -> Result<PcgOutcome, String> {
        assert_eq!(a.n(), self.inv_diag.len(), "PCG workspace built for another size");
        blocks_mut(self.rhs.as_mut()).copy_from_slice(b);
        blocks_mut(self.sol.as_mut()).copy_from_slice(x);
        // The default MaybeNonZero initial guess: faer 0.24's `Zero` path leaves the
        // residual uninitialised.
        let params = CgParams {
            abs_tolerance,
            rel_tolerance: settings.rel_tolerance,
            max_iters: settings.max_iterations,
            ..Default::default()
        };
        let operator = Operator { a, filter, parallel };
        let result = match settings.preconditioner {
            Preconditioner::BlockJacobi => {
                inverse_diagonal(a, Some(filter), &mut self.inv_diag)
                    .map_err(|r| format!("diagonal block of particle {r} is not positive definite"))?;
                let precond = BlockJacobi { inv: &self.inv_diag };
                run_cg(
                    self.sol.as_mut(),
                    precond,
                    operator,
                    self.rhs.as_ref(),
                    params,
                    &mut self.buffer,
                )
            }
            Preconditioner::Multigrid => {
                let multigrid = match &mut self.multigrid {
                    Some(m) if m.fits(a) => m,
                    slot => slot.insert(Multigrid::new(a)),
                };
                multigrid.build(a, filter, parallel)?;
                let precond = MultigridCycle {
                    multigrid,
                    a,
                    filter,
                    parallel,
                };
                let result = run_cg(
                    self.sol.as_mut(),
                    precond,
                    operator,
                    self.rhs.as_ref(),
                    params,
                    &mut self.buffer,
                );
                if let Err(CgError::NonPositiveDefinitePreconditioner) = result {
                    // The smoother's weight rests on an estimate of the spectral radius;
                    // should it fall short, the cycle is not definite. Block Jacobi always
                    // is: solve again with it rather than fail the step.
                    inverse_diagonal(a, Some(filter), &mut self.inv_diag)
                        .map_err(|r| format!("diagonal block of particle {r} is not positive definite"))?;
                    blocks_mut(self.sol.as_mut()).copy_from_slice(x);
                    let precond = BlockJacobi { inv: &self.inv_diag };
                    run_cg(
                        self.sol.as_mut(),
                        precond,
                        operator,
                        self.rhs.as_ref(),
                        params,
                        &mut self.buffer,
                    )
                } else {
                    result
                }
            }
        };
        let outcome = match result {
            Ok(info) => PcgOutcome {
                iterations: info.iter_count,
                rel_residual: info.rel_residual,
                converged: true,
            },
            // faer 0.24 reports the initial residual here, so measure the final one.
            Err(CgError::NoConvergence { .. }) => {
                let x = blocks(self.sol.as_ref());
                a.mul_then(x, &mut self.residual, parallel, |r, y| filter.project_row(r, y));
                let (mut r2, mut b2) = (0.0, 0.0);
                for (ax, bk) in self.residual.iter().zip(b) {
                    r2 += (bk - ax).norm_squared();
                    b2 += bk.norm_squared();
                }
                PcgOutcome {
                    iterations: settings.max_iterations,
                    rel_residual: (r2 / b2).sqrt(),
                    converged: false,
                }
            }
            Err(CgError::NonPositiveDefiniteOperator) => {
                return Err("the system matrix is not positive definite".into())
            }
            Err(CgError::NonPositiveDefinitePreconditioner) => {
                return Err("the preconditioner is not positive definite".into())
            }
        };
        x.copy_from_slice(blocks(self.sol.as_ref()));
        Ok(outcome)
    }
}
