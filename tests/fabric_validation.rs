//! Fabrics against physical measurements and exact references: the cantilever against
//! the inextensible elastica, the fixed-angle bending length, the Cusick drape against
//! measured ranges, and a hanging strip with a J-shaped tensile law.

use cloth::presets::FabricLibrary;
use cloth::validation::cantilever::bending_length;
use cloth::validation::{fixed_angle, Cantilever, CusickTest, HangingStrip};
use cloth::{Fabric, TensileLaw};

fn preset(name: &str) -> Fabric {
    FabricLibrary::builtin().fabric(name).unwrap()
}

/// Tip drop / L within 5% of the elastica (shot in `cloth::validation::elastica`) for
/// every Gamma, at two resolutions a factor 2 apart. The fabric's tensile law is a KES
/// power law, so the membrane is soft at rest and stiffens as it stretches.
#[test]
fn cantilever_tip_drop_matches_the_elastica_at_two_resolutions() {
    let fabric = preset("cotton_poplin");
    assert!(matches!(fabric.warp, TensileLaw::PowerLaw { .. }));
    let mut worst: f64 = 0.0;
    for gamma in [0.5, 1.0, 2.0, 4.0, 8.0, 20.0] {
        for cells in [20, 40] {
            let test = Cantilever::at_gamma(fabric.clone(), gamma, cells);
            let rest = test.run().unwrap();
            let (simulated, reference) = (rest.drop / test.overhang, test.reference_drop());
            let error = simulated / reference - 1.0;
            println!(
                "Gamma {gamma:>4}: {cells} cells, drop/L {simulated:.4} vs elastica {reference:.4} ({:+.2}%)",
                100.0 * error
            );
            assert!(
                error.abs() < 0.05,
                "Gamma {gamma}, {cells} cells: {simulated} vs {reference}"
            );
            worst = worst.max(error.abs());
        }
    }
    println!("largest error {:.2}%", 100.0 * worst);
}

/// Peirce's fixed-angle test reads the bending length (B/w)^(1/3) within 5%, along the
/// warp of two fabrics of different rigidity.
#[test]
fn fixed_angle_cantilever_reads_the_bending_length() {
    for name in ["cotton_poplin", "wang_black_denim"] {
        let fabric = preset(name);
        let c = bending_length(&fabric);
        let result = fixed_angle(&fabric, c / 16.0).unwrap();
        let error = result.bending_length / c - 1.0;
        println!(
            "{name}: bending length {:.3} cm from the 41.5 degree overhang, (B/w)^(1/3) = {:.3} cm ({:+.2}%, {} runs)",
            100.0 * result.bending_length,
            100.0 * c,
            100.0 * error,
            result.runs
        );
        assert!(error.abs() < 0.05, "{name}: {result:?} vs {c}");
    }
}

/// The Cusick drape coefficients of the silk-like, cotton-like and denim-like presets
/// land in the measured ranges of fabrics.md, with between 4 and 10 folds. The denim is
/// Wang et al.'s measured one.
#[test]
fn cusick_drape_of_silk_cotton_and_denim_lands_in_the_measured_ranges() {
    for (name, low, high) in [
        ("silk", 20.0, 40.0),
        ("cotton_poplin", 60.0, 76.0),
        ("wang_black_denim", 70.0, 90.0),
    ] {
        let result = CusickTest::new(preset(name)).run().unwrap();
        println!(
            "{name}: drape coefficient {:.1}% (measured {low}-{high}%), {} folds, {} steps",
            result.drape_coefficient, result.folds, result.steps
        );
        assert!(
            (low..=high).contains(&result.drape_coefficient),
            "{name}: {} outside {low}-{high}%",
            result.drape_coefficient
        );
        assert!((4..=10).contains(&result.folds), "{name}: {} folds", result.folds);
    }
}

/// The drape coefficient rises with bending rigidity, the rest of the fabric unchanged.
#[test]
fn cusick_drape_coefficient_rises_with_bending_rigidity() {
    let base = preset("cotton_poplin");
    let coefficients: Vec<f64> = [0.25, 1.0, 4.0]
        .iter()
        .map(|&scale| {
            let mut fabric = base.clone();
            fabric.bending.warp *= scale;
            fabric.bending.weft *= scale;
            let dc = CusickTest::new(fabric).run().unwrap().drape_coefficient;
            println!("B x {scale}: drape coefficient {dc:.1}%");
            dc
        })
        .collect();
    assert!(
        coefficients.windows(2).all(|w| w[1] > w[0] + 5.0),
        "not rising with B: {coefficients:?}"
    );
}

/// A knit jersey hung along its course: the KES power law has exponent 2/LT - 1 = 4.7,
/// so the strain at the top (about 15%) is far from any linear reading of the curve.
#[test]
fn hanging_strip_with_a_j_shaped_law_strains_as_its_inverse_law_says() {
    let fabric = preset("knit_jersey");
    match fabric.weft {
        TensileLaw::PowerLaw { exponent, .. } => assert!(exponent > 4.0, "{exponent}"),
        ref other => panic!("jersey weft is {other:?}"),
    }
    let strip = HangingStrip {
        fabric,
        length: 1.0,
        width: 0.05,
        rows: 101,
    };
    let rest = strip.run().unwrap();
    let error = rest.top_strain / rest.expected_strain - 1.0;
    println!(
        "top strain {:.5} at {:.3} N/m, inverse law {:.5} ({:+.3}%, {} steps)",
        rest.top_strain,
        rest.top_tension,
        rest.expected_strain,
        100.0 * error,
        rest.steps
    );
    assert!(rest.top_strain > 0.05, "{rest:?}");
    assert!(error.abs() < 0.02, "{rest:?}");
}
