//! A symmetric matrix of 3x3 blocks in compressed rows, with the pattern fixed at build.
//!
//! Both triangles are stored so each row's product is independent: the product is
//! parallel over rows with no reduction across threads, hence identical for any
//! thread count.

use super::row_chunks::{for_each_entry, for_each_row};
use crate::{Mat3, Vec3};

#[derive(Debug, Clone)]
pub struct BlockSparse {
    row_ptr: Vec<usize>,
    cols: Vec<u32>,
    blocks: Vec<Mat3>,
    diag: Vec<u32>,
    transpose: Vec<u32>,
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
        let mut m = Self {
            blocks: vec![Mat3::zeros(); cols.len()],
            diag: vec![0; n],
            transpose: vec![0; cols.len()],
            row_ptr,
            cols,
        };
        for r in 0..n {
            for s in m.row_ptr[r]..m.row_ptr[r + 1] {
                let c = m.cols[s] as usize;
                m.transpose[s] = m.slot(c, r).expect("pattern is symmetric") as u32;
                if c == r {
                    m.diag[r] = s as u32;
                }
            }
        }
        m
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

    /// Sets the values row by row, in parallel when `parallel`: `f(r, first, blocks)` gets
    /// row `r`'s blocks, the first of them at storage slot `first`.
    pub fn fill_rows(&mut self, parallel: bool, f: impl Fn(usize, usize, &mut [Mat3]) + Sync) {
        for_each_row(&self.row_ptr, &mut self.blocks, parallel, f);
    }

    /// Zeroes every block but the diagonal ones, which become `diagonal(r)`; in parallel
    /// when `parallel`.
    pub fn reset(&mut self, parallel: bool, diagonal: impl Fn(usize) -> Mat3 + Sync) {
        let diag = &self.diag;
        for_each_row(&self.row_ptr, &mut self.blocks, parallel, |r, first, row| {
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

    /// `y = A x`, in parallel over rows when `parallel`.
    pub fn mul(&self, x: &[Vec3], y: &mut [Vec3], parallel: bool) {
        self.mul_then(x, y, parallel, |_, s| s);
    }

    /// `y_r = f(r, (A x)_r)`: a product whose rows are post-processed in the same pass.
    pub fn mul_then(
        &self,
        x: &[Vec3],
        y: &mut [Vec3],
        parallel: bool,
        f: impl Fn(usize, Vec3) -> Vec3 + Sync,
    ) {
        debug_assert_eq!(x.len(), self.n());
        debug_assert_eq!(y.len(), self.n());
        for_each_entry(y, parallel, |r, yr| {
            let mut s = Vec3::zeros();
            for slot in self.row(r) {
                s += self.blocks[slot] * x[self.cols[slot] as usize];
            }
            *yr = f(r, s);
        });
    }

    /// Dense copy (tests and diagnostics).
    pub fn to_dense(&self) -> nalgebra::DMatrix<f64> {
        let n = self.n();
        let mut d = nalgebra::DMatrix::zeros(3 * n, 3 * n);
        for r in 0..n {
            for s in self.row(r) {
                let c = self.col_of(s);
                d.view_mut((3 * r, 3 * c), (3, 3)).copy_from(&self.blocks[s]);
            }
        }
        d
    }
}
