//! Preconditioned conjugate gradients through faer's matrix-free solver, with our
//! block-sparse operator and the constraint filter inside it, and a multigrid or
//! block-Jacobi preconditioner. All scratch is allocated by the first solve (and again
//! only if the matrix's pattern changes).

use super::diagonal_inverse::inverse_diagonal;
use super::{BlockSparse, Filter, Multigrid, MultigridError};
use crate::math::{Mat3, Vec3};
use crate::parallelism::Parallelism;
use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::matrix_free::conjugate_gradient::{
    conjugate_gradient, conjugate_gradient_scratch, CgError, CgInfo, CgParams,
};
use faer::matrix_free::{LinOp, Precond};
use faer::{Mat, MatMut, MatRef, Par};
use serde::{Deserialize, Serialize};

/// Why a solve failed (not converging is an outcome, not an error: see [`PcgOutcome`]).
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum PcgError {
    #[error("diagonal block of particle {particle} is not positive definite")]
    DiagonalNotDefinite { particle: usize },
    #[error("the system matrix is not positive definite")]
    MatrixNotDefinite,
    #[error("the preconditioner is not positive definite")]
    PreconditionerNotDefinite,
    #[error(transparent)]
    Multigrid(#[from] MultigridError),
}

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

/// A linear map on `n` 3-vectors, `f(x, y)` writing `y`: our operator and preconditioners
/// seen through faer's interfaces (a faer column of length 3n is n 3-vectors, no copy).
#[derive(Clone, Copy)]
struct BlockMap<F> {
    n: usize,
    f: F,
}

impl<F> std::fmt::Debug for BlockMap<F> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("BlockMap").field("n", &self.n).finish()
    }
}

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

impl<F: Fn(&[Vec3], &mut [Vec3]) + Sync> LinOp<f64> for BlockMap<F> {
    fn apply_scratch(&self, _: usize, _: Par) -> StackReq {
        StackReq::EMPTY
    }
    fn nrows(&self) -> usize {
        3 * self.n
    }
    fn ncols(&self) -> usize {
        3 * self.n
    }
    fn apply(&self, out: MatMut<'_, f64>, rhs: MatRef<'_, f64>, _: Par, _: &mut MemStack) {
        (self.f)(blocks(rhs), blocks_mut(out));
    }
    fn conj_apply(&self, out: MatMut<'_, f64>, rhs: MatRef<'_, f64>, par: Par, stack: &mut MemStack) {
        self.apply(out, rhs, par, stack);
    }
}

impl<F: Fn(&[Vec3], &mut [Vec3]) + Sync> Precond<f64> for BlockMap<F> {}

/// `S A S + I - S` on vectors in the range of `S`, where it is `S A`: every CG vector stays
/// there (the right-hand side and the initial guess are projected, and both
/// preconditioners keep the split), so one product and a projection of the constrained
/// rows in the same pass is the whole filtered operator.
fn filtered_product<'a>(
    a: &'a BlockSparse,
    filter: &'a Filter,
    par: Parallelism,
) -> BlockMap<impl Fn(&[Vec3], &mut [Vec3]) + Sync + Copy + 'a> {
    BlockMap {
        n: a.n(),
        f: move |x: &[Vec3], y: &mut [Vec3]| a.mul_then(x, y, par, |r, v| filter.project_row(r, v)),
    }
}

/// The block-Jacobi preconditioner: each particle's inverse diagonal block.
fn block_jacobi(inv: &[Mat3]) -> BlockMap<impl Fn(&[Vec3], &mut [Vec3]) + Sync + '_> {
    BlockMap {
        n: inv.len(),
        f: move |x: &[Vec3], y: &mut [Vec3]| {
            for ((yk, xk), m) in y.iter_mut().zip(x).zip(inv) {
                *yk = m * xk;
            }
        },
    }
}

