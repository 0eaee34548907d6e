//! Fabric parameters: KES-F and source conversions, the preset library, and bad input.

use cloth::fabric::kes::{GF_CM2_PER_CM, GF_CM_PER_CM2, GF_PER_CM, GF_PER_CM_DEGREE};
use cloth::presets::{FabricLibrary, PresetError, PresetForm};
use cloth::{
    BendingLaw, Fabric, GridBuilder, KesDirection, KesMeasurement, ParamError, SourceCoefficients, TensileLaw,
};

fn direction(emt: f64, lt: f64, g: f64, b: f64) -> KesDirection {
    KesDirection {
        emt,
        lt,
        wt: lt * 500.0 * emt / 100.0 / 2.0,
        rt: Some(60.0),
        g,
        two_hg: Some(1.0),
        two_hg5: Some(2.5),
        b,
        two_hb: Some(0.05),
    }
}

fn record() -> KesMeasurement {
    KesMeasurement {
        w: 20.0,
        t: 0.6,
        miu: Some(0.22),
        warp: direction(5.0, 0.7, 1.0, 0.12),
        weft: direction(8.0, 0.6, 0.8, 0.08),
    }
}

/// Energy under a tensile law from 0 to `strain`, by Simpson's rule on its tension.
fn energy_by_quadrature(law: &TensileLaw, strain: f64) -> f64 {
    let n = 2000;
    let h = strain / n as f64;
    (0..=n)
        .map(|k| {
            let w = if k == 0 || k == n {
                1.0
            } else if k % 2 == 1 {
                4.0
            } else {
                2.0
            };
            w * law.extension(k as f64 * h).tension
        })
        .sum::<f64>()
        * h
        / 3.0
}

#[test]
fn unit_conversions_are_those_of_fabrics_md() {
    // fabrics.md: 1 gf*cm^2/cm = 9.807e-5 N*m, 1 gf/(cm*deg) = 56.19 N/m per radian,
    // 1 gf/cm = 0.9807 N/m, 1 gf*cm/cm^2 = 0.9807 J/m^2.
    assert!((GF_CM2_PER_CM - 9.807e-5).abs() < 1e-8);
    assert!((GF_PER_CM_DEGREE - 56.19).abs() < 5e-3);
    assert!((GF_PER_CM - 0.9807).abs() < 1e-4 && (GF_CM_PER_CM2 - 0.9807).abs() < 1e-4);
}

#[test]
fn kes_record_converts_to_si_and_its_curves_pass_through_emt_with_energy_wt() {
    let kes = record();
    let out = kes.to_fabric().unwrap();
    let f = &out.fabric;
    assert!(
        (f.area_density - 0.20).abs() < 1e-12,
        "W 20 mg/cm^2 is 0.2 kg/m^2"
    );
    assert!((f.thickness - 0.6e-3).abs() < 1e-15);
    assert_eq!(f.friction, 0.22, "MIU is the friction coefficient");
    assert!((f.bending.warp - 0.12 * 9.80665e-5).abs() < 1e-12);
    assert!((f.bending.weft - 0.08 * 9.80665e-5).abs() < 1e-12);
    assert!(
        (f.shear_modulus - 0.9 * GF_PER_CM_DEGREE).abs() < 1e-9,
        "mean of the two G"
    );
    for (law, d) in [(&f.warp, &kes.warp), (&f.weft, &kes.weft)] {
        let emt = d.emt / 100.0;
        let end = law.extension(emt);
        assert!((end.tension - 500.0 * GF_PER_CM).abs() < 1e-9, "{law:?}");
        let wt = d.wt * GF_CM_PER_CM2;
        assert!((end.energy - wt).abs() < 1e-9 * wt, "{} vs {wt}", end.energy);
        assert!((energy_by_quadrature(law, emt) - wt).abs() < 1e-6 * wt);
        // LT < 1: a J-shaped power law, 2/LT - 1.
        match law {
            TensileLaw::PowerLaw { exponent, .. } => assert!((exponent - (2.0 / d.lt - 1.0)).abs() < 1e-12),
            other => panic!("{other:?}"),
        }
    }
    // Anisotropy survives: the weft is the more extensible direction.
    assert!(f.weft.strain_at(100.0) > f.warp.strain_at(100.0));
    let unused: Vec<&str> = out.unused.iter().map(|u| u.field).collect();
    assert_eq!(
        unused,
        [
            "warp.RT",
            "warp.2HG",
            "warp.2HG5",
            "warp.2HB",
            "weft.RT",
            "weft.2HG",
            "weft.2HG5",
            "weft.2HB"
        ]
    );
}

