//! Smoothed-aggregation algebraic multigrid (Vaněk, Mandel & Brezina 1996) for the
//! filtered system, in the form Tamstorf, Jones & McCormick (2015) give for cloth: the
//! near-null space on the finest level is the translations each node's constraints leave
//! free, so every coarse correction already obeys the filter and the coarse matrices are
//! plain Galerkin products `P^T (S A S) P`.
//!
//! One V-cycle with damped block-Jacobi smoothing is the preconditioner of PCG. The
//! aggregates of every level are made once per matrix pattern, along the mesh's
//! couplings alone; a [`Multigrid::build`] recomputes the values. A matrix's transient
//! couplings (the cloth's contacts with itself) are folded into its pattern for the
//! smoothed prolongator and the coarse matrices (see [`folded`]); the patterns and plans
//! that follow are made again, in their own storage, when the couplings join other pairs.

mod aggregation;
mod folded;
mod galerkin;
mod prolongator;
mod spectrum;
mod tentative;

use super::{inverse_diagonal, BlockSparse, Filter};
use crate::math::{Mat3, Vec3};
use crate::parallelism::Parallelism;
use aggregation::{aggregate, Aggregates};
use folded::Folded;
use galerkin::Galerkin;
use nalgebra::{DMatrix, DVector};
use prolongator::Prolongator;
use spectrum::Spectrum;
use std::sync::Mutex;
use tentative::Tentative;

/// Strength threshold of the finest level's aggregation: cloth's bending couplings are a
/// few hundredths of its stretch couplings, and aggregating across them slows the
/// convergence (55 against 67 iterations to 1e-6 for the 30 x 30 sheet of
/// `tests/multigrid.rs`).
const STRENGTH: f64 = 0.02;
/// A level this small (in nodes) is solved directly.
const COARSEST_NODES: usize = 64;
/// Levels at most, the finest included (each at most half the size of the one above).
const MAX_LEVELS: usize = 32;
/// Jacobi damping and prolongator smoothing weight, over the spectral radius of `D^-1 A`
/// (the smoother converges below 2, so this leaves 10% for the estimate's error). Above
/// the textbook 4/3 because it converges faster here: a median of 19 rather than 24 CG
/// iterations a step in `cargo bench --bench step` (the hanging 110 x 110 sheet), 36
/// rather than 38 in the sphere step of `cargo bench --bench contact`.
const JACOBI_WEIGHT: f64 = 1.8;
/// Levels storing fewer blocks run sequentially: their work is smaller than a thread's wake-up.
const PARALLEL_BLOCKS: usize = 16_384;

/// One level above the coarsest: its smoother and its prolongator to the next.
#[derive(Debug, Clone)]
struct Level {
    aggregates: Aggregates,
    p: Prolongator,
    galerkin: Galerkin,
    tentative: Tentative,
    inv_diag: Vec<Mat3>,
    /// Jacobi damping of the smoother and of the prolongator, `JACOBI_WEIGHT / rho(D^-1 A)`.
    omega: f64,
}

/// Per-level vectors of a cycle.
#[derive(Debug, Clone, Default)]
struct Scratch {
    b: Vec<Vec3>,
    x: Vec<Vec3>,
    r: Vec<Vec3>,
}

/// Why the multigrid hierarchy could not be built.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum MultigridError {
    /// A diagonal block of a level's matrix, the smoother's, is not positive definite.
    #[error("multigrid level {level}: diagonal block {block} is not positive definite")]
    NotDefinite { level: usize, block: usize },
    #[error("multigrid: the coarsest matrix is not positive definite")]
    CoarsestNotDefinite,
}

/// The multigrid hierarchy of one matrix pattern.
#[derive(Debug)]
pub struct Multigrid {
    levels: Vec<Level>,
    /// The matrices of levels 1.. (the last one the coarsest's).
    coarse: Vec<BlockSparse>,
    /// Cholesky factor of the coarsest matrix, dense.
    factor: Option<nalgebra::Cholesky<f64, nalgebra::Dyn>>,
    /// Near-null space of the finest level: each particle's free translations.
    fine_basis: Vec<Mat3>,
    /// The finest matrix's own pattern (row starts, columns), the aggregates' ...
    mesh_pattern: (Vec<usize>, Vec<u32>),
    /// ... and whether the prolongators and coarse patterns are made for it, or for it
    /// with the transient couplings of the last build folded in.
    folded_in: bool,
    folded: Folded,
    scratch: Mutex<(Vec<Scratch>, DVector<f64>)>,
    spectrum: Spectrum,
}