/// Whether conjugate gradients found the operator or the preconditioner not definite.
/// faer 0.24 cannot tell which: a preconditioner with `r^T z <= 0` after the first
/// iteration is reported as `NonPositiveDefiniteOperator` (GarmentCode's rand_1_099 and
/// rand_1_068 failed every substep so, on a matrix whose diagonal blocks and couplings are
/// all definite), so a multigrid solve that ends in either is taken again with block
/// Jacobi, and only Jacobi's says the matrix is at fault.
fn not_definite(e: &CgError<f64>) -> bool {
    matches!(
        e,
        CgError::NonPositiveDefiniteOperator | CgError::NonPositiveDefinitePreconditioner
    )
}

/// Runs faer's conjugate gradients with `precond`.
fn run_cg(
    sol: MatMut<'_, f64>,
    precond: impl Precond<f64>,
    operator: impl LinOp<f64>,
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

/// How much of the last solve's preconditioner a solve keeps (see [`Pcg::solve_with`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Setup {
    /// Nothing: the multigrid hierarchy is built for this matrix and filter.
    Build,
    /// After a solve of a system that differs from this one only in a few particles'
    /// rows, and whose filter constrained those particles more (a contact let go within a
    /// step): its hierarchy is kept, only the finest smoother brought up to date (its
    /// inverse diagonal, and its spectral radius estimated again, so the cycle stays
    /// symmetric and definite). The coarse spaces miss the freed directions and the
    /// coarse matrices the changed rows, which the smoother makes good, at a few
    /// iterations rather than a whole setup.
    RefreshFinest,
    /// Everything, for the matrix and filter of the last solve solved further (say to a
    /// tighter tolerance).
    Keep,
}

