//! Static equilibria against analytic references.

use cloth::validation::HangingStrip;
use cloth::{
    math::Vec3, Fabric, GridBuilder, Pin, RestCriteria, RestOutcome, Simulation, SimulationBuilder,
    SolverSettings, StopReason,
};

/// A vertical strip pinned along its top edge: the strain at the top is the law's at the
/// weight below, rho g L / k for a linear law (the J-shaped law is in fabric_validation.rs).
#[test]
fn hanging_strip_top_strain_is_rho_g_l_over_k() {
    let (length, k, rho) = (1.0, 50.0, 0.15);
    let rest = HangingStrip {
        fabric: Fabric::isotropic_linear(rho, k, 5.0, 1e-6),
        length,
        width: 0.05,
        rows: 101,
    }
    .run()
    .unwrap();
    let expected = rho * 9.81 * length / k;
    let err = (rest.top_strain - expected).abs() / expected;
    println!(
        "top strain {:.6}, rho g L / k = {expected:.6}, error {:.2}% ({} steps)",
        rest.top_strain,
        100.0 * err,
        rest.steps
    );
    assert!(
        err < 0.02,
        "top strain {} vs {expected}: {:.2}% off",
        rest.top_strain,
        100.0 * err
    );
}

/// Runs a cantilever to a tight rest (1 nm per step) and checks it got there.
fn settle(sim: &mut Simulation) -> RestOutcome {
    let out = sim
        .run_to_rest(&RestCriteria {
            max_time_step: None,
            tolerance: 1e-9,
            consecutive_steps: 20,
            max_steps: 5000,
            moving_fraction: 0.0,
        })
        .unwrap();
    assert_eq!(out.reason, StopReason::AtRest, "{out:?}");
    out
}

/// A strip clamped at one end bends under its own weight. For a small load
/// (Gamma = q L^3 / B = 0.29) the tip drop is the Euler-Bernoulli q L^4 / (8 B). The drop
/// must approach the reference as the mesh is refined, and the first-order (Richardson)
/// extrapolation of the two resolutions must land on it. (Since hinges along a clamp bend
/// in their free wing alone, the errors are under 1% at both resolutions.)
#[test]
fn clamped_strip_tip_drop_converges_to_beam_theory() {
    let (overhang, width, rho, b): (f64, f64, f64, f64) = (0.1, 0.02, 0.15, 5e-3);
    let q = rho * 9.81;
    let expected = q * overhang.powi(4) / (8.0 * b);
    let mut drops = Vec::new();
    for cells in [20usize, 40] {
        let d = overhang / cells as f64;
        let (nx, ny) = (cells + 2, (width / d).round() as usize + 1);
        let mesh = GridBuilder::new(nx, ny).spacing(d, d).build().unwrap();
        let g = mesh.grid().unwrap();
        // A near-inextensible membrane: B / (k d^2) ~ 1e-3, as for real cloth at centimetre cells.
        let fabric = Fabric::isotropic_linear(rho, 1e6, 1e4, b);
        let pins = (0..ny).flat_map(|j| [Pin::fixed(g.index(0, j)), Pin::fixed(g.index(1, j))]);
        let mut sim = SimulationBuilder::new(mesh, fabric).pins(pins).build().unwrap();
        let out = settle(&mut sim);
        let drop = -(0..ny)
            .map(|j| sim.positions()[g.index(nx - 1, j)].z)
            .sum::<f64>()
            / ny as f64;
        println!(
            "{cells} cells: tip drop {drop:.6e} m, beam theory {expected:.6e} m ({} steps)",
            out.steps
        );
        drops.push(drop);
    }
    let errors: Vec<f64> = drops.iter().map(|d| (d - expected) / expected).collect();
    let extrapolated = 2.0 * drops[1] - drops[0];
    println!("relative errors {errors:?}, extrapolated {extrapolated:.6e}");
    assert!(
        errors.iter().all(|e| e.abs() < 0.08),
        "tip drops {drops:?} vs {expected}"
    );
    assert!(
        errors[1].abs() < 0.6 * errors[0].abs(),
        "no convergence: {errors:?}"
    );
    assert!(
        (extrapolated - expected).abs() < 0.01 * expected,
        "extrapolated {extrapolated} vs {expected}"
    );
}

