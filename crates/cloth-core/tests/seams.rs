//! Meshes sewn from panels: material coordinates per triangle corner, and seam forces.

use cloth_core::{math::Vec3, ClothMesh, Fabric, GridBuilder, SeamPull, SimulationBuilder};
use nalgebra::{Rotation2, Vector2};

/// A 6 x 5 grid cut along the column i = 3 into two panels, the right panel's material
/// coordinates turned by 90 degrees (warp and weft swapped) and moved, then welded back
/// by per-corner coordinates: the same cloth as the grid when warp and weft are alike.
fn welded_grid() -> (ClothMesh, ClothMesh) {
    let grid = GridBuilder::new(6, 5).size(0.1, 0.08).build().unwrap();
    let g = grid.grid().unwrap();
    let turn = Rotation2::new(90f64.to_radians());
    let shift = Vector2::new(0.3, -0.2);
    let corner_uv = grid
        .triangles()
        .iter()
        .map(|t| {
            // A triangle is in the right panel when its vertices' mean column is past 3.
            let right = t.iter().map(|&v| (v % g.nx) as f64).sum::<f64>() / 3.0 > 3.0;
            t.map(|v| {
                let uv = grid.uv()[v];
                if right {
                    turn * uv + shift
                } else {
                    uv
                }
            })
        })
        .collect();
    let welded =
        ClothMesh::with_corner_uv(grid.positions().to_vec(), grid.triangles().to_vec(), corner_uv).unwrap();
    (grid, welded)
}

fn deformed(mesh: &ClothMesh) -> Vec<Vec3> {
    mesh.positions()
        .iter()
        .map(|p| {
            Vec3::new(
                p.x * 1.02 + 0.01 * (9.0 * p.y).sin(),
                p.y * 0.99,
                0.02 * (30.0 * p.x).sin() * p.y,
            )
        })
        .collect()
}

#[test]
fn per_corner_material_coordinates_give_the_rest_state() {
    let (grid, welded) = welded_grid();
    assert!(welded.has_seams() && !grid.has_seams());
    assert_eq!(welded.hinges().len(), grid.hinges().len());
    assert!((welded.total_rest_area() - grid.total_rest_area()).abs() < 1e-15);
    // Cut open, the seam's 5 vertices are doubled and the hinges across it are gone.
    let cut = welded.cut_at_seams();
    assert_eq!(cut.vertex_count(), grid.vertex_count() + 5);
    assert!(!cut.has_seams());
    assert!(cut.hinges().len() < grid.hinges().len());

    let fabric = Fabric::isotropic_linear(0.2, 500.0, 20.0, 3e-5);
    let build = |mesh: &ClothMesh| {
        let moved = ClothMesh::new(deformed(mesh), mesh.uv().to_vec(), mesh.triangles().to_vec()).unwrap();
        let mesh = if mesh.has_seams() {
            let corners = (0..mesh.triangles().len()).map(|t| mesh.corner_uv(t)).collect();
            ClothMesh::with_corner_uv(moved.positions().to_vec(), mesh.triangles().to_vec(), corners).unwrap()
        } else {
            moved
        };
        SimulationBuilder::new(mesh, fabric.clone())
            .bending_calibration(vec![[1.1, 1.1]])
            .build()
            .unwrap()
    };
    let (mut a, mut b) = (build(&grid), build(&welded));
    let (fa, fb) = (a.forces().to_vec(), b.forces().to_vec());
    let scale = fa.iter().map(|f| f.norm()).fold(0.0, f64::max);
    for (i, (x, y)) in fa.iter().zip(&fb).enumerate() {
        assert!((x - y).norm() < 1e-9 * scale, "particle {i}: {x} vs {y}");
    }
    // And the calibration of a seamed mesh is that of its panels.
    let c = SimulationBuilder::new(welded.clone(), fabric.clone())
        .build()
        .unwrap();
    let d = SimulationBuilder::new(welded.cut_at_seams(), fabric)
        .build()
        .unwrap();
    assert_eq!(c.bending_calibration(), d.bending_calibration());
}

/// Two strips 4 x 10 cm side by side, 6 cm apart, and the pairs that sew the left one's
/// right column to the right one's left column.
fn two_strips() -> (ClothMesh, Vec<[usize; 2]>) {
    let strip = |x0: f64| {
        GridBuilder::new(3, 6)
            .size(0.04, 0.1)
            .origin(Vec3::new(x0, 0.0, 0.0))
            .build()
            .unwrap()
    };
    let (left, right) = (strip(0.0), strip(0.1));
    let n = left.vertex_count();
    let mut positions = left.positions().to_vec();
    positions.extend(right.positions());
    let mut uv = left.uv().to_vec();
    uv.extend(right.uv());
    let mut triangles = left.triangles().to_vec();
    triangles.extend(right.triangles().iter().map(|t| t.map(|i| i + n)));
    let mesh = ClothMesh::new(positions, uv, triangles).unwrap();
    let pairs: Vec<[usize; 2]> = (0..6).map(|j| [j * 3 + 2, n + j * 3]).collect();
    (mesh, pairs)
}

