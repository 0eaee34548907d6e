//! The coarse matrix `A_c = P^T A P`, through `AP = A P` row by row. The patterns and the
//! storage slot of every product term are found once; a rebuild only multiplies and adds.

use super::prolongator::Prolongator;
use crate::linalg::row_chunks::for_each_row;
use crate::linalg::BlockSparse;
use crate::math::Mat3;
use crate::parallelism::Parallelism;

#[derive(Debug, Clone, Default)]
pub(super) struct Galerkin {
    /// `A P` by fine rows: row starts, columns, values.
    ap_ptr: Vec<usize>,
    ap_cols: Vec<u32>,
    ap: Vec<Mat3>,
    /// For fine row `i`, in the order `for s in A.row(i), for q in P.row(col(s))`: the
    /// slot of `AP` the term `A[s] P[q]` adds to.
    ap_terms_ptr: Vec<usize>,
    ap_terms: Vec<u32>,
    /// For coarse row `a`, in the order `for (i, p) in P.column(a), for t in AP.row(i)`:
    /// the slot of `A_c` the term `P[p]^T AP[t]` adds to.
    coarse_terms_ptr: Vec<usize>,
    coarse_terms: Vec<u32>,
    /// Scratch of the plan: one row's columns, and the coarse matrix's pattern.
    row: Vec<u32>,
    coarse_ptr: Vec<usize>,
    coarse_cols: Vec<u32>,
}

impl Galerkin {
    /// Plans the product for `a` and `p` and sets the coarse matrix's pattern (values
    /// zero), in the storage of both, which they allocate only to grow.
    pub fn plan(&mut self, a: &BlockSparse, p: &Prolongator, coarse: &mut BlockSparse) {
        let n = a.n();
        let row = &mut self.row;
        self.ap_ptr.clear();
        self.ap_ptr.push(0);
        self.ap_cols.clear();
        self.ap_terms_ptr.clear();
        self.ap_terms_ptr.push(0);
        self.ap_terms.clear();
        for i in 0..n {
            row.clear();
            for s in a.row(i) {
                row.extend(p.row(a.col_of(s)).map(|q| p.col_of(q) as u32));
            }
            row.sort_unstable();
            row.dedup();
            let base = self.ap_cols.len();
            for s in a.row(i) {
                for q in p.row(a.col_of(s)) {
                    let k = row.binary_search(&(p.col_of(q) as u32)).expect("in the row");
                    self.ap_terms.push((base + k) as u32);
                }
            }
            self.ap_terms_ptr.push(self.ap_terms.len());
            self.ap_cols.extend_from_slice(row);
            self.ap_ptr.push(self.ap_cols.len());
        }
        self.ap.clear();
        self.ap.resize(self.ap_cols.len(), Mat3::zeros());

        // Coarse row `a` holds the columns of `AP`'s rows at the fine nodes `P` takes `a`
        // to: symmetric, as `A`'s pattern is, and with its diagonal, as every aggregate
        // holds a node `i` and `AP` has `(i, a)` through `A`'s diagonal and `P`'s `(i, a)`.
        let (ap_ptr, ap_cols) = (&self.ap_ptr, &self.ap_cols);
        self.coarse_ptr.clear();
        self.coarse_ptr.push(0);
        self.coarse_cols.clear();
        for a_c in 0..p.coarse() {
            row.clear();
            for (i, _) in p.column(a_c) {
                row.extend_from_slice(&ap_cols[ap_ptr[i]..ap_ptr[i + 1]]);
            }
            row.sort_unstable();
            row.dedup();
            self.coarse_cols.extend_from_slice(row);
            self.coarse_ptr.push(self.coarse_cols.len());
        }
        coarse.set_pattern(&self.coarse_ptr, &self.coarse_cols);

        self.coarse_terms_ptr.clear();
        self.coarse_terms_ptr.push(0);
        self.coarse_terms.clear();
        for a_c in 0..p.coarse() {
            for (i, _) in p.column(a_c) {
                for &b_c in &ap_cols[ap_ptr[i]..ap_ptr[i + 1]] {
                    let slot = coarse.slot(a_c, b_c as usize).expect("in the pattern");
                    self.coarse_terms.push(slot as u32);
                }
            }
            self.coarse_terms_ptr.push(self.coarse_terms.len());
        }
    }

    /// `coarse = P^T a P`, symmetrised against rounding.
    pub fn multiply(&mut self, a: &BlockSparse, p: &Prolongator, coarse: &mut BlockSparse, par: Parallelism) {
        let (ap_ptr, terms_ptr, terms) = (&self.ap_ptr, &self.ap_terms_ptr, &self.ap_terms);
        for_each_row(ap_ptr, &mut self.ap, par, |i, first, row| {
            row.fill(Mat3::zeros());
            let mut k = terms_ptr[i];
            for s in a.row(i) {
                let block = &a.blocks()[s];
                for q in p.row(a.col_of(s)) {
                    row[terms[k] as usize - first] += block * p.blocks()[q];
                    k += 1;
                }
            }
        });

        let (ap, ap_ptr) = (&self.ap, &self.ap_ptr);
        let (terms_ptr, terms) = (&self.coarse_terms_ptr, &self.coarse_terms);
        coarse.fill_rows(par, |a_c, first, row| {
            row.fill(Mat3::zeros());
            let mut k = terms_ptr[a_c];
            for (i, block) in p.column(a_c) {
                let pt = block.transpose();
                for t in ap_ptr[i]..ap_ptr[i + 1] {
                    row[terms[k] as usize - first] += pt * ap[t];
                    k += 1;
                }
            }
        });
        coarse.symmetrize();
    }
}
