//! The coarse matrix `A_c = P^T A P`, through `AP = A P` row by row. The patterns and the
//! storage slot of every product term are found once; a rebuild only multiplies and adds.

use super::prolongator::Prolongator;
use crate::linalg::row_chunks::for_each_row;
use crate::linalg::BlockSparse;
use crate::Mat3;

#[derive(Debug, Clone)]
pub(super) struct Galerkin {
    /// `A P` by fine rows.
    ap_ptr: Vec<usize>,
    ap: Vec<Mat3>,
    /// For fine row `i`, in the order `for s in A.row(i), for q in P.row(col(s))`: the
    /// slot of `AP` the term `A[s] P[q]` adds to.
    ap_terms_ptr: Vec<usize>,
    ap_terms: Vec<u32>,
    /// For coarse row `a`, in the order `for (i, p) in P.column(a), for t in AP.row(i)`:
    /// the slot of `A_c` the term `P[p]^T AP[t]` adds to.
    coarse_terms_ptr: Vec<usize>,
    coarse_terms: Vec<u32>,
}

impl Galerkin {
    /// The product's plan and the coarse matrix's pattern (values zero).
    pub fn plan(a: &BlockSparse, p: &Prolongator) -> (Self, BlockSparse) {
        let n = a.n();
        let mut ap_ptr = vec![0usize];
        let mut ap_cols: Vec<u32> = Vec::new();
        let mut ap_terms_ptr = vec![0usize];
        let mut ap_terms = Vec::new();
        let mut row: Vec<u32> = Vec::new();
        for i in 0..n {
            row.clear();
            for s in a.row(i) {
                row.extend(p.row(a.col_of(s)).map(|q| p.col_of(q) as u32));
            }
            row.sort_unstable();
            row.dedup();
            let base = ap_cols.len();
            for s in a.row(i) {
                for q in p.row(a.col_of(s)) {
                    let k = row.binary_search(&(p.col_of(q) as u32)).expect("in the row");
                    ap_terms.push((base + k) as u32);
                }
            }
            ap_terms_ptr.push(ap_terms.len());
            ap_cols.extend_from_slice(&row);
            ap_ptr.push(ap_cols.len());
        }

        let nc = p.coarse();
        let mut pairs = Vec::new();
        for i in 0..n {
            for q in p.row(i) {
                let a_c = p.col_of(q);
                for t in ap_ptr[i]..ap_ptr[i + 1] {
                    let b_c = ap_cols[t] as usize;
                    if a_c <= b_c {
                        pairs.push((a_c, b_c));
                    }
                }
            }
        }
        pairs.sort_unstable();
        pairs.dedup();
        let coarse = BlockSparse::from_pairs(nc, pairs);
        let mut coarse_terms_ptr = vec![0usize];
        let mut coarse_terms = Vec::new();
        for a_c in 0..nc {
            for (i, _) in p.column(a_c) {
                for t in ap_ptr[i]..ap_ptr[i + 1] {
                    let slot = coarse.slot(a_c, ap_cols[t] as usize).expect("in the pattern");
                    coarse_terms.push(slot as u32);
                }
            }
            coarse_terms_ptr.push(coarse_terms.len());
        }
        (
            Self {
                ap: vec![Mat3::zeros(); ap_cols.len()],
                ap_ptr,
                ap_terms_ptr,
                ap_terms,
                coarse_terms_ptr,
                coarse_terms,
            },
            coarse,
        )
    }

    /// `coarse = P^T a P`, symmetrised against rounding.
    pub fn multiply(&mut self, a: &BlockSparse, p: &Prolongator, coarse: &mut BlockSparse, parallel: bool) {
        let (ap_ptr, terms_ptr, terms) = (&self.ap_ptr, &self.ap_terms_ptr, &self.ap_terms);
        for_each_row(ap_ptr, &mut self.ap, parallel, |i, first, row| {
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
        coarse.fill_rows(parallel, |a_c, first, row| {
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
