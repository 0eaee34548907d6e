//! The prolongator `P` from a level to the next coarser one: a rectangular matrix of 3x3
//! blocks, fine nodes by aggregates, stored by rows with a transposed index so both `P x`
//! and `P^T r` run in parallel over their output rows.

use super::aggregation::Aggregates;
use crate::linalg::row_chunks::{for_each_entry, for_each_row};
use crate::linalg::BlockSparse;
use crate::math::{Mat3, Vec3};
use crate::parallelism::Parallelism;

#[derive(Debug, Clone, Default)]
pub(super) struct Prolongator {
    coarse: usize,
    row_ptr: Vec<usize>,
    cols: Vec<u32>,
    blocks: Vec<Mat3>,
    /// `P^T` by rows: for each coarse node its column's slots, in fine-row order, ...
    col_ptr: Vec<usize>,
    col_slots: Vec<u32>,
    /// ... the fine row of each, ...
    col_rows: Vec<u32>,
    /// ... and a copy of its blocks, so `P^T r` streams through memory as `P x` does.
    col_blocks: Vec<Mat3>,
    /// Scratch of the pattern: one row's columns, and each column's next free place.
    row: Vec<u32>,
    fill: Vec<usize>,
}

impl Prolongator {
    /// Makes the pattern of the smoothed prolongator `(I - w D^-1 A) P_tentative`, values
    /// zero: fine node `i` reaches the aggregates of its neighbours in `a`. In this
    /// prolongator's storage, which it allocates only to grow.
    pub fn set_pattern(&mut self, a: &BlockSparse, aggregates: &Aggregates) {
        let n = a.n();
        self.row_ptr.clear();
        self.cols.clear();
        self.row_ptr.push(0);
        for i in 0..n {
            self.row.clear();
            self.row.extend(a.row(i).map(|s| aggregates.of_node[a.col_of(s)]));
            self.row.sort_unstable();
            self.row.dedup();
            self.cols.extend_from_slice(&self.row);
            self.row_ptr.push(self.cols.len());
        }
        let coarse = aggregates.count;
        self.coarse = coarse;
        self.col_ptr.clear();
        self.col_ptr.resize(coarse + 1, 0);
        for &c in &self.cols {
            self.col_ptr[c as usize + 1] += 1;
        }
        for k in 0..coarse {
            self.col_ptr[k + 1] += self.col_ptr[k];
        }
        self.fill.clear();
        self.fill.extend_from_slice(&self.col_ptr);
        let nnz = self.cols.len();
        self.col_slots.resize(nnz, 0);
        self.col_rows.resize(nnz, 0);
        for i in 0..n {
            for s in self.row_ptr[i]..self.row_ptr[i + 1] {
                let c = self.cols[s] as usize;
                self.col_slots[self.fill[c]] = s as u32;
                self.col_rows[self.fill[c]] = i as u32;
                self.fill[c] += 1;
            }
        }
        self.blocks.clear();
        self.blocks.resize(nnz, Mat3::zeros());
        self.col_blocks.clear();
        self.col_blocks.resize(nnz, Mat3::zeros());
    }

    pub fn coarse(&self) -> usize {
        self.coarse
    }
    pub fn row(&self, i: usize) -> std::ops::Range<usize> {
        self.row_ptr[i]..self.row_ptr[i + 1]
    }
    pub fn col_of(&self, slot: usize) -> usize {
        self.cols[slot] as usize
    }
    pub fn blocks(&self) -> &[Mat3] {
        &self.blocks
    }
    /// The blocks of coarse column `a`, with their fine rows.
    pub fn column(&self, a: usize) -> impl Iterator<Item = (usize, &Mat3)> + '_ {
        let range = self.col_ptr[a]..self.col_ptr[a + 1];
        self.col_rows[range.clone()]
            .iter()
            .zip(&self.col_blocks[range])
            .map(|(&i, block)| (i as usize, block))
    }

    /// Fills the values row by row: `f(i, cols, blocks)` writes row `i`.
    pub fn fill_rows(&mut self, par: Parallelism, f: impl Fn(usize, &[u32], &mut [Mat3]) + Sync) {
        let cols = &self.cols;
        for_each_row(&self.row_ptr, &mut self.blocks, par, |i, first, row| {
            f(i, &cols[first..first + row.len()], row)
        });
        let (blocks, slots) = (&self.blocks, &self.col_slots);
        for_each_entry(&mut self.col_blocks, par, |k, b| *b = blocks[slots[k] as usize]);
    }

    /// `y += P x`: a coarse correction brought to the fine nodes.
    pub fn prolong_add(&self, x: &[Vec3], y: &mut [Vec3], par: Parallelism) {
        for_each_entry(y, par, |i, yi| {
            let mut s = Vec3::zeros();
            for slot in self.row(i) {
                s += self.blocks[slot] * x[self.cols[slot] as usize];
            }
            *yi += s;
        });
    }

    /// `out = P^T r`.
    pub fn restrict(&self, r: &[Vec3], out: &mut [Vec3], par: Parallelism) {
        for_each_entry(out, par, |a, o| {
            let mut s = Vec3::zeros();
            for (i, block) in self.column(a) {
                s += block.tr_mul(&r[i]);
            }
            *o = s;
        });
    }
}
