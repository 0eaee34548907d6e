//! The inverses of a block-sparse matrix's diagonal blocks: block Jacobi, as the
//! conjugate gradients' preconditioner and as the multigrid's smoother.

use super::row_chunks::for_each_entry;
use super::{BlockSparse, Filter};
use crate::math::Mat3;
use crate::parallelism::Parallelism;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The inverses of the diagonal blocks of `a`, filtered by `filter` if given, or the
/// first block that is not positive definite.
pub(crate) fn inverse_diagonal(
    a: &BlockSparse,
    filter: Option<&Filter>,
    out: &mut [Mat3],
    par: Parallelism,
) -> Result<(), usize> {
    let failed = AtomicUsize::new(usize::MAX);
    for_each_entry(out, par, |r, inv| {
        let d = a.smoother_diagonal(r);
        let d = filter.map_or(d, |f| f.filtered_diagonal(r, &d));
        match spd_inverse(&d) {
            Some(i) => *inv = i,
            None => {
                failed.fetch_min(r, Ordering::Relaxed);
            }
        }
    });
    match failed.into_inner() {
        usize::MAX => Ok(()),
        r => Err(r),
    }
}

/// The inverse of a symmetric 3x3 block by its adjugate, if the block is positive
/// definite (all leading minors positive); several times cheaper than a factorisation,
/// and the blocks (mass plus stiffness) are far from singular.
fn spd_inverse(d: &Mat3) -> Option<Mat3> {
    let (a, b, c) = (d[(0, 0)], d[(0, 1)], d[(0, 2)]);
    let (e, f, i) = (d[(1, 1)], d[(1, 2)], d[(2, 2)]);
    let (c00, c01, c02) = (e * i - f * f, c * f - b * i, b * f - c * e);
    let minor = a * e - b * b;
    let det = a * c00 + b * c01 + c * c02;
    if !(a > 0.0 && minor > 0.0 && det > 0.0) {
        return None;
    }
    let (c11, c12, c22) = (a * i - c * c, b * c - a * f, minor);
    Some(Mat3::new(c00, c01, c02, c01, c11, c12, c02, c12, c22) / det)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Vec3;

    #[test]
    fn spd_inverse_inverts_definite_blocks_and_refuses_the_rest() {
        let blocks = [
            Mat3::new(4.0, 1.0, 0.5, 1.0, 3.0, -0.2, 0.5, -0.2, 2.0),
            // Mass plus a stiff stretch along one direction, as in the cloth's rows.
            Mat3::from_diagonal_element(1e-5)
                + 2e-1 * Vec3::new(0.6, 0.8, 0.0) * Vec3::new(0.6, 0.8, 0.0).transpose(),
        ];
        for d in blocks {
            let inv = spd_inverse(&d).expect("positive definite");
            let reference = d.cholesky().expect("positive definite").inverse();
            let error = (inv - reference).norm() / reference.norm();
            // Both are backward stable: they agree to rounding times the condition number.
            let eigenvalues = d.symmetric_eigenvalues();
            let condition = eigenvalues.max() / eigenvalues.min();
            assert!(error < 1e-15 * condition, "{error:e} at condition {condition:e}");
        }
        for d in [
            Mat3::from_diagonal(&Vec3::new(1.0, 1.0, 0.0)),
            Mat3::from_diagonal(&Vec3::new(1.0, 1.0, -1.0)),
            Mat3::from_diagonal(&Vec3::new(1.0, -1.0, -1.0)),
            Mat3::from_diagonal(&Vec3::new(-1.0, 1.0, 1.0)),
            Mat3::new(1.0, 2.0, 0.0, 2.0, 1.0, 0.0, 0.0, 0.0, 1.0),
        ] {
            assert_eq!(spd_inverse(&d), None, "{d}");
        }
    }
}
