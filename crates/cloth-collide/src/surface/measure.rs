//! Measures of a surface and the operations that keep it valid: rigid motion and union.

use cloth_core::math::Vec3;
use nalgebra::{Isometry3, Point3};

use super::TriSurface;

/// Componentwise bounds (zeros for no points, which only an unchecked mesh can have).
pub(super) fn bounds(points: &[Vec3]) -> (Vec3, Vec3) {
    let Some(&first) = points.first() else {
        return (Vec3::zeros(), Vec3::zeros());
    };
    points
        .iter()
        .fold((first, first), |(lo, hi), p| (lo.inf(p), hi.sup(p)))
}

impl TriSurface {
    /// Enclosed volume, m^3 (positive: the surface faces outward).
    pub fn volume(&self) -> f64 {
        // Measuring from the box centre rather than the origin keeps a body far from the
        // origin from losing digits.
        let (lo, hi) = self.bounding_box();
        let centre = 0.5 * (lo + hi);
        self.corners()
            .map(|[p, q, r]| (p - centre).dot(&(q - centre).cross(&(r - centre))))
            .sum::<f64>()
            / 6.0
    }

    /// Surface area, m^2.
    pub fn area(&self) -> f64 {
        self.corners()
            .map(|[p, q, r]| 0.5 * (q - p).cross(&(r - p)).norm())
            .sum()
    }

    /// Lower and upper corners of the axis-aligned bounding box.
    pub fn bounding_box(&self) -> (Vec3, Vec3) {
        bounds(&self.vertices)
    }

    /// The surface moved rigidly by `pose` (a rotation cannot turn it inside out).
    pub fn transformed(&self, pose: &Isometry3<f64>) -> TriSurface {
        TriSurface {
            vertices: self
                .vertices
                .iter()
                .map(|p| pose.transform_point(&Point3::from(*p)).coords)
                .collect(),
            triangles: self.triangles.clone(),
            buried: self.buried.clone(),
            defects: self.defects.clone(),
        }
    }

    /// The union of surfaces, e.g. a table made of five boxes. Vertices are not welded, so
    /// parts stay separate components with their own defects; the parts are expected not
    /// to overlap.
    ///
    /// # Panics
    /// If `parts` is empty (a surface always has triangles) or the union has more than
    /// `u32::MAX` vertices.
    pub fn merged(parts: &[TriSurface]) -> TriSurface {
        assert!(!parts.is_empty(), "TriSurface::merged needs at least one part");
        let total: usize = parts.iter().map(|s| s.vertices.len()).sum();
        assert!(
            total <= u32::MAX as usize,
            "merged surface has {total} vertices, over u32 indices"
        );
        let (mut vertices, mut triangles) = (Vec::with_capacity(total), Vec::new());
        let (mut buried, mut defects) = (Vec::new(), Vec::new());
        for part in parts {
            let offset = vertices.len() as u32;
            vertices.extend_from_slice(&part.vertices);
            triangles.extend(part.triangles.iter().map(|tri| tri.map(|i| i + offset)));
            buried.extend((0..part.triangles.len()).map(|t| part.is_buried(t)));
            defects.extend_from_slice(&part.defects);
        }
        TriSurface::assemble(vertices, triangles, buried, defects)
    }

    /// The three corner positions of each triangle.
    pub(super) fn corners(&self) -> impl Iterator<Item = [Vec3; 3]> + '_ {
        self.triangles
            .iter()
            .map(|tri| tri.map(|i| self.vertices[i as usize]))
    }
}