/// The system a solve is asked: the matrix `A`, the filter `S` of the step's constraints,
/// and the right-hand side `b`.
#[derive(Debug, Clone, Copy)]
pub struct FilteredSystem<'a> {
    pub matrix: &'a BlockSparse,
    pub filter: &'a Filter,
    pub rhs: &'a [Vec3],
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
            block_jacobi(&inv_diag),
            filtered_product(&a, &filter, Parallelism::Sequential),
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

    /// Solves the filtered system `(S A S + I - S) x = b` for SPD `A` (see [`Filter`] and
    /// [`FilteredSystem`]),
    /// starting from the `x` given, to `settings` or to an absolute residual
    /// `abs_tolerance`, whichever is looser. `b` and `x` must be projected (`S b = b`,
    /// `S x = x`). The operator runs on rayon's pool when `par` says so; faer's own vector work
    /// stays sequential so the result does not depend on the number of threads.
    pub fn solve(
        &mut self,
        system: FilteredSystem<'_>,
        x: &mut [Vec3],
        settings: &PcgSettings,
        abs_tolerance: f64,
        par: Parallelism,
    ) -> Result<PcgOutcome, PcgError> {
        self.solve_with(system, x, settings, abs_tolerance, par, Setup::Build)
    }

    /// As [`Pcg::solve`], keeping as much of the last solve's preconditioner as `setup`
    /// says.
    pub fn solve_with(
        &mut self,
        system: FilteredSystem<'_>,
        x: &mut [Vec3],
        settings: &PcgSettings,
        abs_tolerance: f64,
        par: Parallelism,
        setup: Setup,
    ) -> Result<PcgOutcome, PcgError> {
        let FilteredSystem {
            matrix: a,
            filter,
            rhs: b,
        } = system;
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
        let operator = filtered_product(a, filter, par);
        let mut result = None;
        if settings.preconditioner == Preconditioner::Multigrid {
            match (&mut self.multigrid, setup) {
                (Some(m), Setup::Keep) if m.fits(a) => {}
                (Some(m), Setup::RefreshFinest) if m.fits(a) => m.refresh_finest(a, filter, par)?,
                (Some(m), _) if m.fits(a) => m.build(a, filter, par)?,
                (slot, _) => slot.insert(Multigrid::new(a)).build(a, filter, par)?,
            }
            let multigrid = self.multigrid.as_ref().expect("made above");
            let cycle = BlockMap {
                n: a.n(),
                f: |x: &[Vec3], y: &mut [Vec3]| multigrid.apply(a, filter, x, y, par),
            };
            let rhs = self.rhs.as_ref();
            match run_cg(self.sol.as_mut(), cycle, operator, rhs, params, &mut self.buffer) {
                // The smoother's weight rests on an estimate of the spectral radius; should
                // it fall short, the cycle is not definite. Block Jacobi always is: solve
                // again with it rather than fail the step.
                Err(e) if not_definite(&e) => {
                    blocks_mut(self.sol.as_mut()).copy_from_slice(x);
                }
                other => result = Some(other),
            }
        }
        let result = match result {
            Some(result) => result,
            None => {
                inverse_diagonal(a, Some(filter), &mut self.inv_diag, par)
                    .map_err(|particle| PcgError::DiagonalNotDefinite { particle })?;
                let precond = block_jacobi(&self.inv_diag);
                let rhs = self.rhs.as_ref();
                run_cg(
                    self.sol.as_mut(),
                    precond,
                    operator,
                    rhs,
                    params,
                    &mut self.buffer,
                )
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
                (operator.f)(blocks(self.sol.as_ref()), &mut self.residual);
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
            Err(CgError::NonPositiveDefiniteOperator) => return Err(PcgError::MatrixNotDefinite),
            Err(CgError::NonPositiveDefinitePreconditioner) => {
                return Err(PcgError::PreconditionerNotDefinite)
            }
        };
        x.copy_from_slice(blocks(self.sol.as_ref()));
        Ok(outcome)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// faer reports a preconditioner that turns indefinite after the first iteration as an
    /// indefinite operator; either is taken as "not definite", and block Jacobi on the
    /// same definite system then solves it.
    #[test]
    fn an_indefinite_preconditioner_is_told_apart_only_by_solving_again() {
        let n = 6;
        // A definite operator with distinct eigenvalues, so CG takes several iterations.
        let diagonal: Vec<Mat3> = (0..n)
            .map(|k| {
                Mat3::from_diagonal(&Vec3::new(
                    1.0 + k as f64,
                    2.0 + 0.5 * k as f64,
                    3.0 + 2.0 * k as f64,
                ))
            })
            .collect();
        let operator = BlockMap {
            n,
            f: |x: &[Vec3], y: &mut [Vec3]| {
                for ((yk, xk), d) in y.iter_mut().zip(x).zip(&diagonal) {
                    *yk = d * xk;
                }
            },
        };
        let b: Vec<f64> = (0..3 * n).map(|i| 1.0 + (i % 5) as f64).collect();
        let rhs = Mat::from_fn(3 * n, 1, |i, _| b[i]);
        let params = CgParams {
            rel_tolerance: 1e-12,
            max_iters: 100,
            ..Default::default()
        };
        let mut buffer = MemBuffer::new(conjugate_gradient_scratch(
            block_jacobi(&diagonal),
            operator,
            1,
            Par::Seq,
        ));
        // Definite on the first residual (positive where it is largest), indefinite
        // afterwards: a smoother whose weight overshoots on some modes.
        let flipped: Vec<Mat3> = (0..n)
            .map(|k| {
                if k % 2 == 0 {
                    Mat3::identity()
                } else {
                    -0.9 * Mat3::identity()
                }
            })
            .collect();
        let mut sol = Mat::<f64>::zeros(3 * n, 1);
        let result = run_cg(
            sol.as_mut(),
            block_jacobi(&flipped),
            operator,
            rhs.as_ref(),
            params,
            &mut buffer,
        );
        match result {
            Err(e) => assert!(not_definite(&e), "{e:?}"),
            Ok(info) => panic!(
                "an indefinite preconditioner converged in {} iterations",
                info.iter_count
            ),
        }
        let inverse: Vec<Mat3> = diagonal
            .iter()
            .map(|d| d.try_inverse().expect("definite"))
            .collect();
        let mut sol = Mat::<f64>::zeros(3 * n, 1);
        run_cg(
            sol.as_mut(),
            block_jacobi(&inverse),
            operator,
            rhs.as_ref(),
            params,
            &mut buffer,
        )
        .expect("block Jacobi on a definite system");
        for (k, (x, d)) in blocks(sol.as_ref()).iter().zip(&diagonal).enumerate() {
            let expected = Vec3::new(b[3 * k], b[3 * k + 1], b[3 * k + 2]);
            assert!((d * x - expected).norm() < 1e-9, "block {k}");
        }
    }
}
