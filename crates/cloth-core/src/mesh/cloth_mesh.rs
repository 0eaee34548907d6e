//! The validated cloth mesh.

use super::grid_shape::GridShape;
use super::topology::{edges_and_hinges, Hinge};

use super::error::MeshError;
use crate::math::Vec3;
use nalgebra::Vector2;

/// A triangle mesh whose vertices carry 3D positions and 2D material coordinates
/// `(u, v)` in metres (u along the warp, v along the weft). The material
/// coordinates define the rest (flat) state.
///
/// A garment's mesh is flat piecewise: a vertex welded along a seam belongs to two
/// panels and has a material position in each. So the rest state is kept per triangle
/// corner ([`corner_uv`](Self::corner_uv)); a mesh made from per-vertex coordinates has
/// corners that agree with them.
#[derive(Debug, Clone)]
pub struct ClothMesh {
    positions: Vec<Vec3>,
    uv: Vec<Vector2<f64>>,
    corner_uv: Vec<[Vector2<f64>; 3]>,
    triangles: Vec<[usize; 3]>,
    edges: Vec<[usize; 2]>,
    hinges: Vec<Hinge>,
    grid: Option<GridShape>,
}

impl ClothMesh {
    /// Builds and validates a mesh. Errors name the offending triangle, edge or vertex.
    pub fn new(
        positions: Vec<Vec3>,
        uv: Vec<Vector2<f64>>,
        triangles: Vec<[usize; 3]>,
    ) -> Result<Self, MeshError> {
        if positions.len() != uv.len() {
            return Err(MeshError::LengthMismatch {
                positions: positions.len(),
                uvs: uv.len(),
            });
        }
        Self::check_indices(positions.len(), &triangles)?;
        let corner_uv = triangles.iter().map(|t| t.map(|i| uv[i])).collect();
        Self::build(positions, uv, corner_uv, triangles)
    }

    /// Builds and validates a mesh whose material coordinates are given per triangle
    /// corner: a garment's panels sewn together, where a seam vertex has a material
    /// position in each panel. [`uv`](Self::uv) then reports, for each vertex, the
    /// corner of the first triangle that uses it.
    pub fn with_corner_uv(
        positions: Vec<Vec3>,
        triangles: Vec<[usize; 3]>,
        corner_uv: Vec<[Vector2<f64>; 3]>,
    ) -> Result<Self, MeshError> {
        if corner_uv.len() != triangles.len() {
            return Err(MeshError::LengthMismatch {
                positions: triangles.len(),
                uvs: corner_uv.len(),
            });
        }
        Self::check_indices(positions.len(), &triangles)?;
        let mut uv = vec![Vector2::new(f64::NAN, f64::NAN); positions.len()];
        let mut seen = vec![false; positions.len()];
        for (tri, corners) in triangles.iter().zip(&corner_uv) {
            for (&i, c) in tri.iter().zip(corners) {
                if !std::mem::replace(&mut seen[i], true) {
                    uv[i] = *c;
                }
            }
        }
        // An unused vertex keeps a finite placeholder so the unused-vertex error, not a
        // non-finite one, names it.
        for (u, s) in uv.iter_mut().zip(&seen) {
            if !s {
                *u = Vector2::zeros();
            }
        }
        Self::build(positions, uv, corner_uv, triangles)
    }

    /// Several pieces of cloth as one mesh (the particles of `pieces[1]` numbered after
    /// those of `pieces[0]`, and so on), each keeping its rest shape: sheets stacked or
    /// dropped onto one another in one simulation.
    pub fn join(pieces: &[ClothMesh]) -> Result<Self, MeshError> {
        let (mut positions, mut triangles, mut corner_uv) = (Vec::new(), Vec::new(), Vec::new());
        for piece in pieces {
            let offset = positions.len();
            positions.extend_from_slice(&piece.positions);
            triangles.extend(piece.triangles.iter().map(|t| t.map(|i| i + offset)));
            corner_uv.extend_from_slice(&piece.corner_uv);
        }
        Self::with_corner_uv(positions, triangles, corner_uv)
    }

    fn check_indices(n: usize, triangles: &[[usize; 3]]) -> Result<(), MeshError> {
        if triangles.is_empty() {
            return Err(MeshError::Empty);
        }
        for (t, tri) in triangles.iter().enumerate() {
            for (k, &index) in tri.iter().enumerate() {
                if index >= n {
                    return Err(MeshError::IndexOutOfRange {
                        triangle: t,
                        index,
                        vertex_count: n,
                    });
                }
                if tri[(k + 1) % 3] == index {
                    return Err(MeshError::RepeatedVertex { triangle: t, index });
                }
            }
        }
        Ok(())
    }

