//! `cloth.ClothMesh`: the cloth's triangles with positions and material coordinates.

use crate::arrays::{index_array, indices, numbers, plane_points, point, points, vec2_array, vec3_array};
use crate::errors::input;
use cloth::{math::Vec3, GridBuilder};
use numpy::{PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use std::path::PathBuf;

/// A triangle mesh with 3D positions and 2D material (warp u, weft v) coordinates in
/// metres, which define the flat rest state. A sewn garment's mesh keeps them per triangle
/// corner.
#[pyclass(frozen, module = "cloth")]
#[derive(Clone)]
pub struct ClothMesh {
    pub inner: cloth::ClothMesh,
}

#[pymethods]
impl ClothMesh {
    /// A rectangular sheet of `nx` by `ny` particles, `size` m, its corner at `origin`, the
    /// warp along `u_axis` and the weft along `v_axis`. Particle (i, j) is number
    /// `j * nx + i` (see `grid_index`).
    #[staticmethod]
    #[pyo3(signature = (nx, ny, size, *, origin = None, u_axis = None, v_axis = None))]
    fn grid(
        nx: usize,
        ny: usize,
        size: &Bound<'_, PyAny>,
        origin: Option<&Bound<'_, PyAny>>,
        u_axis: Option<&Bound<'_, PyAny>>,
        v_axis: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let or = |v: Option<&Bound<'_, PyAny>>, name, default| v.map_or(Ok(default), |v| point(v, name));
        let [width, height] = numbers::<2>(size, "size")?;
        let mesh = GridBuilder::new(nx, ny)
            .size(width, height)
            .origin(or(origin, "origin", Vec3::zeros())?)
            .axes(or(u_axis, "u_axis", Vec3::x())?, or(v_axis, "v_axis", Vec3::y())?)
            .build()
            .map_err(input)?;
        Ok(Self { inner: mesh })
    }

    /// From `(N, 3)` positions, `(N, 2)` material coordinates and `(M, 3)` vertex indices.
    /// Bad shapes, dtypes, indices or degenerate triangles raise ValueError or TypeError
    /// naming the array and the element.
    #[staticmethod]
    fn from_arrays(
        positions: &Bound<'_, PyAny>,
        uv: &Bound<'_, PyAny>,
        triangles: &Bound<'_, PyAny>,
    ) -> PyResult<Self> {
        let x = points(positions, "positions", None)?;
        let uv = plane_points(uv, "uv", Some(x.len()))?;
        let t = indices::<3>(triangles, "triangles", x.len())?;
        let mesh = cloth::ClothMesh::new(x, uv, t).map_err(input)?;
        Ok(Self { inner: mesh })
    }

    /// An OBJ file, as a scene's `[cloth.mesh]`: its `vt` times `uv_scale` are the material
    /// coordinates; a file without them must be flat, and is its own rest shape with the
    /// warp along x. Coordinates are multiplied by `scale`, turned from `up_axis` ("y" or
    /// "z") to z up, then by `rotation` (degrees about x, then y, then z), then moved by
    /// `position`.
    #[staticmethod]
    #[pyo3(signature = (path, *, scale = 1.0, uv_scale = 1.0, up_axis = "z", rotation = None, position = None))]
    fn load(
        path: PathBuf,
        scale: f64,
        uv_scale: f64,
        up_axis: &str,
        rotation: Option<&Bound<'_, PyAny>>,
        position: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let offset = position.map_or(Ok(Vec3::zeros()), |p| point(p, "position"))?;
        let turn = rotation.map_or(Ok(Vec3::zeros()), |r| point(r, "rotation"))?;
        let up = crate::convert::up_axis(up_axis)?;
        let placed = cloth::scene_file::placement(up, turn.into(), offset.into())
            .map_err(|reason| input(format!("rotation: {reason}")))?;
        let mesh = cloth::scene_file::read_cloth_obj(&path, scale, uv_scale, &placed)
            .map_err(|reason| input(format!("'{}': {reason}", path.display())))?;
        Ok(Self { inner: mesh })
    }

    /// `(N, 3)` initial positions.
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        vec3_array(py, self.inner.positions())
    }
    /// `(N, 2)` material coordinates (for a seam vertex, those of its first triangle).
    #[getter]
    fn uv<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        vec2_array(py, self.inner.uv())
    }
    /// `(M, 3, 2)` material coordinates of every triangle's corners, m (u along the warp,
    /// v along the weft): a seam vertex has each panel's own at its corners there.
    #[getter]
    fn corner_uv<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray3<f64>> {
        let m = self.inner.triangles().len();
        let flat: Vec<f64> = (0..m)
            .flat_map(|t| self.inner.corner_uv(t))
            .flat_map(|c| [c.x, c.y])
            .collect();
        numpy::PyArray1::from_vec(py, flat)
            .reshape([m, 3, 2])
            .expect("a flat array of m * 6 reshapes to (m, 3, 2)")
    }
    /// `(M, 3)` vertex indices.
    #[getter]
    fn triangles<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<i64>> {
        index_array(py, self.inner.triangles())
    }
    /// `(E, 2)` vertex indices of the distinct edges.
    #[getter]
    fn edges<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<i64>> {
        index_array(py, self.inner.edges())
    }
    /// Number of vertices (particles).
    #[getter]
    fn vertex_count(&self) -> usize {
        self.inner.vertex_count()
    }
    /// Number of triangles.
    #[getter]
    fn triangle_count(&self) -> usize {
        self.inner.triangles().len()
    }
    /// `(nx, ny)` of a grid mesh, else None.
    #[getter]
    fn grid_shape(&self) -> Option<(usize, usize)> {
        self.inner.grid().map(|g| (g.nx, g.ny))
    }
    /// The particle at thread crossing (i, j) of a grid mesh.
    fn grid_index(&self, i: usize, j: usize) -> PyResult<usize> {
        let g = self
            .inner
            .grid()
            .ok_or_else(|| input("grid_index: the mesh is not a grid"))?;
        if i >= g.nx || j >= g.ny {
            return Err(input(format!(
                "grid_index: ({i}, {j}) is outside the {} x {} grid",
                g.nx, g.ny
            )));
        }
        Ok(g.index(i, j))
    }
    /// Total material area, m^2.
    #[getter]
    fn rest_area(&self) -> f64 {
        self.inner.total_rest_area()
    }
    /// Writes the mesh (at `positions` if given) as OBJ with its material coordinates.
    #[pyo3(signature = (path, positions = None))]
    fn save_obj(&self, path: PathBuf, positions: Option<&Bound<'_, PyAny>>) -> PyResult<()> {
        let x = match positions {
            Some(p) => points(p, "positions", Some(self.inner.vertex_count()))?,
            None => self.inner.positions().to_vec(),
        };
        let comments = cloth::scene_file::UpAxis::Z.file_header("the cloth");
        let obj = cloth::formats::obj::ClothObj {
            comments: &comments,
            mesh: &self.inner,
            positions: &x,
            panels: None,
        };
        cloth::formats::obj::write_cloth_obj_with_uv(&path, &obj).map_err(|e| {
            pyo3::exceptions::PyOSError::new_err(format!("cannot write '{}': {e}", path.display()))
        })
    }

    fn __repr__(&self) -> String {
        format!(
            "ClothMesh({} vertices, {} triangles)",
            self.inner.vertex_count(),
            self.inner.triangles().len()
        )
    }
}