/// `y_i = g(i, (A x)_i)`, or with `filter`, `g(i, (S A x)_i)`: the filtered
/// `S A S + I - S` on the range of `S`, where every vector of the finest level lives.
fn product_then(
    m: &BlockSparse,
    filter: Option<&Filter>,
    x: &[Vec3],
    y: &mut [Vec3],
    par: Parallelism,
    g: impl Fn(usize, Vec3) -> Vec3 + Sync,
) {
    match filter {
        Some(f) => m.mul_then(x, y, par, |i, v| g(i, f.project_row(i, v))),
        None => m.mul_then(x, y, par, g),
    }
}

impl Multigrid {
    /// The hierarchy's structure for matrices with `a`'s pattern. The finest level is
    /// aggregated along `a`'s strong couplings; the coarse levels, whose values are not
    /// known yet, along all of theirs. Transient couplings, which join other pairs at
    /// every step, are not aggregated along: aggregates that join layers across their
    /// contacts move them together in every coarse correction, where pressed layers
    /// still slide past each other (two sheets pressed together took 146 iterations to
    /// 1e-6 so, 76 with the finest level aggregated along each sheet, 52 with every level,
    /// as many as apart: `tests/multigrid.rs`).
    pub fn new(a: &BlockSparse) -> Self {
        let mut levels: Vec<Level> = Vec::new();
        let mut coarse: Vec<BlockSparse> = Vec::new();
        let mut scratch = Vec::new();
        let mut n = a.n();
        while n > COARSEST_NODES && levels.len() + 1 < MAX_LEVELS {
            let m = coarse.last().unwrap_or(a);
            let strength = if levels.is_empty() { STRENGTH } else { 0.0 };
            let aggregates = aggregate(m, strength);
            debug_assert!(2 * aggregates.count <= n + 1, "aggregation halves a level");
            let mut level = Level {
                aggregates,
                p: Prolongator::default(),
                galerkin: Galerkin::default(),
                tentative: Tentative::default(),
                inv_diag: vec![Mat3::identity(); n],
                omega: 0.0,
            };
            let mut next = BlockSparse::default();
            level.p.set_pattern(m, &level.aggregates);
            level.galerkin.plan(m, &level.p, &mut next);
            scratch.push(Scratch {
                b: vec![Vec3::zeros(); n],
                x: vec![Vec3::zeros(); n],
                r: vec![Vec3::zeros(); n],
            });
            levels.push(level);
            n = next.n();
            coarse.push(next);
        }
        scratch.push(Scratch {
            b: vec![Vec3::zeros(); n],
            x: vec![Vec3::zeros(); n],
            r: Vec::new(),
        });
        Self {
            levels,
            coarse,
            factor: None,
            fine_basis: vec![Mat3::identity(); a.n()],
            mesh_pattern: (a.row_starts().to_vec(), a.columns().to_vec()),
            folded_in: false,
            folded: Folded::default(),
            spectrum: Spectrum::new(a.n()),
            scratch: Mutex::new((scratch, DVector::zeros(3 * n))),
        }
    }

    /// Whether this hierarchy was made for `a`'s pattern (its own, transient couplings
    /// aside).
    pub fn fits(&self, a: &BlockSparse) -> bool {
        self.mesh_pattern.0 == a.row_starts() && self.mesh_pattern.1 == a.columns()
    }

    /// Makes every prolongator's pattern, product plan and coarse pattern for the finest
    /// matrix `fine`, the aggregates kept.
    fn set_patterns(&mut self, fine: &BlockSparse) {
        for l in 0..self.levels.len() {
            let (done, rest) = self.coarse.split_at_mut(l);
            let m = if l == 0 { fine } else { &done[l - 1] };
            let level = &mut self.levels[l];
            level.p.set_pattern(m, &level.aggregates);
            level.galerkin.plan(m, &level.p, &mut rest[0]);
        }
    }

    /// Number of levels, the coarsest included.
    pub fn depth(&self) -> usize {
        self.levels.len() + 1
    }

