//! The constant map from a triangle's vertex positions to its deformation gradient.

use crate::math::Vec3;
use nalgebra::Vector2;

/// For a triangle with rest material coordinates `uv`, the deformation gradient
/// `F = [w_u w_v]` is linear in the positions: `w_u = sum a_i x_i`, `w_v = sum b_i x_i`
/// (Baraff & Witkin 1998). `|w_u| - 1` is the warp strain, `|w_v| - 1` the weft strain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TriangleRest {
    pub a: [f64; 3],
    pub b: [f64; 3],
    /// Rest area in material space, m^2.
    pub area: f64,
}

impl TriangleRest {
    /// `None` for a triangle with zero material area.
    pub fn new(uv: [Vector2<f64>; 3]) -> Option<Self> {
        let (du1, dv1) = (uv[1].x - uv[0].x, uv[1].y - uv[0].y);
        let (du2, dv2) = (uv[2].x - uv[0].x, uv[2].y - uv[0].y);
        let det = du1 * dv2 - du2 * dv1;
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let (a1, a2) = (dv2 / det, -dv1 / det);
        let (b1, b2) = (-du2 / det, du1 / det);
        Some(Self {
            a: [-(a1 + a2), a1, a2],
            b: [-(b1 + b2), b1, b2],
            area: 0.5 * det.abs(),
        })
    }

    /// The two columns of the deformation gradient at positions `x`.
    #[inline]
    pub fn deformation(&self, x: &[Vec3; 3]) -> (Vec3, Vec3) {
        let wu = x[0] * self.a[0] + x[1] * self.a[1] + x[2] * self.a[2];
        let wv = x[0] * self.b[0] + x[1] * self.b[1] + x[2] * self.b[2];
        (wu, wv)
    }
}
