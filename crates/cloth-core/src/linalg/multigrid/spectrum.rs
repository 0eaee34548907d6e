//! The spectral radius of a level's block-Jacobi-scaled matrix `D^-1 A`, which sets the
//! smoother's damping: too low an estimate and the smoother, hence the cycle, diverges.
//! Power iteration creeps up on it (10 steps stopped 13% short on the 110 x 110 sheet,
//! 60 steps still 2% short); Lanczos, in the `D` inner product in which `D^-1 A` is
//! symmetric, finds it to a fraction of a percent in as many products.

use super::product_then;
use crate::linalg::{BlockSparse, Filter};
use crate::math::{Mat3, Vec3};
use crate::parallelism::Parallelism;
use nalgebra::SMatrix;

/// Lanczos steps (matrix-vector products) per estimate.
const STEPS: usize = 10;

/// Scratch of the Lanczos recurrence, sized for the finest level and shared by all.
#[derive(Debug, Clone)]
pub(super) struct Spectrum {
    /// The last two Lanczos vectors `q`, their images `D q`, and `A q`.
    q: [Vec<Vec3>; 2],
    dq: [Vec<Vec3>; 2],
    aq: Vec<Vec3>,
}

fn dot(x: &[Vec3], y: &[Vec3]) -> f64 {
    x.iter().zip(y).map(|(a, b)| a.dot(b)).sum()
}

fn scale(x: &mut [Vec3], s: f64) {
    x.iter_mut().for_each(|v| *v *= s);
}

impl Spectrum {
    pub fn new(n: usize) -> Self {
        let zeros = || vec![Vec3::zeros(); n];
        Self {
            q: [zeros(), zeros()],
            dq: [zeros(), zeros()],
            aq: zeros(),
        }
    }

    /// An estimate of the largest eigenvalue of `D^-1 S m S` on the range of the filter
    /// `f` (`D` the filtered block diagonal, `inv_diag` its inverse there), from a fixed
    /// start (so a build is deterministic): the largest Ritz value, which approaches it
    /// from below, plus its residual bound, which puts some eigenvalue within that
    /// distance of it. That lands at or just above the largest (see the tests); it is
    /// not a proven bound. Nothing free gives the smallest positive number.
    pub fn radius(
        &mut self,
        m: &BlockSparse,
        f: Option<&Filter>,
        inv_diag: &[Mat3],
        par: Parallelism,
    ) -> f64 {
        let n = m.n();
        let [q0, q1] = &mut self.q;
        let [dq0, dq1] = &mut self.dq;
        let (mut q, mut q_prev) = (&mut q1[..n], &mut q0[..n]);
        let (mut dq, mut dq_prev) = (&mut dq1[..n], &mut dq0[..n]);
        let aq = &mut self.aq[..n];
        // Start from q = D^-1 r for a pseudo-random r, so that D q = r needs no product.
        for (k, r) in dq.iter_mut().enumerate() {
            let h = |salt: u64| {
                let v = (k as u64 * 3 + salt).wrapping_mul(0x9E37_79B9_7F4A_7C15);
                (v >> 11) as f64 / (1u64 << 53) as f64 - 0.5
            };
            *r = Vec3::new(h(0), h(1), h(2));
        }
        if let Some(f) = f {
            f.project(dq);
        }
        for ((qk, dqk), inv) in q.iter_mut().zip(dq.iter()).zip(inv_diag) {
            *qk = inv * dqk;
        }
        let norm = dot(q, dq).max(0.0).sqrt();
        if norm == 0.0 {
            return f64::MIN_POSITIVE;
        }
        scale(q, 1.0 / norm);
        scale(dq, 1.0 / norm);
        q_prev.fill(Vec3::zeros());
        dq_prev.fill(Vec3::zeros());

        let (mut alpha, mut beta) = ([0.0; STEPS], [0.0; STEPS]);
        let mut steps = 0;
        for j in 0..STEPS {
            product_then(m, f, q, aq, par, |_, v| v);
            alpha[j] = dot(q, aq);
            steps = j + 1;
            // The next vector w = D^-1 A q - alpha q - beta q_prev, and D w, over the
            // previous ones.
            let b = if j > 0 { beta[j - 1] } else { 0.0 };
            for i in 0..n {
                q_prev[i] = inv_diag[i] * aq[i] - alpha[j] * q[i] - b * q_prev[i];
                dq_prev[i] = aq[i] - alpha[j] * dq[i] - b * dq_prev[i];
            }
            beta[j] = dot(q_prev, dq_prev).max(0.0).sqrt();
            // An invariant subspace (the whole space, for a system smaller than the steps):
            // the Ritz values are eigenvalues, and what is left of w is rounding, which
            // would only feed the recurrence noise.
            if beta[j] <= 1e-8 * (alpha[j].abs() + b) {
                beta[j] = 0.0;
                break;
            }
            scale(q_prev, 1.0 / beta[j]);
            scale(dq_prev, 1.0 / beta[j]);
            std::mem::swap(&mut q, &mut q_prev);
            std::mem::swap(&mut dq, &mut dq_prev);
        }
        // The tridiagonal Lanczos matrix; unused rows stay zero, below every Ritz value of
        // a positive definite matrix.
        let mut t = SMatrix::<f64, STEPS, STEPS>::zeros();
        for j in 0..steps {
            t[(j, j)] = alpha[j];
            if j + 1 < steps {
                t[(j, j + 1)] = beta[j];
                t[(j + 1, j)] = beta[j];
            }
        }
        let eigen = t.symmetric_eigen();
        let top = eigen.eigenvalues.imax();
        let residual = beta[steps - 1] * eigen.eigenvectors[(steps - 1, top)].abs();
        (eigen.eigenvalues[top] + residual).max(f64::MIN_POSITIVE)
    }
}