/// The widest gap of `pairs` in `sim`, m.
fn widest(sim: &cloth_core::Simulation, pairs: &[[usize; 2]]) -> f64 {
    pairs
        .iter()
        .map(|&[a, b]| (sim.positions()[a] - sim.positions()[b]).norm())
        .fold(0.0, f64::max)
}

#[test]
fn seam_forces_close_a_gap_and_bad_pairs_are_refused() {
    let (mesh, pairs) = two_strips();
    let fabric = Fabric::cotton_like().with_damping(0.01);
    let settings = cloth_core::SolverSettings {
        gravity: Vec3::zeros(),
        ..Default::default()
    };
    let mut sim = SimulationBuilder::new(mesh.clone(), fabric.clone())
        .settings(settings)
        .seams(pairs.clone())
        .build()
        .unwrap();
    let gap = |sim: &cloth_core::Simulation| widest(sim, &pairs);
    // Without a pull nothing moves.
    sim.step().unwrap();
    assert!((gap(&sim) - 0.06).abs() < 1e-12);
    sim.set_seam_pull(SeamPull {
        stiffness: 0.05,
        reach: 0.01,
        damping: 0.0,
    })
    .unwrap();
    // A pull of 0.5 mN per pair on strips of 0.6 g: a few m/s^2.
    for _ in 0..600 {
        sim.step().unwrap();
    }
    assert!(gap(&sim) < 1e-3, "gap {}", gap(&sim));
    assert!(sim
        .set_seam_pull(SeamPull {
            stiffness: -1.0,
            reach: 0.01,
            damping: 0.0,
        })
        .is_err());
    let bad = SimulationBuilder::new(mesh, fabric).seams(vec![[0, 0]]).build();
    assert!(bad.unwrap_err().to_string().contains("seams"));
}

#[test]
fn a_seam_pair_weighed_zero_is_not_pulled_until_weighed_again() {
    let (mesh, pairs) = two_strips();
    let settings = cloth_core::SolverSettings {
        gravity: Vec3::zeros(),
        ..Default::default()
    };
    let sim = || {
        let mut sim = SimulationBuilder::new(mesh.clone(), Fabric::cotton_like().with_damping(0.01))
            .settings(settings.clone())
            .seams(pairs.clone())
            .build()
            .unwrap();
        sim.set_seam_pull(SeamPull {
            stiffness: 0.05,
            reach: 0.01,
            damping: 0.0,
        })
        .unwrap();
        sim
    };
    let gap = |sim: &cloth_core::Simulation, k: usize| widest(sim, &pairs[k..=k]);
    // Every pair weighed zero: pulled, nothing moves.
    let mut none = sim();
    none.set_seam_weights(&[0.0; 6]).unwrap();
    for _ in 0..20 {
        none.step().unwrap();
    }
    assert!((widest(&none, &pairs) - 0.06).abs() < 1e-12);
    // Only the bottom pair pulled, the strips close at the bottom first; only the top
    // one, at the top: the weights go to the pairs in the order they were given.
    for (pulled, other) in [(0, 5), (5, 0)] {
        let mut one = sim();
        let mut weights = [0.0; 6];
        weights[pulled] = 1.0;
        one.set_seam_weights(&weights).unwrap();
        for _ in 0..40 {
            one.step().unwrap();
        }
        let (near, far) = (gap(&one, pulled), gap(&one, other));
        assert!(
            near < 0.06 - 1e-3 && near < 0.9 * far,
            "pulled {near} m, other {far} m"
        );
    }
    // Weighed again, every pair closes.
    none.set_seam_weights(&[1.0; 6]).unwrap();
    for _ in 0..600 {
        none.step().unwrap();
    }
    assert!(widest(&none, &pairs) < 1e-3, "{} m apart", widest(&none, &pairs));
    // One weight per pair, finite and not negative.
    for bad in [
        vec![1.0; 5],
        vec![1.0, 1.0, 1.0, 1.0, 1.0, -1.0],
        vec![f64::NAN; 6],
    ] {
        let error = none.set_seam_weights(&bad).unwrap_err();
        assert!(error.to_string().contains("seam_weights"), "{error}");
    }
}