#[test]
fn a_kes_curve_stiffer_at_the_start_is_two_segments_with_the_same_energy() {
    let mut kes = record();
    kes.warp = direction(5.0, 1.2, 1.0, 0.12);
    let f = kes.to_fabric().unwrap().fabric;
    let TensileLaw::PiecewiseLinear { ref points } = f.warp else {
        panic!("{:?}", f.warp)
    };
    assert_eq!(points.len(), 2);
    let end = f.warp.extension(0.05);
    assert!((end.tension - 500.0 * GF_PER_CM).abs() < 1e-9);
    assert!((end.energy - kes.warp.wt * GF_CM_PER_CM2).abs() < 1e-9);
    kes.warp = direction(5.0, 1.6, 1.0, 0.12);
    let err = kes.to_fabric().unwrap_err();
    assert!(err.to_string().contains("warp.LT"), "{err}");
}

#[test]
fn inconsistent_or_impossible_kes_values_name_the_field() {
    let mut kes = record();
    kes.weft.lt = 0.8; // WT says 0.6
    let err = kes.to_fabric().unwrap_err();
    assert!(
        matches!(err, ParamError::Inconsistent { name: "weft.LT", .. }),
        "{err}"
    );
    assert!(err.to_string().contains("weft.WT"), "{err}");
    for (mutate, field) in [
        (
            Box::new(|k: &mut KesMeasurement| k.w = 0.0) as Box<dyn Fn(&mut KesMeasurement)>,
            "W",
        ),
        (Box::new(|k: &mut KesMeasurement| k.t = -1.0), "T"),
        (Box::new(|k: &mut KesMeasurement| k.warp.emt = 0.0), "warp.EMT"),
        (Box::new(|k: &mut KesMeasurement| k.weft.b = -0.1), "weft.B"),
        (Box::new(|k: &mut KesMeasurement| k.warp.g = f64::NAN), "warp.G"),
        (Box::new(|k: &mut KesMeasurement| k.miu = Some(-0.2)), "MIU"),
    ] {
        let mut kes = record();
        mutate(&mut kes);
        let err = kes.to_fabric().unwrap_err();
        assert!(err.to_string().contains(&format!("`{field}`")), "{field}: {err}");
    }
}

/// The source's coefficients: its hinge energy `mu_b cos^2(theta/2)` is `k (1 - cos psi)`
/// with `k = mu_b / 2`, which is what the hinges of a square grid get (before the
/// calibration) from B = mu_b / 2; its shear `mu_s (l1 l2 / 2) phi_deg^2` is G = 2 mu_s
/// (180/pi)^2 per radian.
#[test]
fn source_coefficients_give_the_source_hinge_and_shear_energies() {
    let c = SourceCoefficients::COTTON;
    let f = Fabric::from_source(c, 0.15, TensileLaw::Linear { stiffness: 8000.0 });
    assert_eq!(f.bending_law, BendingLaw::SourceCosine);
    assert!((f.bending.warp - 1.07e-5).abs() < 1e-18 && f.bending.weft == f.bending.warp);
    let mesh = GridBuilder::new(5, 5).spacing(0.003, 0.003).build().unwrap();
    let k = cloth::energy::bending::hinge_stiffnesses(&mesh, &f.bending, [1.0, 1.0]);
    let uv = mesh.uv();
    let along_threads: Vec<f64> = mesh
        .hinges()
        .iter()
        .zip(&k)
        .filter(|(h, _)| {
            let e = uv[h.edge[1]] - uv[h.edge[0]];
            e.x.abs() < 1e-12 || e.y.abs() < 1e-12
        })
        .map(|(_, &k)| k)
        .collect();
    assert!(!along_threads.is_empty());
    for k in along_threads {
        assert!((k - c.mu_b / 2.0).abs() < 1e-15, "{k}");
    }
    // One degree of shear on a unit rest area: mu_s J.
    let phi = 1f64.to_radians();
    assert!((0.5 * f.shear_modulus * phi * phi - c.mu_s).abs() < 1e-9);
}

#[test]
fn builtin_presets_cover_the_required_fabrics_with_their_origins() {
    let library = FabricLibrary::builtin();
    let names: Vec<&str> = library.names().collect();
    for required in [
        "source_cotton",
        "silk",
        "wool_suiting",
        "polyester_lining",
        "denim",
        "knit_jersey",
    ] {
        assert!(names.contains(&required), "{required} missing from {names:?}");
    }
    let wang: Vec<_> = library
        .presets()
        .iter()
        .filter(|p| p.name.starts_with("wang_"))
        .collect();
    assert_eq!(wang.len(), 10, "the ten measured fabrics of fabrics.md");
    for p in library.presets() {
        p.fabric.validate().unwrap();
        assert!(p.origin.len() > 40, "{}: origin `{}`", p.name, p.origin);
        assert!(!p.description.is_empty());
        match p.form {
            PresetForm::Kes => assert!(!p.unused.is_empty(), "{}: hysteresis reported", p.name),
            _ => assert!(p.unused.is_empty()),
        }
    }
    // The measured values, read back: Wang's denim.
    let denim = library.fabric("wang_black_denim").unwrap();
    assert!((denim.area_density - 0.324).abs() < 1e-12);
    assert_eq!(denim.warp, TensileLaw::Linear { stiffness: 411.0 });
    assert!((denim.bending.warp - 97e-6).abs() < 1e-12 && (denim.bending.weft - 64.2e-6).abs() < 1e-12);
    assert_eq!(denim.bending.bias, Some(73.4e-6));
    // Real anisotropy wherever the data differ.
    for p in library.presets().iter().filter(|p| p.name != "source_cotton") {
        let f = &p.fabric;
        assert!(
            (f.warp.strain_at(50.0) / f.weft.strain_at(50.0) - 1.0).abs() > 0.005
                || (f.bending.warp / f.bending.weft - 1.0).abs() > 0.005,
            "{} is isotropic",
            p.name
        );
    }
    let source = library.fabric("source_cotton").unwrap();
    assert_eq!(source.bending_law, BendingLaw::SourceCosine);
    assert!((source.shear_modulus - SourceCoefficients::COTTON.shear_modulus()).abs() < 1e-9);
}

