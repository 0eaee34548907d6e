//! The prolongator `P` from a level to the next coarser one: a rectangular matrix of 3x3
//! blocks, fine nodes by aggregates, stored by rows with a transposed index so both `P x`
//! and `P^T r` run in parallel over their output rows.

use super::aggregation::Aggregates;
use crate::linalg::row_chunks::{for_each_entry, for_each_row};
use crate::linalg::BlockSparse;
use crate::{Mat3, Vec3};

#[derive(Debug, Clone)]
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
}

impl Prolongator {
    /// The pattern of the smoothed prolongator `(I - w D^-1 A) P_tentative`: fine node `i`
    /// reaches the aggregates of its neighbours in `a`.
    pub fn pattern(a: &BlockSparse, aggregates: &Aggregates) -> Self {
        let n = a.n();
        let mut row_ptr = Vec::with_capacity(n + 1);
        let mut cols = Vec::new();
        row_ptr.push(0);
        let mut row = Vec::new();
        for i in 0..n {
            row.clear();
            row.extend(a.row(i).map(|s| aggregates.of_node[a.col_of(s)]));
            row.sort_unstable();
            row.dedup();
            cols.extend_from_slice(&row);
            row_ptr.push(cols.len());
        }
        let coarse = aggregates.count;
        let mut col_count = vec![0usize; coarse + 1];
        for &c in &cols {
            col_count[c as usize + 1] += 1;
        }
        let mut col_ptr = col_count;
        for k in 0..coarse {
            col_ptr[k + 1] += col_ptr[k];
        }
        let mut fill = col_ptr.clone();
        let mut col_slots = vec![0u32; cols.len()];
        let mut col_rows = vec![0u32; cols.len()];
        for i in 0..n {
            for s in row_ptr[i]..row_ptr[i + 1] {
                let c = cols[s] as usize;
                col_slots[fill[c]] = s as u32;
                col_rows[fill[c]] = i as u32;
                fill[c] += 1;
            }
        }
        Self {
            coarse,
            blocks: vec![Mat3::zeros(); cols.len()],
            col_blocks: vec![Mat3::zeros(); cols.len()],
            row_ptr,
            cols,
            col_ptr,
            col_slots,
            col_rows,
        }
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
    pub fn fill_rows(&mut self, parallel: bool, f: impl Fn(usize, &[u32], &mut [Mat3]) + Sync) {
        let cols = &self.cols;
        for_each_row(&self.row_ptr, &mut self.blocks, parallel, |i, first, row| {
            f(i, &cols[first..first + row.len()], row)
        });
        let (blocks, slots) = (&self.blocks, &self.col_slots);
        for_each_entry(&mut self.col_blocks, parallel, |k, b| {
            *b = blocks[slots[k] as usize]
        });
    }

    /// `y += P x`: a coarse correction brought to the fine nodes.
    pub fn prolong_add(&self, x: &[Vec3], y: &mut [Vec3], parallel: bool) {
        for_each_entry(y, parallel, |i, yi| {
            let mut s = Vec3::zeros();
            for slot in self.row(i) {
                s += self.blocks[slot] * x[self.cols[slot] as usize];
            }
            *yi += s;
        });
    }

    /// `out = P^T r`.
    pub fn restrict(&self, r: &[Vec3], out: &mut [Vec3], parallel: bool) {
        for_each_entry(out, parallel, |a, o| {
            let mut s = Vec3::zeros();
            for (i, block) in self.column(a) {
                s += block.tr_mul(&r[i]);
            }
            *o = s;
        });
    }
}