    /// Computes every level's values for the filtered matrix `S A S + I - S`.
    pub fn build(
        &mut self,
        a: &BlockSparse,
        filter: &Filter,
        par: Parallelism,
    ) -> Result<(), MultigridError> {
        // Taken out for the build, so the folded matrix can be read while the levels are
        // written.
        let mut folded = std::mem::take(&mut self.folded);
        let result = self.build_folded(a, &mut folded, filter, par);
        self.folded = folded;
        result
    }

    fn build_folded(
        &mut self,
        a: &BlockSparse,
        folded: &mut Folded,
        filter: &Filter,
        par: Parallelism,
    ) -> Result<(), MultigridError> {
        let fold = a.has_transient();
        let (fine, changed) = if fold {
            folded.fold(a, par.for_size(a.nnz_blocks(), PARALLEL_BLOCKS))
        } else {
            (a, false)
        };
        if changed || fold != self.folded_in {
            self.set_patterns(fine);
        }
        self.folded_in = fold;
        for l in 0..self.levels.len() {
            let (done, rest) = self.coarse.split_at_mut(l);
            // The smoother's diagonal is `a`'s, which bounds its transient couplings from
            // above (on their own diagonal blocks, Jacobi does poorly); its products are
            // the same operator as the folded matrix's.
            let (m, smoother) = if l == 0 {
                (fine, a)
            } else {
                (&done[l - 1], &done[l - 1])
            };
            let f = (l == 0).then_some(filter);
            let par = par.for_size(m.nnz_blocks(), PARALLEL_BLOCKS);
            let (above, below) = self.levels.split_at_mut(l);
            let level = &mut below[0];
            let basis = match above.last() {
                Some(up) => &up.tentative.coarse_basis,
                None => {
                    for (i, b) in self.fine_basis.iter_mut().enumerate() {
                        *b = filter.free_projection(i);
                    }
                    &self.fine_basis
                }
            };
            inverse_diagonal(smoother, f, &mut level.inv_diag, par)
                .map_err(|block| MultigridError::NotDefinite { level: l, block })?;
            level.omega = JACOBI_WEIGHT / self.spectrum.radius(smoother, f, &level.inv_diag, par);
            level.tentative.build(basis, &level.aggregates);
            smooth_prolongator(level, m, f, par);
            level.galerkin.multiply(m, &level.p, &mut rest[0], par);
            for (c, empty) in level.tentative.empty.iter().enumerate() {
                let d = rest[0].diag_slot(c);
                rest[0].blocks_mut()[d] += empty;
            }
        }
        // The factor is made in the storage of the last one.
        let mut dense = match self.factor.take() {
            Some(factor) => factor.unpack(),
            None => {
                let n = 3 * self.coarse.last().unwrap_or(fine).n();
                DMatrix::zeros(n, n)
            }
        };
        match self.coarse.last() {
            Some(m) => dense_into(m, None, &mut dense),
            None => dense_into(fine, Some(filter), &mut dense),
        }
        self.factor = Some(nalgebra::Cholesky::new(dense).ok_or(MultigridError::CoarsestNotDefinite)?);
        Ok(())
    }

    /// Brings the finest smoother up to date with `a` and `filter`, the rest of the
    /// hierarchy kept from the last build (see [`crate::linalg::Setup::RefreshFinest`]). The
    /// filter may only have freed directions since: the coarse corrections then stay in
    /// its range. The smoother's spectral radius is estimated again, as letting go of a
    /// contact's drag may raise it.
    pub fn refresh_finest(
        &mut self,
        a: &BlockSparse,
        filter: &Filter,
        par: Parallelism,
    ) -> Result<(), MultigridError> {
        let Some(level) = self.levels.first_mut() else {
            // A single level is the dense factor of the filtered matrix itself.
            return self.build(a, filter, par);
        };
        inverse_diagonal(a, Some(filter), &mut level.inv_diag, par)
            .map_err(|block| MultigridError::NotDefinite { level: 0, block })?;
        level.omega = JACOBI_WEIGHT / self.spectrum.radius(a, Some(filter), &level.inv_diag, par);
        Ok(())
    }

