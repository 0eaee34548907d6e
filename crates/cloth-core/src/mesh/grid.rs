//! A rectangular warp/weft grid: the source's particles at thread crossings.

use super::cloth_mesh::ClothMesh;
use super::error::MeshError;
use super::grid_shape::{GridDiagonals, GridShape};
use crate::math::Vec3;
use nalgebra::Vector2;

/// Builds a grid of `nx` x `ny` particles. Material coordinates are `(i du, j dv)`;
/// the 3D sheet lies in the plane spanned by `u_axis` and `v_axis` from `origin`.
#[derive(Debug, Clone)]
pub struct GridBuilder {
    nx: usize,
    ny: usize,
    du: f64,
    dv: f64,
    origin: Vec3,
    u_axis: Vec3,
    v_axis: Vec3,
    diagonals: GridDiagonals,
}

impl GridBuilder {
    /// `nx` particles along the warp, `ny` along the weft, 1 cm apart, in the x-y plane.
    pub fn new(nx: usize, ny: usize) -> Self {
        Self {
            nx,
            ny,
            du: 0.01,
            dv: 0.01,
            origin: Vec3::zeros(),
            u_axis: Vec3::x(),
            v_axis: Vec3::y(),
            diagonals: GridDiagonals::default(),
        }
    }
    /// Sets the spacing so the sheet measures `width` x `height` metres.
    pub fn size(mut self, width: f64, height: f64) -> Self {
        self.du = width / (self.nx.max(2) - 1) as f64;
        self.dv = height / (self.ny.max(2) - 1) as f64;
        self
    }
    pub fn spacing(mut self, du: f64, dv: f64) -> Self {
        self.du = du;
        self.dv = dv;
        self
    }
    pub fn origin(mut self, origin: Vec3) -> Self {
        self.origin = origin;
        self
    }
    /// Directions of the warp and weft in space (normalised here).
    pub fn axes(mut self, u_axis: Vec3, v_axis: Vec3) -> Self {
        self.u_axis = u_axis.normalize();
        self.v_axis = v_axis.normalize();
        self
    }
    pub fn diagonals(mut self, diagonals: GridDiagonals) -> Self {
        self.diagonals = diagonals;
        self
    }

    pub fn build(&self) -> Result<ClothMesh, MeshError> {
        let (nx, ny, du, dv) = (self.nx, self.ny, self.du, self.dv);
        if nx < 2 || ny < 2 || !(du > 0.0) || !(dv > 0.0) || !du.is_finite() || !dv.is_finite() {
            return Err(MeshError::BadGrid { nx, ny, du, dv });
        }
        let shape = GridShape {
            nx,
            ny,
            du,
            dv,
            diagonals: self.diagonals,
        };
        let mut positions = Vec::with_capacity(nx * ny);
        let mut uv = Vec::with_capacity(nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                let (u, v) = (i as f64 * du, j as f64 * dv);
                uv.push(Vector2::new(u, v));
                positions.push(self.origin + self.u_axis * u + self.v_axis * v);
            }
        }
        let mut triangles = Vec::with_capacity(2 * (nx - 1) * (ny - 1));
        for j in 0..ny - 1 {
            for i in 0..nx - 1 {
                let a = shape.index(i, j);
                let b = shape.index(i + 1, j);
                let c = shape.index(i + 1, j + 1);
                let d = shape.index(i, j + 1);
                let flip = self.diagonals == GridDiagonals::Alternating && (i + j) % 2 == 1;
                if flip {
                    triangles.push([a, b, d]);
                    triangles.push([b, c, d]);
                } else {
                    triangles.push([a, b, c]);
                    triangles.push([a, c, d]);
                }
            }
        }
        Ok(ClothMesh::new(positions, uv, triangles)?.with_grid(shape))
    }
}
