//! Triangulation of a simple polygon by constrained Delaunay refinement (spade).
//!
//! spade's refinement takes one global area limit and splits boundary edges only where
//! they are encroached, so the outline is first split into segments of the target
//! length: the boundary then gets the same resolution as the interior.

use cloth_core::{ClothMesh, MeshError, Vec3};
use nalgebra::Vector2;
use spade::{AngleLimit, ConstrainedDelaunayTriangulation, Point2, RefinementParameters, Triangulation};
use std::collections::HashMap;

/// Why a polygon could not be meshed.
#[derive(Debug, thiserror::Error)]
pub enum MeshingError {
    #[error("polygon outline has {0} vertices; it needs at least 3")]
    TooFewVertices(usize),
    #[error("target edge length {0} m must be positive and finite")]
    BadEdgeLength(f64),
    /// `index` counts the outline's vertices, then the interior points.
    #[error("polygon vertex {index} is not finite or cannot be triangulated: {reason}")]
    BadVertex { index: usize, reason: String },
    #[error("polygon outline crosses itself at edge {edge}")]
    SelfIntersecting { edge: usize },
    #[error(transparent)]
    Mesh(#[from] MeshError),
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
/// triangles of edges about `edge_length` and no angle under 25 degrees. `points` inside
/// it become vertices too (where the mesh must have one: a clamp's edge, a mark). The
/// flat mesh lies in the z = 0 plane at its material coordinates.
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
    let mut cdt = ConstrainedDelaunayTriangulation::<Point2<f64>>::new();
    let mut insert = |p: Vector2<f64>, index: usize| {
        cdt.insert(Point2::new(p.x, p.y))
            .map_err(|e| MeshingError::BadVertex {
                index,
                reason: e.to_string(),
            })
    };
    let mut loop_handles = Vec::new();
    for (k, &a) in outline.iter().enumerate() {
        let b = outline[(k + 1) % outline.len()];
        let pieces = ((b - a).norm() / edge_length).ceil().max(1.0) as usize;
        for j in 0..pieces {
            loop_handles.push((insert(a + (b - a) * (j as f64 / pieces as f64), k)?, k));
        }
    }
    for (k, &p) in points.iter().enumerate() {
        insert(p, outline.len() + k)?;
    }
    for (j, &(h, edge)) in loop_handles.iter().enumerate() {
        let (next, _) = loop_handles[(j + 1) % loop_handles.len()];
        if !cdt.can_add_constraint(h, next) {
            return Err(MeshingError::SelfIntersecting { edge });
        }
        cdt.add_constraint(h, next);
    }
    // An equilateral triangle of the target edge.
    let area = 3f64.sqrt() / 4.0 * edge_length * edge_length;
    let result = cdt.refine(
        RefinementParameters::new()
            .exclude_outer_faces(true)
            .keep_constraint_edges()
            .with_max_allowed_area(area)
            .with_angle_limit(AngleLimit::from_deg(25.0))
            .with_max_additional_vertices(usize::MAX / 4),
    );
    let excluded: std::collections::HashSet<_> = result.excluded_faces.iter().collect();
    let mut index = HashMap::new();
    let (mut uv, mut triangles) = (Vec::new(), Vec::new());
    for face in cdt.inner_faces() {
        if excluded.contains(&face.fix()) {
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
    let positions = uv.iter().map(|p| Vec3::new(p.x, p.y, 0.0)).collect();
    Ok(ClothMesh::new(positions, uv, triangles)?)
}