/// Bending across the warp and across the weft of a grid with non-square cells both
/// come out at their own rigidity (the calibration treats the two directions apart).
#[test]
fn anisotropic_cells_and_rigidity_bend_at_their_own_rigidity() {
    let (rho, length, width): (f64, f64, f64) = (0.15, 0.1, 0.02);
    let q = rho * 9.81;
    for (along_warp, b_warp, b_weft) in [(true, 5e-3, 2.5e-3), (false, 5e-3, 2.5e-3)] {
        // Cells of 2.5 mm along the strip and 5 mm across it, whichever thread it follows.
        let (du, dv) = if along_warp {
            (0.0025, 0.005)
        } else {
            (0.005, 0.0025)
        };
        let (cells_u, cells_v) = if along_warp {
            ((length / du).round() as usize, (width / dv).round() as usize)
        } else {
            ((width / du).round() as usize, (length / dv).round() as usize)
        };
        let mesh = GridBuilder::new(
            cells_u + 1 + along_warp as usize,
            cells_v + 1 + !along_warp as usize,
        )
        .spacing(du, dv)
        .build()
        .unwrap();
        let g = mesh.grid().unwrap();
        let mut fabric = Fabric::isotropic_linear(rho, 1e6, 1e4, b_warp);
        fabric.bending.weft = b_weft;
        let b = if along_warp { b_warp } else { b_weft };
        let pins: Vec<Pin> = if along_warp {
            (0..g.ny)
                .flat_map(|j| [Pin::fixed(g.index(0, j)), Pin::fixed(g.index(1, j))])
                .collect()
        } else {
            (0..g.nx)
                .flat_map(|i| [Pin::fixed(g.index(i, 0)), Pin::fixed(g.index(i, 1))])
                .collect()
        };
        let mut sim = SimulationBuilder::new(mesh, fabric).pins(pins).build().unwrap();
        settle(&mut sim);
        let tip: Vec<f64> = if along_warp {
            (0..g.ny)
                .map(|j| -sim.positions()[g.index(g.nx - 1, j)].z)
                .collect()
        } else {
            (0..g.nx)
                .map(|i| -sim.positions()[g.index(i, g.ny - 1)].z)
                .collect()
        };
        let drop = tip.iter().sum::<f64>() / tip.len() as f64;
        let expected = q * length.powi(4) / (8.0 * b);
        println!(
            "along warp {along_warp}: drop {drop:.5e}, beam {expected:.5e}, kappa {:?}",
            sim.bending_calibration()
        );
        // The discretisation of the 40-cell case above: within 6%.
        assert!(
            (drop - expected).abs() < 0.06 * expected,
            "along warp {along_warp}: {drop} vs {expected}"
        );
    }
}

/// Uniform stretch of a grid reads back as the same strain in every metric.
#[test]
fn strain_metrics_read_a_known_stretch() {
    let mesh = GridBuilder::new(7, 5).size(0.3, 0.2).build().unwrap();
    let x: Vec<Vec3> = mesh
        .uv()
        .iter()
        .map(|p| Vec3::new(1.1 * p.x, 0.0, -1.05 * p.y))
        .collect();
    let report = cloth::StrainReport::new(&mesh, &x);
    assert!((report.max_warp - 10.0).abs() < 1e-9 && (report.p99_warp - 10.0).abs() < 1e-9);
    assert!((report.max_weft - 5.0).abs() < 1e-9 && (report.p99_weft - 5.0).abs() < 1e-9);
    let grid = cloth::GridStretch::new(&mesh, &x).unwrap();
    assert!((grid.horizontal - 10.0).abs() < 1e-9 && (grid.vertical - 5.0).abs() < 1e-9);
    let _ = SolverSettings::default();
}