    /// `x = M b`, one V-cycle; `b` and `x` are in the range of `filter`.
    pub fn apply(&self, a: &BlockSparse, filter: &Filter, b: &[Vec3], x: &mut [Vec3], par: Parallelism) {
        // A panic inside a cycle leaves nothing half-done in the scratch: every vector in
        // it is written before it is read.
        let mut guard = self.scratch.lock().unwrap_or_else(|e| e.into_inner());
        let (scratch, dense) = &mut *guard;
        scratch[0].b.copy_from_slice(b);
        self.cycle(0, a, filter, scratch, dense, par);
        x.copy_from_slice(&scratch[0].x);
        // Exact in exact arithmetic (the prolongator's rows are projected); this keeps
        // rounding out of the constrained directions, which CG must never see.
        filter.project(x);
    }

    /// One V-cycle on level `l`, from `scratch[0].b` into `scratch[0].x`.
    fn cycle(
        &self,
        l: usize,
        a: &BlockSparse,
        filter: &Filter,
        scratch: &mut [Scratch],
        dense: &mut DVector<f64>,
        par: Parallelism,
    ) {
        let (here, below) = scratch.split_first_mut().expect("a scratch per level");
        let (b, x) = (&here.b, &mut here.x);
        let Some(level) = self.levels.get(l) else {
            let factor = self.factor.as_ref().expect("built before use");
            for (k, bk) in b.iter().enumerate() {
                dense.fixed_rows_mut::<3>(3 * k).copy_from(bk);
            }
            factor.solve_mut(dense);
            for (k, xk) in x.iter_mut().enumerate() {
                *xk = dense.fixed_rows::<3>(3 * k).into();
            }
            return;
        };
        let (m, f) = if l == 0 {
            (a, Some(filter))
        } else {
            (&self.coarse[l - 1], None)
        };
        let par = par.for_size(m.nnz_blocks(), PARALLEL_BLOCKS);
        let r = &mut here.r;
        for ((xk, bk), inv) in x.iter_mut().zip(b).zip(&level.inv_diag) {
            *xk = level.omega * (inv * bk);
        }
        product_then(m, f, x, r, par, |i, v| b[i] - v);
        level.p.restrict(r, &mut below[0].b, par);
        self.cycle(l + 1, a, filter, below, dense, par);
        level.p.prolong_add(&below[0].x, x, par);
        product_then(m, f, x, r, par, |i, v| b[i] - v);
        for ((xk, rk), inv) in x.iter_mut().zip(r.iter()).zip(&level.inv_diag) {
            *xk += level.omega * (inv * rk);
        }
    }
}

/// `P = (I - w D^-1 A) T`, `T` the tentative prolongator; on the finest level the rows
/// are projected by the filter, so every correction obeys the constraints.
fn smooth_prolongator(level: &mut Level, m: &BlockSparse, f: Option<&Filter>, par: Parallelism) {
    let (t, of_node) = (&level.tentative.blocks, &level.aggregates.of_node);
    let (inv_diag, omega) = (&level.inv_diag, level.omega);
    level.p.fill_rows(par, |i, cols, row| {
        row.fill(Mat3::zeros());
        let column = |g: u32| {
            cols.iter()
                .position(|&c| c == g)
                .expect("the pattern holds every neighbour's aggregate")
        };
        for s in m.row(i) {
            let j = m.col_of(s);
            row[column(of_node[j])] += m.blocks()[s] * t[j];
        }
        for block in row.iter_mut() {
            let projected = f.map_or(*block, |f| f.free_projection(i) * *block);
            *block = -omega * (inv_diag[i] * projected);
        }
        row[column(of_node[i])] += t[i];
    });
}

/// `m`, dense, into `out`; with `filter`, the filtered `S m S + I - S`.
fn dense_into(m: &BlockSparse, filter: Option<&Filter>, out: &mut DMatrix<f64>) {
    out.fill(0.0);
    let free = |r| filter.map_or(Mat3::identity(), |f| f.free_projection(r));
    for r in 0..m.n() {
        for s in m.row(r) {
            let c = m.col_of(s);
            let block = free(r) * m.blocks()[s] * free(c);
            out.fixed_view_mut::<3, 3>(3 * r, 3 * c).copy_from(&block);
        }
        let mut diag = out.fixed_view_mut::<3, 3>(3 * r, 3 * r);
        diag += Mat3::identity() - free(r);
    }
}
