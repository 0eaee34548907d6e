//! A symmetric matrix of 3x3 blocks in compressed rows, with the pattern fixed at build,
//! plus transient couplings outside it that are set anew each step (contacts of the cloth
//! with itself, which join particles far apart in the mesh).
//!
//! Both triangles are stored so each row's product is independent: the product is
//! parallel over rows with no reduction across threads, hence identical for any
//! thread count.

use super::row_chunks::{for_each_entry, for_each_row};
use super::transient::Transient;
use crate::math::{Mat3, Vec3};
use crate::parallelism::Parallelism;

/// The default is a matrix of no rows, for a pattern to be set into
/// ([`BlockSparse::set_pattern`]).
#[derive(Debug, Clone, Default)]
pub struct BlockSparse {
    row_ptr: Vec<usize>,
    cols: Vec<u32>,
    blocks: Vec<Mat3>,
    diag: Vec<u32>,
    transpose: Vec<u32>,
    transient: Transient,
}

impl BlockSparse {
    /// The pattern with every diagonal block and both `(i, j)` and `(j, i)` for each
    /// coupled pair; values start at zero.
    pub fn from_pairs(n: usize, pairs: impl IntoIterator<Item = (usize, usize)>) -> Self {
        let mut rows: Vec<Vec<u32>> = (0..n).map(|i| vec![i as u32]).collect();
        for (i, j) in pairs {
            rows[i].push(j as u32);
            rows[j].push(i as u32);
        }
        let mut row_ptr = Vec::with_capacity(n + 1);
        let mut cols = Vec::new();
        row_ptr.push(0);
        for row in &mut rows {
            row.sort_unstable();
            row.dedup();
            cols.extend_from_slice(row);
            row_ptr.push(cols.len());
        }
        Self::from_rows(row_ptr, cols)
    }

    /// The pattern whose row `r` is `cols[row_ptr[r]..row_ptr[r + 1]]`: each row sorted,
    /// holding its diagonal, the whole symmetric; values start at zero.
    fn from_rows(row_ptr: Vec<usize>, cols: Vec<u32>) -> Self {
        let mut m = Self {
            row_ptr,
            cols,
            ..Self::default()
        };
        m.index_pattern();
        m
    }

    /// Makes this matrix's pattern `row_ptr` and `cols` (as [`BlockSparse::from_pairs`]
    /// makes it), values zero and no transient coupling, in its own storage: it allocates
    /// only to grow.
    pub(super) fn set_pattern(&mut self, row_ptr: &[usize], cols: &[u32]) {
        self.row_ptr.clear();
        self.row_ptr.extend_from_slice(row_ptr);
        self.cols.clear();
        self.cols.extend_from_slice(cols);
        self.index_pattern();
    }

    /// Sizes the values, the diagonal and the transposition of the pattern set in
    /// `row_ptr` and `cols`.
    fn index_pattern(&mut self) {
        let n = self.row_ptr.len() - 1;
        self.blocks.clear();
        self.blocks.resize(self.cols.len(), Mat3::zeros());
        self.diag.clear();
        self.diag.resize(n, 0);
        self.transpose.clear();
        self.transpose.resize(self.cols.len(), 0);
        if self.transient.size() == n {
            self.transient.clear();
        } else {
            self.transient = Transient::new(n);
        }
        for r in 0..n {
            for s in self.row_ptr[r]..self.row_ptr[r + 1] {
                let c = self.cols[s] as usize;
                self.transpose[s] = self.slot(c, r).expect("pattern is symmetric") as u32;
                if c == r {
                    self.diag[r] = s as u32;
                }
            }
            debug_assert_eq!(
                self.cols[self.diag[r] as usize] as usize, r,
                "row {r} holds its diagonal"
            );
        }
    }

    /// Number of block rows.
    pub fn n(&self) -> usize {
        self.diag.len()
    }
    /// Number of stored blocks.
    pub fn nnz_blocks(&self) -> usize {
        self.blocks.len()
    }
    /// Storage index of block (r, c), if it is in the pattern.
    pub fn slot(&self, r: usize, c: usize) -> Option<usize> {
        let range = self.row_ptr[r]..self.row_ptr[r + 1];
        self.cols[range.clone()]
            .binary_search(&(c as u32))
            .ok()
            .map(|k| range.start + k)
    }
    pub fn diag_slot(&self, r: usize) -> usize {
        self.diag[r] as usize
    }
    pub fn row(&self, r: usize) -> std::ops::Range<usize> {
        self.row_ptr[r]..self.row_ptr[r + 1]
    }
    pub fn col_of(&self, slot: usize) -> usize {
        self.cols[slot] as usize
    }
    pub fn transpose_slot(&self, slot: usize) -> usize {
        self.transpose[slot] as usize
    }
    /// The pattern: each row's first storage slot (and the end), and each slot's column.
    pub fn row_starts(&self) -> &[usize] {
        &self.row_ptr
    }
    pub fn columns(&self) -> &[u32] {
        &self.cols
    }
    pub fn blocks(&self) -> &[Mat3] {
        &self.blocks
    }
    pub fn blocks_mut(&mut self) -> &mut [Mat3] {
        &mut self.blocks
    }

    /// Sets the values row by row, on rayon's pool when `par` says so: `f(r, first, blocks)` gets
    /// row `r`'s blocks, the first of them at storage slot `first`.
    pub fn fill_rows(&mut self, par: Parallelism, f: impl Fn(usize, usize, &mut [Mat3]) + Sync) {
        for_each_row(&self.row_ptr, &mut self.blocks, par, f);
    }