    fn build(
        positions: Vec<Vec3>,
        uv: Vec<Vector2<f64>>,
        corner_uv: Vec<[Vector2<f64>; 3]>,
        triangles: Vec<[usize; 3]>,
    ) -> Result<Self, MeshError> {
        for (vertex, p) in positions.iter().enumerate() {
            if !p.iter().all(|c| c.is_finite()) {
                return Err(MeshError::NonFinite {
                    vertex,
                    field: "position",
                });
            }
            if !uv[vertex].iter().all(|c| c.is_finite()) {
                return Err(MeshError::NonFinite { vertex, field: "uv" });
            }
        }
        let n = positions.len();
        for (t, tri) in triangles.iter().enumerate() {
            let corners = corner_uv[t];
            if let Some(k) = corners.iter().position(|c| !c.iter().all(|x| x.is_finite())) {
                return Err(MeshError::NonFinite {
                    vertex: tri[k],
                    field: "uv",
                });
            }
            let [a, b, c] = *tri;
            let (e1, e2) = (corners[1] - corners[0], corners[2] - corners[0]);
            let area_uv = 0.5 * (e1.x * e2.y - e1.y * e2.x).abs();
            if is_degenerate(area_uv, corners.map(|p| p.push(0.0))) {
                return Err(MeshError::DegenerateTriangle {
                    triangle: t,
                    space: "uv",
                    area: area_uv,
                });
            }
            let (p, q, r) = (positions[a], positions[b], positions[c]);
            let area_3d = 0.5 * (q - p).cross(&(r - p)).norm();
            if is_degenerate(area_3d, [p, q, r]) {
                return Err(MeshError::DegenerateTriangle {
                    triangle: t,
                    space: "3D",
                    area: area_3d,
                });
            }
        }
        let mut used = vec![false; n];
        triangles.iter().flatten().for_each(|&i| used[i] = true);
        if let Some(vertex) = used.iter().position(|u| !u) {
            return Err(MeshError::UnusedVertex { vertex });
        }
        let (edges, hinges) = edges_and_hinges(&triangles)?;
        Ok(Self {
            positions,
            uv,
            corner_uv,
            triangles,
            edges,
            hinges,
            grid: None,
        })
    }

    pub(crate) fn with_grid(mut self, grid: GridShape) -> Self {
        self.grid = Some(grid);
        self
    }

    /// Moves the given vertices by `by` (a panel placed elsewhere before it is sewn); the
    /// rest shape is untouched.
    pub fn translate_vertices(&mut self, vertices: &[usize], by: Vec3) {
        for &i in vertices {
            self.positions[i] += by;
        }
    }
    pub fn positions(&self) -> &[Vec3] {
        &self.positions
    }
    /// Each vertex's material coordinates. On a seam a vertex has one in each panel;
    /// this is that of its first triangle, and the rest state is [`corner_uv`](Self::corner_uv).
    pub fn uv(&self) -> &[Vector2<f64>] {
        &self.uv
    }
    /// The material coordinates of triangle `t`'s corners: its rest shape.
    pub fn corner_uv(&self, t: usize) -> [Vector2<f64>; 3] {
        self.corner_uv[t]
    }
    /// Whether some vertex has different material coordinates in different triangles (a
    /// sewn garment), so that [`uv`](Self::uv) alone does not give the rest state.
    pub fn has_seams(&self) -> bool {
        self.triangles
            .iter()
            .zip(&self.corner_uv)
            .any(|(t, c)| t.iter().zip(c).any(|(&i, c)| *c != self.uv[i]))
    }
    /// The same triangles with every seam vertex split into one vertex per panel, so each
    /// vertex has one material position: the panels laid out unsewn, in place.
    pub fn cut_at_seams(&self) -> ClothMesh {
        let mut ids: std::collections::HashMap<(usize, [u64; 2]), usize> = std::collections::HashMap::new();
        let (mut positions, mut uv) = (Vec::new(), Vec::new());
        let triangles = self
            .triangles
            .iter()
            .zip(&self.corner_uv)
            .map(|(t, c)| {
                std::array::from_fn(|k| {
                    *ids.entry((t[k], [c[k].x.to_bits(), c[k].y.to_bits()]))
                        .or_insert_with(|| {
                            positions.push(self.positions[t[k]]);
                            uv.push(c[k]);
                            uv.len() - 1
                        })
                })
            })
            .collect();
        ClothMesh::new(positions, uv, triangles).expect("cutting a valid mesh keeps it valid")
    }
    pub fn triangles(&self) -> &[[usize; 3]] {
        &self.triangles
    }
    /// Unique edges, each as a sorted vertex pair.
    pub fn edges(&self) -> &[[usize; 2]] {
        &self.edges
    }
    pub fn hinges(&self) -> &[Hinge] {
        &self.hinges
    }
    /// The grid layout when the mesh came from [`GridBuilder`](super::GridBuilder).
    pub fn grid(&self) -> Option<GridShape> {
        self.grid
    }
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Rest (material) area of triangle `t`.
    pub fn rest_area(&self, t: usize) -> f64 {
        let [a, b, c] = self.corner_uv[t];
        let (e1, e2) = (b - a, c - a);
        0.5 * (e1.x * e2.y - e1.y * e2.x).abs()
    }

    /// Total rest area.
    pub fn total_rest_area(&self) -> f64 {
        (0..self.triangles.len()).map(|t| self.rest_area(t)).sum()
    }

    /// Lumped masses: each triangle gives a third of its rest mass to each corner.
    pub fn lumped_masses(&self, area_density: f64) -> Vec<f64> {
        let mut m = vec![0.0; self.vertex_count()];
        for (t, tri) in self.triangles.iter().enumerate() {
            let share = area_density * self.rest_area(t) / 3.0;
            for &v in tri {
                m[v] += share;
            }
        }
        m
    }
}

/// Zero area relative to the triangle's size (scale-free, so millimetre and metre meshes agree).
fn is_degenerate(area: f64, p: [Vec3; 3]) -> bool {
    let longest = (0..3)
        .map(|k| (p[(k + 1) % 3] - p[k]).norm_squared())
        .fold(0.0, f64::max);
    !(area > 1e-10 * longest)
}
