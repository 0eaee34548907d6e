//! Pieces of cloth that touch at a point at the start (GarmentCode's godets, side by side
//! in one plane, meet at their hem corners) part freely when the touching particles are
//! given to the builder: the cloth's contact with itself does not hold the point.

use cloth_core::{
    math::Vec3, ClothMesh, Fabric, GridBuilder, Simulation, SimulationBuilder, SolverSettings, StrainReport,
};

/// Two 10 cm sheets in the plane z = 0 meeting at the origin, corner to corner: `a` over
/// [-0.1, 0] x [0, 0.1], `b` over [0, 0.1] x [-0.1, 0]. Returns the mesh and the two
/// particles at the origin.
fn corner_to_corner() -> (ClothMesh, [usize; 2]) {
    let a = GridBuilder::new(11, 11)
        .size(0.1, 0.1)
        .origin(Vec3::new(-0.1, 0.0, 0.0))
        .build()
        .unwrap();
    let b = GridBuilder::new(11, 11)
        .size(0.1, 0.1)
        .origin(Vec3::new(0.0, -0.1, 0.0))
        .build()
        .unwrap();
    let n = a.vertex_count();
    let mut positions = a.positions().to_vec();
    positions.extend(b.positions());
    let mut uv = a.uv().to_vec();
    uv.extend(b.uv());
    let mut triangles = a.triangles().to_vec();
    triangles.extend(b.triangles().iter().map(|t| t.map(|i| i + n)));
    let at_origin = |x: &[Vec3]| (0..x.len()).find(|&i| x[i].norm() < 1e-12).unwrap();
    let corners = [at_origin(a.positions()), n + at_origin(b.positions())];
    (ClothMesh::new(positions, uv, triangles).unwrap(), corners)
}

/// Sheet `a` set moving at [`VA`] and `b` at [`VB`] (apart, and out of their plane in
/// opposite senses), for 0.2 s.
const VA: [f64; 3] = [-0.3, 0.0, 0.1];
const VB: [f64; 3] = [0.0, -0.3, -0.1];

fn drawn_apart(touching: Vec<[usize; 2]>) -> (Simulation, [usize; 2]) {
    let (mesh, corners) = corner_to_corner();
    let n = mesh.vertex_count();
    let half = n / 2;
    let v = (0..n)
        .map(|i| if i < half { Vec3::from(VA) } else { Vec3::from(VB) })
        .collect();
    let mut sim = SimulationBuilder::new(mesh, Fabric::cotton_like())
        .settings(SolverSettings {
            gravity: Vec3::zeros(),
            time_step: 1.0 / 50.0,
            ..SolverSettings::default()
        })
        .velocities(v)
        .touching(touching)
        .build()
        .unwrap();
    for _ in 0..10 {
        sim.step().unwrap();
    }
    (sim, corners)
}

#[test]
fn pieces_touching_at_a_point_part_when_the_point_is_given() {
    let (mesh, corners) = corner_to_corner();
    let n = mesh.vertex_count();
    let (sim, [a, b]) = drawn_apart(vec![corners]);
    let x = sim.positions();
    // Each corner went with its sheet, the cloth unstrained.
    let gap = (x[a] - x[b]).norm();
    let expected = 0.2 * (Vec3::from(VA) - Vec3::from(VB)).norm();
    assert!(
        (gap - expected).abs() < 0.05 * expected,
        "corners {gap} m apart, not {expected}"
    );
    let strain = StrainReport::new(sim.mesh(), x);
    assert!(
        strain.max_warp < 1.0 && strain.max_weft < 1.0,
        "{} {}",
        strain.max_warp,
        strain.max_weft
    );
    assert_eq!(sim.self_intersections().count, 0);
    // The pair is checked as seams are.
    assert!(SimulationBuilder::new(mesh, Fabric::cotton_like())
        .touching(vec![[0, n]])
        .build()
        .is_err());
}

#[test]
fn pieces_touching_at_a_point_not_given_are_held_there() {
    // What the builder's `touching` is for: the same sheets, the point not given. The
    // contact of each corner with the other sheet's corner triangles holds them together,
    // and the cells round them are drawn out to several times their length.
    let (sim, [a, b]) = drawn_apart(Vec::new());
    let x = sim.positions();
    let gap = (x[a] - x[b]).norm();
    assert!(gap < 0.01, "corners {gap} m apart");
    let strain = StrainReport::new(sim.mesh(), x);
    assert!(
        strain.max_warp.max(strain.max_weft) > 100.0,
        "{} {}",
        strain.max_warp,
        strain.max_weft
    );
}
