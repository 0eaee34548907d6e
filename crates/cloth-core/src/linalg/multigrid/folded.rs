//! The system matrix with its transient couplings folded into its pattern, as the multigrid
//! preconditioner takes it. Kept apart from the mesh's pattern, the cloth's contacts with
//! itself reached the coarse levels only through the tentative prolongator, while the
//! smoothed one moved two layers pressed together by differently smoothed shapes, which
//! the stiff contacts between them resist: the cycle then did little for the garment's
//! slow motions. Folded in, the smoothed prolongator and the coarse matrices see them as
//! they see the mesh's couplings. (GarmentCode's rand_1_089 in its drape, 23,927
//! particles pressed by about 10,000 contacts: gravity's pull solved to 1e-6 in 1,121
//! iterations kept apart, 338 folded in with the finest level alone aggregated along the
//! mesh; the step's own solve to 1e-3 in 123 and 68. Every level aggregated so, as now,
//! its whole drape took 109 iterations a step against 227 kept apart.)
//!
//! The pattern is made again, in the same storage, only when the couplings join other
//! pairs than at the last fold; within a step's solves only the values change.

use crate::linalg::BlockSparse;
use crate::parallelism::Parallelism;

/// The folded matrix and the scratch its pattern is made in.
#[derive(Debug, Default)]
pub(super) struct Folded {
    matrix: BlockSparse,
    row_ptr: Vec<usize>,
    cols: Vec<u32>,
}

impl Folded {
    /// `a` with its transient couplings as blocks of the union of both patterns, and
    /// whether that pattern differs from the last fold's; on rayon's pool when `par` says so.
    pub fn fold(&mut self, a: &BlockSparse, par: Parallelism) -> (&BlockSparse, bool) {
        self.row_ptr.clear();
        self.cols.clear();
        self.row_ptr.push(0);
        for r in 0..a.n() {
            a.union_row(r, &mut self.cols);
            self.row_ptr.push(self.cols.len());
        }
        let changed = self.matrix.row_starts() != self.row_ptr.as_slice()
            || self.matrix.columns() != self.cols.as_slice();
        if changed {
            self.matrix.set_pattern(&self.row_ptr, &self.cols);
        }
        self.matrix.set_folded(a, par);
        (&self.matrix, changed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{Mat3, Vec3};

    fn chain(n: usize) -> BlockSparse {
        let mut m = BlockSparse::from_pairs(n, (1..n).map(|i| (i - 1, i)));
        for r in 0..n {
            for s in m.row(r) {
                let c = m.col_of(s);
                m.blocks_mut()[s] = if c == r {
                    Mat3::from_diagonal_element(4.0 + r as f64)
                } else {
                    Mat3::from_diagonal_element(-1.0)
                };
            }
        }
        m
    }

    #[test]
    fn the_folded_matrix_is_the_same_operator_and_keeps_its_pattern_while_the_couplings_do() {
        let n = 6;
        let mut a = chain(n);
        let k = Mat3::new(2.0, 0.5, 0.0, 0.5, 3.0, 0.1, 0.0, 0.1, 1.0);
        // A coupling across the chain (0 with 4 and 5), and one along a mesh edge (2, 3).
        a.add_coupling(
            k,
            [
                (0, Mat3::identity()),
                (4, -0.5 * Mat3::identity()),
                (5, -0.5 * Mat3::identity()),
            ],
        );
        a.add_coupling(k, [(2, Mat3::identity()), (3, -Mat3::identity())]);
        a.finish_transient();
        let x: Vec<Vec3> = (0..n)
            .map(|i| Vec3::new(1.0 + i as f64, (i * i) as f64 - 3.0, 0.5 * i as f64))
            .collect();
        let (mut ax, mut fx) = (vec![Vec3::zeros(); n], vec![Vec3::zeros(); n]);
        a.mul(&x, &mut ax, Parallelism::Sequential);

        let mut folded = Folded::default();
        let (f, changed) = folded.fold(&a, Parallelism::Sequential);
        assert!(changed && !f.has_transient());
        // The chain's 16 blocks and the coupling's new pairs (0, 4), (0, 5), (4, 5) both ways
        // ((4, 5) and (2, 3) were in the chain).
        assert_eq!(f.nnz_blocks(), 16 + 4);
        f.mul(&x, &mut fx, Parallelism::Sequential);
        for (p, q) in ax.iter().zip(&fx) {
            assert!((p - q).norm() <= 1e-12 * p.norm().max(1.0), "{p} against {q}");
        }
        let pattern = (f.row_starts().as_ptr(), f.columns().as_ptr());

        // New values on the same pairs: the same pattern, in the same storage.
        a.clear_transient();
        a.add_coupling(
            2.0 * k,
            [
                (0, Mat3::identity()),
                (5, -Mat3::identity()),
                (4, 0.3 * Mat3::identity()),
            ],
        );
        a.add_coupling(k, [(3, Mat3::identity()), (2, -Mat3::identity())]);
        a.finish_transient();
        a.mul(&x, &mut ax, Parallelism::Sequential);
        let (f, changed) = folded.fold(&a, Parallelism::Rayon);
        assert!(!changed);
        assert_eq!(pattern, (f.row_starts().as_ptr(), f.columns().as_ptr()));
        f.mul(&x, &mut fx, Parallelism::Sequential);
        for (p, q) in ax.iter().zip(&fx) {
            assert!((p - q).norm() <= 1e-12 * p.norm().max(1.0), "{p} against {q}");
        }

        // The couplings gone: the chain's pattern again.
        a.clear_transient();
        a.finish_transient();
        let (f, changed) = folded.fold(&a, Parallelism::Sequential);
        assert!(changed);
        assert_eq!(f.nnz_blocks(), 16);
        assert_eq!(f.columns(), a.columns());
    }
}