#[cfg(test)]
mod tests {
    use super::super::dense_into;
    use super::*;
    use crate::linalg::{inverse_diagonal, Constraint, ConstraintKind};
    use nalgebra::{DMatrix, Matrix3};

    /// A chain of `n` particles with coupled, unequal diagonal blocks: SPD, and with a
    /// spread of block sizes so that `D^-1 A` differs from `A`.
    fn chain(n: usize) -> BlockSparse {
        let mut a = BlockSparse::from_pairs(n, (1..n).flat_map(|i| [(i - 1, i), (i, i - 1)]));
        for i in 0..n {
            let s = 1.0 + 0.5 * (i as f64).sin();
            let d = a.diag_slot(i);
            a.blocks_mut()[d] = s * Matrix3::new(4.0, 0.5, 0.0, 0.5, 3.0, 0.2, 0.0, 0.2, 2.5);
        }
        for i in 1..n {
            for slot in a.row(i) {
                if a.col_of(slot) == i - 1 {
                    a.blocks_mut()[slot] = -0.4 * Matrix3::new(1.0, 0.2, 0.0, 0.1, 0.8, 0.0, 0.0, 0.0, 0.6);
                }
            }
            for slot in a.row(i - 1) {
                if a.col_of(slot) == i {
                    a.blocks_mut()[slot] = -0.4 * Matrix3::new(1.0, 0.1, 0.0, 0.2, 0.8, 0.0, 0.0, 0.0, 0.6);
                }
            }
        }
        a
    }

    #[test]
    fn lanczos_finds_the_spectral_radius_from_above() {
        let a = chain(300);
        let mut inv_diag = vec![Mat3::zeros(); a.n()];
        inverse_diagonal(&a, None, &mut inv_diag, Parallelism::Sequential).expect("SPD");
        let estimate = Spectrum::new(a.n()).radius(&a, None, &inv_diag, Parallelism::Sequential);
        let rho = exact(&a, &Filter::new(a.n(), 0));
        assert!(
            estimate >= rho * (1.0 - 1e-9) && estimate <= 1.05 * rho,
            "estimate {estimate}, spectral radius {rho}"
        );
    }

