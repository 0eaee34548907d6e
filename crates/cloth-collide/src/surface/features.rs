//! Sharp edges and corners: where a smooth-surface contact normal would be wrong.

use cloth_core::math::Vec3;

use super::edges::{edge_groups, sorted_sides};
use super::TriSurface;

/// A sharp edge (`a != b`) or corner vertex (`a == b`) of a surface, by vertex index, with an
/// outward unit pseudo-normal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SharpFeature {
    pub a: u32,
    pub b: u32,
    pub normal: Vec3,
}

impl TriSurface {
    /// The edges where the surface folds by more than `angle` (radians, between the normals
    /// of the two faces), with `a < b` and the normalised sum of the two face normals; then
    /// the corners: vertices where one sharp edge ends or three or more meet, with the
    /// normalised angle-weighted sum of the normals of their faces. Edges come first, each
    /// list in vertex order.
    pub fn sharp_features(&self, angle: f64) -> Vec<SharpFeature> {
        let normals: Vec<Vec3> = self
            .corners()
            .map(|[p, q, r]| {
                (q - p)
                    .cross(&(r - p))
                    .try_normalize(0.0)
                    .unwrap_or_else(Vec3::zeros)
            })
            .collect();
        let sides = sorted_sides(&self.triangles);
        let mut sharp_count = vec![0usize; self.vertices.len()];
        let mut features = Vec::new();
        for group in edge_groups(&sides) {
            // A valid surface has exactly two sides per edge.
            let [s, t] = group else { continue };
            let (n, m) = (normals[s.triangle as usize], normals[t.triangle as usize]);
            // Written so that a NaN `angle` marks nothing sharp.
            let sharp = n.cross(&m).norm().atan2(n.dot(&m)) > angle;
            if !sharp {
                continue;
            }
            sharp_count[s.lo as usize] += 1;
            sharp_count[s.hi as usize] += 1;
            let normal = (n + m)
                .try_normalize(1e-12)
                .unwrap_or_else(|| self.fin_normal(s.lo, s.hi, [s.triangle, t.triangle]));
            features.push(SharpFeature {
                a: s.lo,
                b: s.hi,
                normal,
            });
        }
        let mut weighted = vec![Vec3::zeros(); self.vertices.len()];
        for (tri, n) in self.triangles.iter().zip(&normals) {
            for k in 0..3 {
                let p = self.vertices[tri[k] as usize];
                let e = self.vertices[tri[(k + 1) % 3] as usize] - p;
                let f = self.vertices[tri[(k + 2) % 3] as usize] - p;
                weighted[tri[k] as usize] += e.angle(&f) * n;
            }
        }
        for (v, &count) in sharp_count.iter().enumerate() {
            if count == 1 || count >= 3 {
                let normal = weighted[v]
                    .try_normalize(1e-12)
                    .unwrap_or_else(|| self.tip_normal(v));
                features.push(SharpFeature {
                    a: v as u32,
                    b: v as u32,
                    normal,
                });
            }
        }
        features
    }

    /// For an edge folded flat onto itself (the face normals cancel): the direction away
    /// from the two opposite vertices, across the edge.
    fn fin_normal(&self, a: u32, b: u32, faces: [u32; 2]) -> Vec3 {
        let (p, q) = (self.vertices[a as usize], self.vertices[b as usize]);
        let axis = (q - p).normalize();
        let mut away = Vec3::zeros();
        for t in faces {
            let tri = self.triangles[t as usize];
            if let Some(&o) = tri.iter().find(|&&i| i != a && i != b) {
                let d = p - self.vertices[o as usize];
                away += d - d.dot(&axis) * axis;
            }
        }
        away.try_normalize(0.0).unwrap_or_else(Vec3::zeros)
    }

    /// For a corner whose face normals cancel: the direction from its neighbours to it.
    fn tip_normal(&self, v: usize) -> Vec3 {
        let mut away = Vec3::zeros();
        for tri in self.triangles.iter().filter(|tri| tri.contains(&(v as u32))) {
            for &i in tri {
                away += self.vertices[v] - self.vertices[i as usize];
            }
        }
        away.try_normalize(0.0).unwrap_or_else(Vec3::zeros)
    }
}
