//! `cloth.Body`: a rigid body built as a scene's `[[bodies]]` entry is, so the checks and
//! messages are the scene file's.

use crate::arrays::{index_array, indices, numbers, points as read_points, vec3_array};
use crate::convert::{from_toml_value, to_toml};
use crate::errors::input;
use cloth::collide::{Bodies, TriSurface};
use cloth::garment::mannequin::Measurements;
use cloth::scene_file::{
    BodyShape, BodySpec, BoxSpec, ContactSpec, CylinderSpec, FileSpec, MeshSpec, Placement, SphereSpec,
    TableSpec, UpAxis,
};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict};
use std::path::Path;
use std::sync::Arc;

/// A rigid body the cloth drapes on: a closed triangle surface placed at `position`, with
/// a contact `thickness` (m) and a `friction` coefficient (the fabric's when None). A
/// mannequin with arms is one Body of three parts.
#[pyclass(frozen, module = "cloth")]
#[derive(Clone)]
pub struct Body {
    name: String,
    pub parts: Vec<cloth::collide::Body>,
}

/// The placement and contact keys every constructor takes.
struct Common<'a, 'py> {
    position: Option<&'a Bound<'py, PyAny>>,
    thickness: Option<f64>,
    friction: Option<f64>,
    name: Option<String>,
}

impl Body {
    /// Builds the body a scene's `[[bodies]]` entry of `shape`, placed by `turn` (up axis
    /// and rotation) and `common`, makes; errors name the constructor (`key`).
    fn build(shape: BodyShape, turn: Placement, common: Common<'_, '_>, key: &str) -> PyResult<Self> {
        let position = match common.position {
            Some(p) => numbers::<3>(p, "position")?,
            None => [0.0; 3],
        };
        let spec = BodySpec {
            name: common.name.clone(),
            shape,
            placement: Placement { position, ..turn },
            contact: ContactSpec {
                thickness: common.thickness,
                min_thickness: None,
                friction: common.friction,
            },
        };
        let parts = spec
            .build("cloth.Body", Path::new("."), key, None)
            .map_err(input)?;
        let name = common.name.unwrap_or_else(|| match parts.as_slice() {
            [one] => one.name().to_string(),
            _ => key.to_string(),
        });
        Ok(Self { name, parts })
    }

    /// [`Self::build`] for a mesh that may have defects: a warning for each kind, saying
    /// it is `source`'s.
    fn build_mesh(
        py: Python<'_>,
        shape: BodyShape,
        turn: Placement,
        common: Common<'_, '_>,
        key: &str,
        source: &str,
    ) -> PyResult<Self> {
        let body = Self::build(shape, turn, common, key)?;
        let warnings = py.import("warnings")?;
        for d in body.defects() {
            warnings.call_method1("warn", (format!("{source}: {d}"),))?;
        }
        Ok(body)
    }

    fn defects(&self) -> Vec<String> {
        self.parts
            .iter()
            .flat_map(|b| b.surface().defects().iter().map(ToString::to_string))
            .collect()
    }

    fn surface(&self) -> TriSurface {
        let surfaces: Vec<TriSurface> = self.parts.iter().map(|b| b.surface_at(0.0)).collect();
        TriSurface::merged(&surfaces)
    }
}

/// The turn of a body given as a mesh: from `up_axis` ("y" or "z") to z up, then by
/// `rotation`; errors name the constructor `what`.
fn turn(what: &str, up_axis: Option<&str>, rotation: Option<&Bound<'_, PyAny>>) -> PyResult<Placement> {
    let up_axis = match up_axis {
        None => None,
        Some("y") => Some(UpAxis::Y),
        Some("z") => Some(UpAxis::Z),
        Some(other) => {
            return Err(input(format!(
                "{what}: up_axis must be \"y\" or \"z\", not {other:?}"
            )))
        }
    };
    Ok(Placement {
        up_axis,
        rotation: rotation
            .map(|r| numbers::<3>(r, "rotation"))
            .transpose()?
            .unwrap_or_default(),
        position: [0.0; 3],
    })
}