    /// The largest eigenvalue of `D^-1 S A S` on the free space of `filter` (all of it
    /// without constraints): with `Q` an orthonormal basis of that space, the largest of
    /// `Q^T A Q x = l Q^T D Q x`.
    fn exact(a: &BlockSparse, filter: &Filter) -> f64 {
        let n = a.n();
        let mut basis = Vec::new();
        for i in 0..n {
            let eigen = filter.free_projection(i).symmetric_eigen();
            for k in 0..3 {
                if eigen.eigenvalues[k] > 0.5 {
                    let mut column = nalgebra::DVector::zeros(3 * n);
                    column
                        .fixed_rows_mut::<3>(3 * i)
                        .copy_from(&eigen.eigenvectors.column(k));
                    basis.push(column);
                }
            }
        }
        let q = DMatrix::from_columns(&basis);
        let mut dense = DMatrix::zeros(3 * n, 3 * n);
        dense_into(a, None, &mut dense);
        let mut diagonal = DMatrix::zeros(3 * n, 3 * n);
        for i in 0..n {
            let block = dense.fixed_view::<3, 3>(3 * i, 3 * i).into_owned();
            diagonal.fixed_view_mut::<3, 3>(3 * i, 3 * i).copy_from(&block);
        }
        let (a_free, d_free) = (q.transpose() * dense * &q, q.transpose() * diagonal * &q);
        let l_inv = d_free
            .cholesky()
            .expect("SPD")
            .l()
            .try_inverse()
            .expect("invertible");
        (&l_inv * a_free * l_inv.transpose())
            .symmetric_eigen()
            .eigenvalues
            .max()
    }

    #[test]
    fn lanczos_respects_the_filter() {
        let a = chain(200);
        let mut filter = Filter::new(a.n(), a.n());
        for particle in (0..a.n()).step_by(3) {
            let kind = match particle % 2 {
                0 => ConstraintKind::Plane {
                    normal: Vec3::new(0.3, (particle as f64).cos(), 1.0).normalize(),
                },
                _ => ConstraintKind::Line {
                    direction: Vec3::new(1.0, 0.2, 0.1).normalize(),
                },
            };
            let constraint = Constraint {
                particle,
                kind,
                velocity: Vec3::zeros(),
            };
            filter.push(&constraint).expect("valid");
        }
        let mut inv_diag = vec![Mat3::zeros(); a.n()];
        inverse_diagonal(&a, Some(&filter), &mut inv_diag, Parallelism::Sequential).expect("SPD");
        let estimate = Spectrum::new(a.n()).radius(&a, Some(&filter), &inv_diag, Parallelism::Sequential);
        let rho = exact(&a, &filter);
        assert!(
            estimate >= rho * (1.0 - 1e-9) && estimate <= 1.05 * rho,
            "estimate {estimate}, spectral radius on the free space {rho}"
        );
    }

    #[test]
    fn lanczos_on_a_small_or_fully_constrained_system() {
        // Fewer dofs than steps: the recurrence spans the whole space and stops, dropping
        // a remainder under 1e-8 of the diagonal, which moves the eigenvalues by no more.
        let a = chain(2);
        let mut inv_diag = vec![Mat3::zeros(); 2];
        inverse_diagonal(&a, None, &mut inv_diag, Parallelism::Sequential).expect("SPD");
        let estimate = Spectrum::new(2).radius(&a, None, &inv_diag, Parallelism::Sequential);
        let rho = exact(&a, &Filter::new(a.n(), 0));
        assert!(
            (estimate - rho).abs() <= 1e-8 * rho,
            "estimate {estimate}, exact {rho}"
        );
        // Nothing free.
        let mut filter = Filter::new(2, 2);
        for particle in 0..2 {
            let fixed = Constraint {
                particle,
                kind: ConstraintKind::Fixed,
                velocity: Vec3::zeros(),
            };
            filter.push(&fixed).expect("valid");
        }
        inverse_diagonal(&a, Some(&filter), &mut inv_diag, Parallelism::Sequential).expect("SPD");
        let estimate = Spectrum::new(2).radius(&a, Some(&filter), &inv_diag, Parallelism::Sequential);
        assert_eq!(estimate, f64::MIN_POSITIVE);
    }
}