fn parse(text: &str) -> Result<FabricLibrary, PresetError> {
    FabricLibrary::from_toml(text, "my_fabrics.toml")
}

const SI: &str = r#"
[test_fabric]
description = "a test"
origin = "made up"
[test_fabric.si]
area_density = 0.2
warp = { law = "linear", stiffness = 500.0 }
weft = { law = "linear", stiffness = 400.0 }
compression_warp = 50.0
compression_weft = 40.0
shear_modulus = 20.0
bending = { warp = 1e-5, weft = 8e-6 }
"#;

#[test]
fn bad_presets_name_the_file_the_fabric_and_the_field() {
    let ok = parse(SI).unwrap();
    assert_eq!(
        ok.fabric("test_fabric").unwrap().thickness,
        cloth::fabric::DEFAULT_THICKNESS
    );
    for (from, to, field) in [
        ("stiffness = 500.0", "stiffness = 0.0", "`warp`"),
        ("stiffness = 400.0", "stiffness = -400.0", "`weft`"),
        ("area_density = 0.2", "area_density = -0.2", "`area_density`"),
        ("area_density = 0.2", "area_density = 0.0", "`area_density`"),
        ("shear_modulus = 20.0", "shear_modulus = -1.0", "`shear_modulus`"),
        (
            "compression_warp = 50.0",
            "compression_warp = 0.0",
            "`compression_warp`",
        ),
    ] {
        let text = SI.replace(from, to);
        assert_ne!(text, SI);
        let err = parse(&text).unwrap_err().to_string();
        assert!(
            err.contains("my_fabrics.toml") && err.contains("test_fabric") && err.contains(field),
            "{err}"
        );
    }
    // Unknown and missing fields, with the line.
    let err = parse(&SI.replace("shear_modulus", "sheer_modulus"))
        .unwrap_err()
        .to_string();
    assert!(err.contains("sheer_modulus") && err.contains("line"), "{err}");
    let err = parse(&SI.replace("area_density = 0.2\n", ""))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("area_density") && err.contains("my_fabrics.toml"),
        "{err}"
    );
    // Two forms, or none.
    let err = parse(&format!("{SI}\n[test_fabric.source]\nmu_b = 1e-5\nmu_s = 1.0\narea_density = 0.1\ntensile = {{ law = \"linear\", stiffness = 1.0 }}\n"))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("exactly one") && err.contains("si and source"),
        "{err}"
    );
}

#[test]
fn a_kes_preset_missing_a_field_names_it() {
    let library =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/fabrics.toml")).unwrap();
    // The silk's warp loses its WT.
    let start = library.find("[silk.kes.warp]").unwrap();
    let wt = start + library[start..].find("WT = ").unwrap();
    let end = wt + library[wt..].find('\n').unwrap() + 1;
    let text = format!("{}{}", &library[..wt], &library[end..]);
    let err = parse(&text).unwrap_err().to_string();
    assert!(
        err.contains("missing field `WT`") && err.contains("line"),
        "{err}"
    );
}

#[test]
fn an_unknown_preset_lists_the_known_ones() {
    let err = FabricLibrary::builtin().fabric("satin").unwrap_err();
    let message = err.to_string();
    assert!(message.contains("`satin`"), "{message}");
    for name in ["silk", "denim", "source_cotton", "wang_royal_target"] {
        assert!(message.contains(name), "{message}");
    }
    let PresetError::Unknown { known, .. } = err else {
        panic!("{err:?}")
    };
    assert_eq!(known.len(), FabricLibrary::builtin().presets().len());
}

#[test]
fn fabric_parameters_out_of_range_name_the_field() {
    let base = Fabric::cotton_like();
    let mut f = base.clone();
    f.thickness = 0.0;
    assert!(f.validate().unwrap_err().to_string().contains("`thickness`"));
    let mut f = base.clone();
    f.friction = -0.1;
    assert!(f.validate().unwrap_err().to_string().contains("`friction`"));
    let mut f = base;
    f.friction = f64::INFINITY;
    f.validate().unwrap();
}
