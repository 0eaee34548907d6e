//! Triangulation of flat regions by constrained Delaunay refinement (spade).
//!
//! spade's refinement takes one global area limit and splits boundary edges only where
//! they are encroached, so boundaries come in already split at the target length and are
//! kept as they are: the boundary then has the interior's resolution, and a seam's
//! vertices are exactly the points the seam was resampled at.

use cloth_core::{math::Vec3, ClothMesh, MeshError};
use nalgebra::Vector2;
use spade::{AngleLimit, ConstrainedDelaunayTriangulation, Point2, RefinementParameters, Triangulation};
use std::collections::HashMap;

/// The smallest angle refinement leaves in a triangle.
pub const ANGLE_LIMIT_DEGREES: f64 = 25.0;

/// Why a region could not be meshed.
#[derive(Debug, thiserror::Error)]
pub enum MeshingError {
    #[error("polygon outline has {0} vertices; it needs at least 3")]
    TooFewVertices(usize),
    #[error("target edge length {0} m must be positive and finite")]
    BadEdgeLength(f64),
    /// `index` counts the loops' points in order, then the interior points.
    #[error("vertex {index} is not finite or cannot be triangulated: {reason}")]
    BadVertex { index: usize, reason: String },
    /// `edge` counts the segments of all loops in order.
    #[error("boundary crosses itself at segment {edge}")]
    SelfIntersecting { edge: usize },
    #[error(transparent)]
    Mesh(#[from] MeshError),
}

/// A flat mesh of a region bounded by closed loops.
#[derive(Debug, Clone)]
pub struct RegionMesh {
    pub uv: Vec<Vector2<f64>>,
    pub triangles: Vec<[usize; 3]>,
    /// The mesh vertex of each loop point, loop by loop.
    pub loop_vertices: Vec<Vec<usize>>,
}

/// A regular polygon of `segments` vertices on the circle of `radius` about `centre`.
pub fn circle(centre: Vector2<f64>, radius: f64, segments: usize) -> Vec<Vector2<f64>> {
    (0..segments)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / segments as f64;
            centre + radius * Vector2::new(a.cos(), a.sin())
        })
        .collect()
}

/// Meshes the inside of the simple polygon `outline` (material coordinates, m) with
/// triangles of edges about `edge_length`. `points` inside it become vertices too (where
/// the mesh must have one: a clamp's edge, a mark). The flat mesh lies in the z = 0 plane
/// at its material coordinates.
pub fn triangulate_polygon(
    outline: &[Vector2<f64>],
    points: &[Vector2<f64>],
    edge_length: f64,
) -> Result<ClothMesh, MeshingError> {
    if outline.len() < 3 {
        return Err(MeshingError::TooFewVertices(outline.len()));
    }
    if !(edge_length > 0.0 && edge_length.is_finite()) {
        return Err(MeshingError::BadEdgeLength(edge_length));
    }
    let mut boundary = Vec::new();
    for (k, &a) in outline.iter().enumerate() {
        let b = outline[(k + 1) % outline.len()];
        let pieces = ((b - a).norm() / edge_length).ceil().max(1.0) as usize;
        boundary.extend((0..pieces).map(|j| a + (b - a) * (j as f64 / pieces as f64)));
    }
    let region = mesh_region(&[boundary], points, edge_length)?;
    let positions = region.uv.iter().map(|p| Vec3::new(p.x, p.y, 0.0)).collect();
    Ok(ClothMesh::new(positions, region.uv, region.triangles)?)
}