    /// Zeroes every block but the diagonal ones, which become `diagonal(r)`, and drops the
    /// transient couplings; on rayon's pool when `par` says so.
    pub fn reset(&mut self, par: Parallelism, diagonal: impl Fn(usize) -> Mat3 + Sync) {
        self.transient.clear();
        let diag = &self.diag;
        for_each_row(&self.row_ptr, &mut self.blocks, par, |r, first, row| {
            row.fill(Mat3::zeros());
            row[diag[r] as usize - first] = diagonal(r);
        });
    }

    /// Makes the matrix exactly symmetric, `(A + A^T) / 2`, after an assembly whose two
    /// triangles were summed in different orders.
    pub fn symmetrize(&mut self) {
        for s in 0..self.blocks.len() {
            let t = self.transpose[s] as usize;
            if t >= s {
                let mean = 0.5 * (self.blocks[s] + self.blocks[t].transpose());
                self.blocks[s] = mean;
                self.blocks[t] = mean.transpose();
            }
        }
    }

    /// `y = A x`, over rows on rayon's pool when `par` says so.
    pub fn mul(&self, x: &[Vec3], y: &mut [Vec3], par: Parallelism) {
        self.mul_then(x, y, par, |_, s| s);
    }

    /// `y_r = f(r, (A x)_r)`: a product whose rows are post-processed in the same pass.
    pub fn mul_then(
        &self,
        x: &[Vec3],
        y: &mut [Vec3],
        par: Parallelism,
        f: impl Fn(usize, Vec3) -> Vec3 + Sync,
    ) {
        debug_assert_eq!(x.len(), self.n());
        debug_assert_eq!(y.len(), self.n());
        if self.transient.is_empty() {
            for_each_entry(y, par, |r, yr| *yr = f(r, self.fixed_row_product(r, x)));
        } else {
            for_each_entry(y, par, |r, yr| *yr = f(r, self.row_product(r, x)));
        }
    }

    /// `(A x)_r`, the transient couplings included.
    pub fn row_product(&self, r: usize, x: &[Vec3]) -> Vec3 {
        self.fixed_row_product(r, x) + self.transient.row_product(r, x)
    }

    #[inline]
    fn fixed_row_product(&self, r: usize, x: &[Vec3]) -> Vec3 {
        let mut s = Vec3::zeros();
        for slot in self.row(r) {
            s += self.blocks[slot] * x[self.cols[slot] as usize];
        }
        s
    }

    /// Diagonal block `r` of a block diagonal that bounds the matrix's transient couplings
    /// from above (see [`BlockSparse::add_coupling`]): the fixed pattern's diagonal block
    /// plus the couplings' bound, for Jacobi smoothing and preconditioning.
    pub fn smoother_diagonal(&self, r: usize) -> Mat3 {
        self.blocks[self.diag[r] as usize] + self.transient.smoother_block(r)
    }

    /// Adds a transient coupling: `G_a^T K G_b` at every pair of its `terms` `(i_a, G_a)`
    /// (a spring `K` on `sum_a G_a x_{i_a}`), kept outside the fixed pattern's values even
    /// where the pattern has the block: the fixed pattern stays the mesh's, which the
    /// multigrid aggregates along, and the multigrid folds the couplings into a copy of it
    /// for its coarse levels. Takes effect at [`BlockSparse::finish_transient`].
    pub fn add_coupling(&mut self, stiffness: Mat3, terms: impl IntoIterator<Item = (usize, Mat3)>) {
        self.transient.add(stiffness, terms);
    }

    /// Drops the transient couplings (a reset does too).
    pub fn clear_transient(&mut self) {
        self.transient.clear();
    }

    /// Gathers the transient couplings into rows, for the products.
    pub fn finish_transient(&mut self) {
        self.transient.finish();
    }

    /// Appends to `out` the columns of row `r` in the pattern and in the transient
    /// couplings, sorted, each once.
    pub(super) fn union_row(&self, r: usize, out: &mut Vec<u32>) {
        let fixed = &self.cols[self.row(r)];
        let mut coupled = self.transient.row_columns(r).peekable();
        for &c in fixed {
            while let Some(t) = coupled.next_if(|&t| t < c) {
                out.push(t);
            }
            coupled.next_if_eq(&c);
            out.push(c);
        }
        out.extend(coupled);
    }

    /// Sets every block to `a`'s, its transient couplings added in; this pattern must hold
    /// both of `a`'s (see [`BlockSparse::union_row`]). On rayon's pool when `par` says so.
    pub(super) fn set_folded(&mut self, a: &BlockSparse, par: Parallelism) {
        let cols = &self.cols;
        for_each_row(&self.row_ptr, &mut self.blocks, par, |r, first, row| {
            let row_cols = &cols[first..first + row.len()];
            let at = |c: u32| {
                row_cols
                    .binary_search(&c)
                    .expect("the pattern holds the couplings")
            };
            row.fill(Mat3::zeros());
            for s in a.row(r) {
                row[at(a.cols[s])] += a.blocks[s];
            }
            for (c, block) in a.transient.row_blocks(r) {
                row[at(c)] += block;
            }
        });
    }

    /// Whether transient couplings are set.
    pub fn has_transient(&self) -> bool {
        !self.transient.is_empty()
    }

    /// Dense copy, the transient couplings included (tests and diagnostics).
    pub fn to_dense(&self) -> nalgebra::DMatrix<f64> {
        let n = self.n();
        let mut d = nalgebra::DMatrix::zeros(3 * n, 3 * n);
        for r in 0..n {
            for s in self.row(r) {
                let c = self.col_of(s);
                d.view_mut((3 * r, 3 * c), (3, 3)).copy_from(&self.blocks[s]);
            }
        }
        for (r, c, b) in self.transient.blocks() {
            let mut view = d.view_mut((3 * r, 3 * c), (3, 3));
            view += b;
        }
        d
    }
}
