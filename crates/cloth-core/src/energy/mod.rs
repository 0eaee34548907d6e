//! Energies with their gradients and Hessians, element by element.
//!
//! Each element fills a [`Local`] with its energy E, gradient dE/dx (the force is its
//! negative) and Hessian d^2E/dx^2 (the Jacobian dF/dx is its negative). The Hessian
//! is either the exact one (checked against finite differences in the tests) or the
//! positive semi-definite form the implicit solver needs, selected by [`HessianMode`].

pub mod particle;
pub mod damping;
mod triangle_rest;
pub mod stretch;
pub mod shear;
pub mod bending;
pub mod attachment;
pub mod repulsion;

pub use triangle_rest::TriangleRest;

use crate::math::{Mat3, Vec3};

/// Which Hessian an element returns.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HessianMode {
    /// The true second derivative (may be indefinite).
    Exact,
    /// A positive semi-definite form for the solver: the exact Hessian with its
    /// indefinite part removed. Equal to `Exact` wherever that is already PSD in the
    /// flat, unstretched rest state.
    Projected,
    /// Energy and gradient only.
    None,
}

/// Energy, gradient and Hessian of one element over its `N` vertices.
#[derive(Debug, Clone, Copy)]
pub struct Local<const N: usize> {
    pub energy: f64,
    pub grad: [Vec3; N],
    pub hess: [[Mat3; N]; N],
}

impl<const N: usize> Default for Local<N> {
    fn default() -> Self {
        Self {
            energy: 0.0,
            grad: [Vec3::zeros(); N],
            hess: [[Mat3::zeros(); N]; N],
        }
    }
}

impl<const N: usize> Local<N> {
    pub fn clear(&mut self) {
        *self = Self::default();
    }

    /// Adds `s * (g g^T)` for a gradient `g` over the element's vertices.
    pub(crate) fn add_outer(&mut self, s: f64, g: &[Vec3; N]) {
        for i in 0..N {
            for j in 0..N {
                self.hess[i][j] += (s * g[i]) * g[j].transpose();
            }
        }
    }

    /// Flattened Hessian as a dense 3N x 3N matrix (tests and diagnostics).
    pub fn hessian_dense(&self) -> nalgebra::DMatrix<f64> {
        let mut m = nalgebra::DMatrix::zeros(3 * N, 3 * N);
        for i in 0..N {
            for j in 0..N {
                m.view_mut((3 * i, 3 * j), (3, 3)).copy_from(&self.hess[i][j]);
            }
        }
        m
    }
}