/// Meshes the region inside `loops[0]` and outside the other loops (holes), each loop a
/// closed polygon already split at about `edge_length` (its points are kept as they are),
/// with no angle under [`ANGLE_LIMIT_DEGREES`] and triangles of about the target size.
pub fn mesh_region(
    loops: &[Vec<Vector2<f64>>],
    points: &[Vector2<f64>],
    edge_length: f64,
) -> Result<RegionMesh, MeshingError> {
    if !(edge_length > 0.0 && edge_length.is_finite()) {
        return Err(MeshingError::BadEdgeLength(edge_length));
    }
    if let Some(l) = loops.iter().find(|l| l.len() < 3) {
        return Err(MeshingError::TooFewVertices(l.len()));
    }
    let mut cdt = ConstrainedDelaunayTriangulation::<Point2<f64>>::new();
    let mut count = 0;
    let mut insert = |p: Vector2<f64>| {
        let index = count;
        count += 1;
        cdt.insert(Point2::new(p.x, p.y))
            .map_err(|e| MeshingError::BadVertex {
                index,
                reason: e.to_string(),
            })
    };
    let mut handles = Vec::with_capacity(loops.len());
    for (k, l) in loops.iter().enumerate() {
        let bowed = bow_straight_runs(l, k == 0);
        handles.push(bowed.iter().map(|&p| insert(p)).collect::<Result<Vec<_>, _>>()?);
    }
    for &p in points {
        insert(p)?;
    }
    let mut segment = 0;
    for h in &handles {
        for j in 0..h.len() {
            let (a, b) = (h[j], h[(j + 1) % h.len()]);
            // Two loop points that landed on one vertex, or a segment through another
            // constraint, are a boundary touching itself.
            if a == b || !cdt.can_add_constraint(a, b) {
                return Err(MeshingError::SelfIntersecting { edge: segment });
            }
            cdt.add_constraint(a, b);
            segment += 1;
        }
    }
    // An equilateral triangle of the target edge.
    let area = 3f64.sqrt() / 4.0 * edge_length * edge_length;
    cdt.refine(
        RefinementParameters::new()
            .exclude_outer_faces(true)
            .keep_constraint_edges()
            .with_max_allowed_area(area)
            .with_angle_limit(AngleLimit::from_deg(ANGLE_LIMIT_DEGREES))
            .with_max_additional_vertices(usize::MAX / 4),
    );
    // Which faces are inside is decided here, by the loops themselves (even-odd), so holes
    // are cut whatever the refinement counted as outer.
    let mut index = HashMap::new();
    let (mut uv, mut triangles) = (Vec::new(), Vec::new());
    for face in cdt.inner_faces() {
        let corners = face.vertices().map(|v| v.position());
        let centroid = Vector2::new(
            (corners[0].x + corners[1].x + corners[2].x) / 3.0,
            (corners[0].y + corners[1].y + corners[2].y) / 3.0,
        );
        let crossings = loops.iter().filter(|l| encloses(l, centroid)).count();
        if crossings % 2 == 0 {
            continue;
        }
        let tri = face.vertices().map(|v| {
            *index.entry(v.fix()).or_insert_with(|| {
                let p = v.position();
                uv.push(Vector2::new(p.x, p.y));
                uv.len() - 1
            })
        });
        triangles.push(tri);
    }
    let mut loop_vertices = Vec::with_capacity(handles.len());
    for (l, h) in handles.iter().enumerate() {
        let ids = h
            .iter()
            .map(|v| index.get(v).copied())
            .collect::<Option<Vec<usize>>>();
        // A boundary point no kept triangle uses: the loop lies outside the region.
        let ids = ids.ok_or(MeshingError::SelfIntersecting {
            edge: handles[..l].iter().map(Vec::len).sum(),
        })?;
        loop_vertices.push(ids);
    }
    Ok(RegionMesh {
        uv,
        triangles,
        loop_vertices,
    })
}

/// Points along a straight boundary are collinear only up to rounding, and where rounding
/// makes the boundary dent inward the triangulation puts flat slivers between the dent
/// and its chord. So each straight run is bowed out of the region by a millionth of its
/// length at the middle (a parabola: a fraction of a micrometre on a garment), which
/// rounding cannot undo. `outer` says the region is inside the loop (else outside it).
fn bow_straight_runs(points: &[Vector2<f64>], outer: bool) -> Vec<Vector2<f64>> {
    let n = points.len();
    let at = |k: usize| points[k % n];
    let straight = |k: usize| {
        let (a, b) = (at(k + n - 1), at(k));
        let (u, v) = (b - a, at(k + 1) - b);
        u.perp(&v).abs() <= 1e-9 * u.norm() * v.norm() && u.dot(&v) > 0.0
    };
    let area: f64 = (0..n).map(|k| at(k).perp(&at(k + 1))).sum();
    // Outward of the region is right of travel for a counter-clockwise outer loop.
    let side = if (area > 0.0) == outer { 1.0 } else { -1.0 };
    let mut out = points.to_vec();
    let Some(first_corner) = (0..n).find(|&k| !straight(k)) else {
        return out;
    };
    let mut k = first_corner;
    for _ in 0..n {
        let next = (1..=n)
            .map(|j| k + j)
            .find(|&j| !straight(j % n))
            .unwrap_or(k + n);
        if next > k + 1 {
            let (a, b) = (at(k), at(next));
            let chord = b - a;
            let len = chord.norm();
            let normal = Vector2::new(chord.y, -chord.x) / len * side;
            for j in k + 1..next {
                let t = (at(j) - a).dot(&chord) / (len * len);
                out[j % n] = at(j) + normal * (1e-6 * len * 4.0 * t * (1.0 - t));
            }
        }
        k = next;
        if k >= first_corner + n {
            break;
        }
    }
    out
}

/// Even-odd point-in-polygon.
pub fn encloses(polygon: &[Vector2<f64>], p: Vector2<f64>) -> bool {
    let n = polygon.len();
    let mut inside = false;
    for i in 0..n {
        let (a, b) = (polygon[i], polygon[(i + 1) % n]);
        if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x) {
            inside = !inside;
        }
    }
    inside
}
