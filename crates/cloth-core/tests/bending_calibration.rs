//! The hinge stiffness calibration: a property of the cells, not of the resolution, and
//! continuous in the rigidities.

use cloth_core::energy::bending::calibration;
use cloth_core::{BendingRigidity, GridBuilder, GridDiagonals};

#[test]
fn grid_calibration_depends_on_the_cells_not_the_resolution() {
    for diagonals in [GridDiagonals::Alternating, GridDiagonals::Uniform] {
        let rigidity = BendingRigidity::isotropic(1e-5);
        let k: Vec<[f64; 2]> = [(6, 0.01), (40, 0.01), (40, 0.002)]
            .iter()
            .map(|&(n, d)| {
                let mesh = GridBuilder::new(n, n)
                    .spacing(d, d)
                    .diagonals(diagonals)
                    .build()
                    .unwrap();
                calibration(&mesh, &rigidity)
            })
            .collect();
        let same = |a: [f64; 2], b: [f64; 2]| (0..2).all(|d| (a[d] - b[d]).abs() < 1e-9 * a[d]);
        assert!(k.windows(2).all(|w| same(w[0], w[1])), "{diagonals:?}: {k:?}");
        // Square cells: warp and weft alike, and relaxation makes the hinges need more
        // stiffness than an imposed cylinder (factor 1) suggests.
        assert!((k[0][0] - k[0][1]).abs() < 1e-9 && k[0][0] > 1.1, "{k:?}");
    }
    // Non-square cells: the two directions differ.
    let mesh = GridBuilder::new(20, 20).spacing(0.0025, 0.005).build().unwrap();
    let k = calibration(&mesh, &BendingRigidity::isotropic(1e-5));
    assert!((k[0] - k[1]).abs() > 0.1, "{k:?}");
}

#[test]
fn calibration_is_continuous_when_one_direction_has_no_rigidity() {
    for diagonals in [GridDiagonals::Alternating, GridDiagonals::Uniform] {
        let mesh = GridBuilder::new(10, 10).diagonals(diagonals).build().unwrap();
        let with = |weft: f64| {
            calibration(
                &mesh,
                &BendingRigidity {
                    warp: 1e-5,
                    weft,
                    bias: None,
                },
            )[0]
        };
        let (zero, tiny) = (with(0.0), with(1e-16));
        assert!(
            (zero - tiny).abs() < 1e-3 * tiny,
            "{diagonals:?}: {zero} vs {tiny}"
        );
        assert!(zero > 1.0, "{diagonals:?}: {zero}");
    }
}
