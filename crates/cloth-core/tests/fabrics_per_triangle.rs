//! Cloth of several fabrics (a garment's panels): each triangle of its own.

use cloth_core::{math::Vec3, Fabric, GridBuilder, Pin, RestCriteria, SimulationBuilder};

/// A 1 m strip, 4 cm wide, hanging from its top row: its upper half of a stiff fabric, its
/// lower half four times softer. With no Poisson coupling in the thread model each cell
/// stretches by the weight below it over its own stiffness, so the extension is that of
/// the discrete chain, cell by cell.
#[test]
fn a_strip_of_two_fabrics_stretches_as_each_of_its_cells() {
    let rows = 41;
    let mesh = GridBuilder::new(3, rows)
        .size(0.04, 1.0)
        .axes(Vec3::x(), -Vec3::z())
        .build()
        .unwrap();
    let g = mesh.grid().unwrap();
    let (stiff, soft) = (400.0, 100.0);
    let density = 0.2;
    let upper = Fabric::isotropic_linear(density, stiff, 5.0, 1e-7).with_damping(0.02);
    let lower = Fabric::isotropic_linear(density, soft, 5.0, 1e-7).with_damping(0.02);
    let cell = 1.0 / (rows - 1) as f64;
    // A triangle is in the lower half when its vertices' mean row is past the middle.
    let triangle_fabric: Vec<usize> = mesh
        .triangles()
        .iter()
        .map(|t| usize::from(t.iter().map(|&i| (i / g.nx) as f64).sum::<f64>() / 3.0 > 20.0))
        .collect();
    let top = (0..g.nx).map(|i| Pin::fixed(g.index(i, 0)));
    let mut sim = SimulationBuilder::new(mesh, upper.clone())
        .fabrics(vec![upper, lower], triangle_fabric.clone())
        .pins(top)
        .build()
        .unwrap();
    assert_eq!(sim.fabrics().len(), 2);
    let outcome = sim
        .run_to_rest(&RestCriteria {
            max_time_step: None,
            tolerance: 1e-9,
            consecutive_steps: 10,
            max_steps: 20_000,
            moving_fraction: 0.0,
        })
        .unwrap();
    assert_eq!(outcome.reason, cloth_core::StopReason::AtRest);
    // Cell j (from the top) carries the rows below it: row weight rho g w cell, half at
    // the bottom row; per unit width, T_j = rho g cell (rows - 2 - j + 1/2).
    let expected: f64 = (0..rows - 1)
        .map(|j| {
            let tension = density * 9.81 * cell * ((rows - 2 - j) as f64 + 0.5);
            let k = if j < 20 { stiff } else { soft };
            tension * cell / k
        })
        .sum();
    let bottom: f64 = (0..g.nx)
        .map(|i| -sim.positions()[g.index(i, rows - 1)].z)
        .sum::<f64>()
        / g.nx as f64;
    let extension = bottom - 1.0;
    assert!(
        (extension / expected - 1.0).abs() < 0.01,
        "extension {extension:.6e} vs {expected:.6e}"
    );
    // The same strip all of the stiff fabric stretches far less: the soft half counts.
    let all_stiff: f64 = (0..rows - 1)
        .map(|j| density * 9.81 * cell * ((rows - 2 - j) as f64 + 0.5) * cell / stiff)
        .sum();
    // (By the chain: (3/8 + 4 / 8) / (1/2) = 1.75 times.)
    assert!(extension > 1.7 * all_stiff, "{extension} vs {all_stiff}");
}

#[test]
fn masses_follow_each_triangles_fabric_and_bad_indices_are_refused() {
    let mesh = GridBuilder::new(5, 5).size(0.4, 0.4).build().unwrap();
    let n_tri = mesh.triangles().len();
    let light = Fabric::isotropic_linear(0.1, 500.0, 10.0, 1e-5);
    let heavy = Fabric::isotropic_linear(0.3, 500.0, 10.0, 1e-5);
    let half: Vec<usize> = (0..n_tri).map(|t| usize::from(t >= n_tri / 2)).collect();
    let area_of = |which: usize| -> f64 {
        (0..n_tri)
            .filter(|&t| half[t] == which)
            .map(|t| mesh.rest_area(t))
            .sum()
    };
    let expected = 0.1 * area_of(0) + 0.3 * area_of(1);
    let sim = SimulationBuilder::new(mesh.clone(), light.clone())
        .fabrics(vec![light.clone(), heavy.clone()], half.clone())
        .build()
        .unwrap();
    let total: f64 = sim.masses().iter().sum();
    assert!(
        (total - expected).abs() < 1e-12 * expected,
        "{total} vs {expected}"
    );
    let e = SimulationBuilder::new(mesh.clone(), light.clone())
        .fabrics(vec![light.clone()], half)
        .build()
        .unwrap_err();
    assert!(e.to_string().contains("triangle_fabric"), "{e}");
    let e = SimulationBuilder::new(mesh, light.clone())
        .fabrics(vec![light, heavy], vec![0; 3])
        .build()
        .unwrap_err();
    assert!(e.to_string().contains("one fabric index per triangle"), "{e}");
}
