//! The scenes' fabric and square sheets.

use cloth_core::{math::Vec3, ClothMesh, Fabric, GridBuilder, MeshError, SimulationBuilder};

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
