//! The tentative prolongator of smoothed aggregation: on each aggregate, the level's
//! near-null space made orthonormal. On the finest level that space is the translations,
//! cut down to the directions each node's constraints leave free; its coarse image is the
//! next level's.
//!
//! Rotations, which Tamstorf et al. add for cloth, did not lower the iteration count of
//! our scenes (24 against 27 per step of the 110 x 110 hanging sheet, before the strength
//! threshold of the aggregation) and cost twice the coarse work, so the coarse levels keep
//! one node of three unknowns per aggregate.

use super::aggregation::Aggregates;
use crate::math::Mat3;

/// Relative size under which a direction of an aggregate's Gram matrix is empty: every
/// node of the aggregate has it constrained.
const EMPTY_DIRECTION: f64 = 1e-10;

#[derive(Debug, Clone, Default)]
pub(super) struct Tentative {
    /// `T_i = B_i G_a^-1/2` for each fine node `i` of aggregate `a`.
    pub blocks: Vec<Mat3>,
    /// `G_a^1/2`: the near-null space on the coarse level.
    pub coarse_basis: Vec<Mat3>,
    /// The directions no node of the aggregate can move in; the coarse matrix gets the
    /// identity there so it stays definite.
    pub empty: Vec<Mat3>,
    inv_root: Vec<Mat3>,
}

impl Tentative {
    /// From the near-null space `basis` (one 3x3 block per node: on the finest level its
    /// free translations, below, its rows of the level above's `G^1/2`).
    pub fn build(&mut self, basis: &[Mat3], aggregates: &Aggregates) {
        let count = aggregates.count;
        // The Gram matrices, in the slots of their inverse roots.
        self.inv_root.clear();
        self.inv_root.resize(count, Mat3::zeros());
        for (b, &a) in basis.iter().zip(&aggregates.of_node) {
            self.inv_root[a as usize] += b.tr_mul(b);
        }
        self.coarse_basis.resize(count, Mat3::zeros());
        self.empty.resize(count, Mat3::zeros());
        for a in 0..count {
            let eig = self.inv_root[a].symmetric_eigen();
            let largest = eig.eigenvalues.max();
            let (mut root, mut inv_root, mut empty) = (Mat3::zeros(), Mat3::zeros(), Mat3::zeros());
            for k in 0..3 {
                let e = eig.eigenvectors.column(k);
                let outer = e * e.transpose();
                let lambda = eig.eigenvalues[k];
                if largest > 0.0 && lambda > EMPTY_DIRECTION * largest {
                    root += lambda.sqrt() * outer;
                    inv_root += outer / lambda.sqrt();
                } else {
                    empty += outer;
                }
            }
            self.coarse_basis[a] = root;
            self.inv_root[a] = inv_root;
            self.empty[a] = empty;
        }
        self.blocks.clear();
        self.blocks.extend(
            basis
                .iter()
                .zip(&aggregates.of_node)
                .map(|(b, &a)| b * self.inv_root[a as usize]),
        );
    }
}
