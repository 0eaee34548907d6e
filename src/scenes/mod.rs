//! Ready-made contact scenes: the examples run them and the integration tests check them.
//! Each is a parameter struct with sensible defaults whose `build` gives a [`Scene`].

mod cube_corner;
mod falling_plate;
mod folding_strip;
mod sheet_onto_sheet;
mod sphere_drop;
mod stacked_sheets;
mod tablecloth;
mod tilted_plane;
mod turning_sphere;

pub use cube_corner::CubeCorner;
pub use falling_plate::FallingPlate;
pub use folding_strip::FoldingStrip;
pub use sheet_onto_sheet::SheetOntoSheet;
pub use sphere_drop::SphereDrop;
pub use stacked_sheets::StackedSheets;
pub use tablecloth::Tablecloth;
pub use tilted_plane::TiltedPlane;
pub use turning_sphere::TurningSphere;

use cloth_collide::{Bodies, Body, BodyError, SurfaceError};
use cloth_core::{
    math::Vec3, ClothMesh, Fabric, GridBuilder, MeshError, ParamError, Simulation, SimulationBuilder,
};
use std::sync::Arc;

/// A simulation with the bodies it collides with (kept to measure penetration).
#[derive(Debug)]
pub struct Scene {
    pub simulation: Simulation,
    pub bodies: Arc<Bodies>,
}

impl Scene {
    /// A scene of one body: the cloth of `simulation` collides with it.
    pub fn new(body: Body, simulation: SimulationBuilder) -> Result<Self, SceneError> {
        let bodies = Arc::new(Bodies::new(vec![body]));
        let simulation = simulation.collider(bodies.clone()).build()?;
        Ok(Self { simulation, bodies })
    }

    /// How deep the deepest particle is inside a body now, m (0 when none is).
    pub fn deepest_penetration(&self) -> f64 {
        self.bodies
            .deepest_inside(self.simulation.time(), self.simulation.positions())
            .0
    }
}

/// Why a scene could not be built.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    #[error(transparent)]
    Surface(#[from] SurfaceError),
    #[error(transparent)]
    Body(#[from] BodyError),
    #[error(transparent)]
    Mesh(#[from] MeshError),
    #[error(transparent)]
    Param(#[from] ParamError),
}

/// The fabric of the scenes: cotton-like, with a little stiffness damping and air drag.
pub fn scene_fabric() -> Fabric {
    Fabric::cotton_like().with_damping(2e-3).with_drag(0.05)
}

/// A horizontal square sheet of the scene fabric stepped at `time_step`: `n` x `n`
/// particles, `size` wide, centred on `centre`.
pub(crate) fn horizontal_sheet(
    n: usize,
    size: f64,
    centre: Vec3,
    time_step: f64,
) -> Result<SimulationBuilder, MeshError> {
    let mesh = square_sheet(n, size, centre, Vec3::x(), Vec3::y())?;
    Ok(SimulationBuilder::new(mesh, scene_fabric()).time_step(time_step))
}

/// Two square sheets of `n` x `n` particles, `size` wide, as one mesh: a horizontal one
/// centred on `centre`, then one moved by `offset` and turned `turn` degrees about the
/// vertical. Returns the mesh and the first sheet's particle count.
pub(crate) fn two_sheets(
    n: usize,
    size: f64,
    centre: Vec3,
    offset: Vec3,
    turn: f64,
) -> Result<(ClothMesh, usize), MeshError> {
    let first = square_sheet(n, size, centre, Vec3::x(), Vec3::y())?;
    let (s, c) = turn.to_radians().sin_cos();
    let second = square_sheet(
        n,
        size,
        centre + offset,
        Vec3::new(c, s, 0.0),
        Vec3::new(-s, c, 0.0),
    )?;
    let count = first.vertex_count();
    Ok((ClothMesh::join(&[first, second])?, count))
}

/// A square sheet of `n` x `n` particles, `size` wide, centred on `centre`, spanned by the
/// unit vectors `u` and `v` (alternating diagonals: the square's symmetries).
pub(crate) fn square_sheet(
    n: usize,
    size: f64,
    centre: Vec3,
    u: Vec3,
    v: Vec3,
) -> Result<ClothMesh, MeshError> {
    let origin = centre - 0.5 * size * (u + v);
    GridBuilder::new(n, n)
        .size(size, size)
        .origin(origin)
        .axes(u, v)
        .build()
}