/// All the parts of `bodies`, as the collider a simulation uses.
pub fn collider(bodies: &[PyRef<'_, Body>]) -> Arc<Bodies> {
    Arc::new(Bodies::new(
        bodies.iter().flat_map(|b| b.parts.iter().cloned()).collect(),
    ))
}

#[pymethods]
impl Body {
    /// An OBJ, STL, PLY, glTF or GLB file (`scale` 0.01 for centimetres), turned from its
    /// `up_axis` ("y" or "z"; glTF's is "y" when not given, the others' "z") to z up, then by
    /// `rotation` (degrees about x, then y, then z), then moved to `position`. A mesh with
    /// holes, stray edges or overlapping parts loads with a warning for each kind of
    /// defect (see `defects`); one that encloses nothing raises ValueError naming the file.
    #[staticmethod]
    #[pyo3(signature = (path, *, scale = 1.0, up_axis = None, rotation = None, position = None, thickness = None, friction = None, name = None))]
    #[allow(clippy::too_many_arguments)]
    fn load(
        py: Python<'_>,
        path: std::path::PathBuf,
        scale: f64,
        up_axis: Option<&str>,
        rotation: Option<&Bound<'_, PyAny>>,
        position: Option<&Bound<'_, PyAny>>,
        thickness: Option<f64>,
        friction: Option<f64>,
        name: Option<String>,
    ) -> PyResult<Self> {
        let turn = turn("Body.load", up_axis, rotation)?;
        let file = BodyShape::File(FileSpec {
            path: path.clone(),
            scale,
        });
        let common = Common {
            position,
            thickness,
            friction,
            name,
        };
        Self::build_mesh(py, file, turn, common, "file", &path.display().to_string())
    }

    /// A body from a triangle mesh in memory: `vertices` `(V, 3)` and `triangles` `(T, 3)`
    /// indices into them, scaled, turned and placed as `load`'s file is (`up_axis` "z" by
    /// default) and checked as a file is: a mesh with defects loads with a warning for each
    /// kind, one that encloses nothing raises ValueError.
    #[staticmethod]
    #[pyo3(signature = (vertices, triangles, *, scale = 1.0, up_axis = None, rotation = None, position = None, thickness = None, friction = None, name = None))]
    #[allow(clippy::too_many_arguments)]
    fn from_arrays(
        py: Python<'_>,
        vertices: &Bound<'_, PyAny>,
        triangles: &Bound<'_, PyAny>,
        scale: f64,
        up_axis: Option<&str>,
        rotation: Option<&Bound<'_, PyAny>>,
        position: Option<&Bound<'_, PyAny>>,
        thickness: Option<f64>,
        friction: Option<f64>,
        name: Option<String>,
    ) -> PyResult<Self> {
        let vertices = read_points(vertices, "vertices", None)?;
        let bound = vertices.len().min(u32::MAX as usize);
        let triangles: Vec<[u32; 3]> = indices::<3>(triangles, "triangles", bound)?
            .into_iter()
            .map(|t| t.map(|i| i as u32))
            .collect();
        let turn = turn("Body.from_arrays", up_axis, rotation)?;
        let shape = BodyShape::Mesh(MeshSpec {
            vertices,
            triangles,
            scale,
        });
        let common = Common {
            position,
            thickness,
            friction,
            name,
        };
        Self::build_mesh(py, shape, turn, common, "mesh", "Body.from_arrays")
    }

    /// A body from a `trimesh.Trimesh` (or anything with `vertices` and `faces`), with
    /// `from_arrays`'s keyword `options`; trimesh meshes are y-up as often as not, so say
    /// `up_axis="y"` for those.
    #[staticmethod]
    #[pyo3(signature = (mesh, **options))]
    fn from_trimesh<'py>(
        mesh: &Bound<'py, PyAny>,
        options: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let py = mesh.py();
        let part = |attribute: &str| {
            mesh.getattr(attribute).map_err(|_| {
                pyo3::exceptions::PyTypeError::new_err(format!(
                    "Body.from_trimesh: expected a trimesh.Trimesh (with vertices and faces), got {}",
                    mesh.get_type().name().map_or("?".into(), |n| n.to_string())
                ))
            })
        };
        let (vertices, faces) = (part("vertices")?, part("faces")?);
        py.get_type::<Body>()
            .call_method("from_arrays", (vertices, faces), options)
    }

    /// What loading found wrong with the mesh and did about it, one line per kind of
    /// defect (empty for a watertight mesh).
    #[getter(defects)]
    fn defect_list(&self) -> Vec<String> {
        self.defects()
    }

    /// A sphere of `radius` centred on `position`.
    #[staticmethod]
    #[pyo3(signature = (radius, *, position = None, thickness = None, friction = None, name = None))]
    fn sphere(
        radius: f64,
        position: Option<&Bound<'_, PyAny>>,
        thickness: Option<f64>,
        friction: Option<f64>,
        name: Option<String>,
    ) -> PyResult<Self> {
        let common = Common {
            position,
            thickness,
            friction,
            name,
        };
        Self::build(
            BodyShape::Sphere(SphereSpec { radius }),
            Placement::default(),
            common,
            "sphere",
        )
    }

    /// A box of `size` (x, y, z) centred on `position`.
    #[staticmethod]
    #[pyo3(signature = (size, *, position = None, thickness = None, friction = None, name = None))]
    fn r#box(
        size: &Bound<'_, PyAny>,
        position: Option<&Bound<'_, PyAny>>,
        thickness: Option<f64>,
        friction: Option<f64>,
        name: Option<String>,
    ) -> PyResult<Self> {
        let size = numbers::<3>(size, "size")?;
        let common = Common {
            position,
            thickness,
            friction,
            name,
        };
        Self::build(
            BodyShape::Box(BoxSpec { size }),
            Placement::default(),
            common,
            "box",
        )
    }

    /// A cylinder along z of `radius` and `height`, centred on `position`.
    #[staticmethod]
    #[pyo3(signature = (radius, height, *, position = None, thickness = None, friction = None, name = None))]
    fn cylinder(
        radius: f64,
        height: f64,
        position: Option<&Bound<'_, PyAny>>,
        thickness: Option<f64>,
        friction: Option<f64>,
        name: Option<String>,
    ) -> PyResult<Self> {
        let common = Common {
            position,
            thickness,
            friction,
            name,
        };
        let shape = BodyShape::Cylinder(CylinderSpec { radius, height });
        Self::build(shape, Placement::default(), common, "cylinder")
    }

    /// A table standing on z = 0 below `position`: a top of `size` (width, depth,
    /// thickness) whose upper face is at `height`, on four legs.
    #[staticmethod]
    #[pyo3(signature = (size, height, *, leg_width = 0.06, leg_inset = 0.05, position = None, thickness = None, friction = None, name = None))]
    #[allow(clippy::too_many_arguments)]
    fn table(
        size: &Bound<'_, PyAny>,
        height: f64,
        leg_width: f64,
        leg_inset: f64,
        position: Option<&Bound<'_, PyAny>>,
        thickness: Option<f64>,
        friction: Option<f64>,
        name: Option<String>,
    ) -> PyResult<Self> {
        let shape = BodyShape::Table(TableSpec {
            size: numbers::<3>(size, "size")?,
            height,
            leg_width,
            leg_inset,
        });
        let common = Common {
            position,
            thickness,
            friction,
            name,
        };
        Self::build(shape, Placement::default(), common, "table")
    }

    /// The parametric mannequin: `height`, `bust`, `waist`, `hip`, `shoulder_width`,
    /// `neck_girth` (m; missing ones take the average body's), and `arms` for a form with
    /// arms: True for the average arms scaled to the height (as `cloth mannequin --arms`),
    /// or a dict of arm measurements (as a scene's `arms = {...}`).
    #[staticmethod]
    #[pyo3(signature = (*, position = None, thickness = None, friction = None, name = None, **measurements))]
    fn mannequin(
        position: Option<&Bound<'_, PyAny>>,
        thickness: Option<f64>,
        friction: Option<f64>,
        name: Option<String>,
        measurements: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let mut shape = toml::Table::new();
        let mut with_arms = false;
        if let Some(m) = measurements {
            for (k, v) in m.iter() {
                let key: String = k.extract()?;
                if key == "arms" && v.is_instance_of::<PyBool>() {
                    with_arms = v.extract::<bool>()?;
                    continue;
                }
                if v.is_none() {
                    continue;
                }
                let what = format!("mannequin.{key}");
                shape.insert(key, to_toml(&v, &what)?);
            }
        }
        let measurements: Measurements = from_toml_value(toml::Value::Table(shape), "Body.mannequin")?;
        // As `cloth mannequin --arms`: the average arms, their length scaled to the body.
        let measurements = if with_arms {
            measurements.with_arms()
        } else {
            measurements
        };
        let common = Common {
            position,
            thickness,
            friction,
            name,
        };
        Self::build(
            BodyShape::Mannequin(measurements),
            Placement::default(),
            common,
            "mannequin",
        )
    }

    /// The body's name.
    #[getter]
    fn name(&self) -> &str {
        &self.name
    }
    /// The names of the surfaces it is made of.
    #[getter]
    fn parts(&self) -> Vec<String> {
        self.parts.iter().map(|b| b.name().to_string()).collect()
    }
    /// `(V, 3)` vertices of all its parts, placed.
    #[getter]
    fn vertices<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        vec3_array(py, self.surface().vertices())
    }
    /// `(T, 3)` indices into `vertices`.
    #[getter]
    fn triangles<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<i64>> {
        let t: Vec<[usize; 3]> = self
            .surface()
            .triangles()
            .iter()
            .map(|t| t.map(|i| i as usize))
            .collect();
        index_array(py, &t)
    }
    /// Signed distance of each point to the body (negative inside), `(N,)`.
    fn signed_distance<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let x = read_points(points, "points", None)?;
        let bodies = Bodies::new(self.parts.clone());
        let d: Vec<f64> = py.detach(|| {
            x.iter()
                .map(|p| bodies.signed_distance(0.0, p).map_or(f64::INFINITY, |(d, _)| d))
                .collect()
        });
        Ok(PyArray1::from_vec(py, d))
    }
    /// Writes its surface as OBJ.
    fn save_obj(&self, path: std::path::PathBuf) -> PyResult<()> {
        self.surface().write_obj(&path).map_err(|e| {
            pyo3::exceptions::PyOSError::new_err(format!("cannot write '{}': {e}", path.display()))
        })
    }

    fn __repr__(&self) -> String {
        format!("Body('{}', {} parts)", self.name, self.parts.len())
    }
}
