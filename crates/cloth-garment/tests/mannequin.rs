//! The parametric dress form: valid surfaces, the measured girths and widths where they
//! belong, refused measurements named, arms where arms go, and OBJ files (written and
//! shipped) that match the generator.

use std::collections::HashSet;
use std::path::{Path, PathBuf};

use cloth_collide::{SurfaceOptions, TriSurface};
use cloth_garment::mannequin::{ArmMeasurements, Mannequin, MannequinError, Measurements};

fn small() -> Measurements {
    Measurements {
        height: 1.55,
        bust: 0.80,
        waist: 0.63,
        hip: 0.86,
        shoulder_width: 0.36,
        neck_girth: 0.32,
        arms: None,
    }
}

fn large() -> Measurements {
    Measurements {
        height: 1.86,
        bust: 1.14,
        waist: 1.02,
        hip: 1.18,
        shoulder_width: 0.46,
        neck_girth: 0.42,
        arms: None,
    }
}

fn build(m: &Measurements) -> Mannequin {
    Mannequin::new(m).unwrap_or_else(|e| panic!("{m:?}: {e}"))
}

/// V - E + F for a closed triangle mesh, where E = 3F/2: 2 for one sphere-like component.
fn euler_characteristic(s: &TriSurface) -> i64 {
    s.vertices().len() as i64 - s.triangles().len() as i64 / 2
}

fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn default_surfaces_are_closed_single_bodies_with_volume() {
    let plain = build(&Measurements::default());
    assert!(plain.arms().is_empty());
    assert_eq!(
        plain.surfaces().iter().map(|(n, _)| *n).collect::<Vec<_>>(),
        ["torso"]
    );
    let armed = build(&Measurements::default().with_arms());
    let names: Vec<&str> = armed.surfaces().iter().map(|(n, _)| *n).collect();
    assert_eq!(names, ["torso", "left_arm", "right_arm"]);
    for (name, surface) in armed.surfaces() {
        // Building again from the raw mesh re-runs every check (closed, manifold, outward).
        let again = TriSurface::new(
            surface.vertices().to_vec(),
            surface.triangles().to_vec(),
            &SurfaceOptions::default(),
        );
        assert!(again.is_ok(), "{name}: {again:?}");
        assert!(surface.volume() > 0.0, "{name}: volume {}", surface.volume());
        assert_eq!(
            euler_characteristic(surface),
            2,
            "{name} is not one sphere-like piece"
        );
    }
    let triangles = armed.torso().triangles().len();
    assert!(
        (4_000..=20_000).contains(&triangles),
        "torso has {triangles} triangles"
    );
    // A standing woman's torso from thigh to neck holds some 35-45 litres.
    let volume = armed.torso().volume();
    assert!((0.030..0.050).contains(&volume), "torso volume {volume} m^3");
    let bodies = armed.bodies();
    let body_names: Vec<&str> = bodies.iter().map(|b| b.name()).collect();
    assert_eq!(body_names, names);
}

#[test]
fn form_is_mirror_symmetric_in_x() {
    let mannequin = build(&Measurements::default().with_arms());
    let key = |x: f64, y: f64, z: f64| [x, y, z].map(|c| (c * 1e7).round() as i64);
    let merged = mannequin.merged();
    let vertices = merged.vertices();
    let set: HashSet<[i64; 3]> = vertices.iter().map(|p| key(p.x, p.y, p.z)).collect();
    for p in vertices {
        assert!(set.contains(&key(-p.x, p.y, p.z)), "no mirror image of {p:?}");
    }
}

#[test]
fn girths_match_the_measurements() {
    for m in [Measurements::default(), small(), large()] {
        let mannequin = build(&m);
        let lm = mannequin.landmarks();
        for (name, z, target) in mannequin.measured_girths() {
            let girth = mannequin.girth_at(z);
            assert!(
                relative(girth, target) < 0.005,
                "{name} of {m:?}: {girth} vs {target}"
            );
        }
        // The waist is the narrowest place between the hip and the bust, the hip and the
        // bust the fullest around them.
        let waist = mannequin.girth_at(lm.waist_z);
        for z in [
            lm.hip_z + 0.02,
            lm.waist_z - 0.03,
            lm.waist_z + 0.03,
            lm.underbust_z,
        ] {
            assert!(
                mannequin.girth_at(z) > waist,
                "{m:?}: girth at {z} under the waist's"
            );
        }
        for (z, full) in [(lm.hip_z, m.hip), (lm.bust_z, m.bust)] {
            for dz in [-0.03, 0.03] {
                let g = mannequin.girth_at(z + dz);
                assert!(g < full * 1.001, "{m:?}: girth {g} at {} over {full}", z + dz);
            }
        }
        assert_eq!(mannequin.girth_at(lm.top_z + 0.01), 0.0);
        assert_eq!(mannequin.girth_at(lm.bottom_z - 0.01), 0.0);
    }
}

#[test]
fn shoulders_are_the_widest_and_the_form_stands_at_its_height() {
    for m in [Measurements::default(), small(), large()] {
        let mannequin = build(&m);
        let lm = *mannequin.landmarks();
        let torso = mannequin.torso();
        let at_shoulder: Vec<f64> = torso
            .vertices()
            .iter()
            .filter(|p| (p.z - lm.shoulder_z).abs() < 1e-12)
            .map(|p| p.x)
            .collect();
        assert!(!at_shoulder.is_empty(), "no ring at the shoulder level");
        let across = at_shoulder.iter().cloned().fold(f64::MIN, f64::max)
            - at_shoulder.iter().cloned().fold(f64::MAX, f64::min);
        assert!(
            relative(across, m.shoulder_width) < 0.02,
            "{m:?}: {across} across the shoulders"
        );
        assert!(relative(2.0 * lm.shoulder_x, m.shoulder_width) < 1e-12);
        let (lo, hi) = torso.bounding_box();
        assert!(
            relative(hi.x - lo.x, m.shoulder_width) < 0.02,
            "{m:?}: widest {}",
            hi.x - lo.x
        );
        assert!((hi.z - lm.top_z).abs() < 1e-9 && (lo.z - lm.bottom_z).abs() < 1e-9);
        let h = m.height;
        assert!(
            (0.85 * h..0.90 * h).contains(&lm.top_z),
            "top {} for height {h}",
            lm.top_z
        );
        assert!(
            (0.40 * h..0.46 * h).contains(&lm.bottom_z),
            "bottom {} for height {h}",
            lm.bottom_z
        );
        let levels = [
            lm.bottom_z,
            lm.crotch_z,
            lm.hip_z,
            lm.waist_z,
            lm.underbust_z,
            lm.bust_z,
            lm.armpit_z,
            lm.shoulder_z,
            lm.neck_z,
            lm.top_z,
        ];
        assert!(levels.windows(2).all(|w| w[0] < w[1]), "{lm:?}");
        // Centred on the z axis, facing -y: the front-most point is the bust, the back-most
        // the seat.
        assert!((hi.x + lo.x).abs() < 1e-9);
        let by_y = |a: &&cloth_core::math::Vec3, b: &&cloth_core::math::Vec3| a.y.total_cmp(&b.y);
        let front = torso.vertices().iter().min_by(by_y).map_or(f64::NAN, |p| p.z);
        let back = torso.vertices().iter().max_by(by_y).map_or(f64::NAN, |p| p.z);
        assert!(
            (front - lm.bust_z).abs() < 0.03,
            "front-most point at z = {front}"
        );
        assert!((back - lm.hip_z).abs() < 0.05, "back-most point at z = {back}");
    }
}

fn expect_field(m: Measurements, field: &str) {
    match Mannequin::new(&m) {
        Ok(_) => panic!("{m:?} was accepted, expected an error about `{field}`"),
        Err(e) => {
            assert_eq!(e.field(), Some(field), "{e}");
            assert!(
                e.to_string().contains(field),
                "message does not name `{field}`: {e}"
            );
        }
    }
}

#[test]
fn bad_measurements_are_refused_by_name() {
    let ok = Measurements::default();
    let arms = ArmMeasurements::default();
    expect_field(Measurements { bust: -0.9, ..ok }, "bust");
    expect_field(
        Measurements {
            waist: f64::NAN,
            ..ok
        },
        "waist",
    );
    expect_field(Measurements { height: 0.0, ..ok }, "height");
    expect_field(
        Measurements {
            hip: f64::INFINITY,
            ..ok
        },
        "hip",
    );
    expect_field(Measurements { height: 3.5, ..ok }, "height");
    expect_field(
        Measurements {
            waist: 1.25 * ok.hip,
            ..ok
        },
        "waist",
    );
    expect_field(
        Measurements {
            shoulder_width: 0.10,
            ..ok
        },
        "shoulder_width",
    );
    expect_field(
        Measurements {
            neck_girth: 0.0,
            ..ok
        },
        "neck_girth",
    );
    let with = |a: ArmMeasurements| Measurements { arms: Some(a), ..ok };
    expect_field(with(ArmMeasurements { length: -1.0, ..arms }), "arms.length");
    expect_field(
        with(ArmMeasurements {
            wrist_girth: 0.4,
            ..arms
        }),
        "arms.wrist_girth",
    );
    expect_field(
        with(ArmMeasurements {
            angle_degrees: 120.0,
            ..arms
        }),
        "arms.angle_degrees",
    );
    expect_field(
        with(ArmMeasurements {
            angle_degrees: f64::NAN,
            ..arms
        }),
        "arms.angle_degrees",
    );
    assert!(ok.validate().is_ok() && ok.with_arms().validate().is_ok());
    assert!(matches!(
        Mannequin::with_resolution(&ok, 40, 30),
        Err(MannequinError::Resolution { name: "segments", .. })
    ));
    assert!(matches!(
        Mannequin::with_resolution(&ok, 3, 32),
        Err(MannequinError::Resolution { name: "rings", .. })
    ));
}

#[test]
fn coarser_resolution_keeps_the_measurements() {
    let m = Measurements::default().with_arms();
    let coarse = Mannequin::with_resolution(&m, 30, 32).unwrap_or_else(|e| panic!("{e}"));
    let fine = build(&m);
    assert!(coarse.torso().triangles().len() < fine.torso().triangles().len() / 2);
    let lm = coarse.landmarks();
    for (z, target) in [(lm.bust_z, m.bust), (lm.waist_z, m.waist), (lm.hip_z, m.hip)] {
        assert!(relative(coarse.girth_at(z), target) < 1e-9);
    }
    assert!(relative(coarse.torso().volume(), fine.torso().volume()) < 0.02);
}

#[test]
fn arms_hang_down_and_out_from_the_shoulders() {
    for m in [Measurements::default().with_arms(), large().with_arms()] {
        let mannequin = build(&m);
        let lm = *mannequin.landmarks();
        let arms = mannequin.arms();
        assert_eq!(arms.len(), 2);
        let (torso_lo, torso_hi) = mannequin.torso().bounding_box();
        for ((arm, side), axis) in arms.iter().zip([1.0, -1.0]).zip(mannequin.arm_axes()) {
            assert_eq!(euler_characteristic(arm), 2);
            assert!(arm.volume() > 0.0);
            let lowest = arm
                .vertices()
                .iter()
                .copied()
                .min_by(|a, b| a.z.total_cmp(&b.z))
                .unwrap_or_else(|| panic!("an arm without vertices"));
            assert!(
                lowest.z < lm.armpit_z,
                "wrist end {lowest:?} not under the armpit"
            );
            assert!(
                side * lowest.x > torso_hi.x.max(-torso_lo.x),
                "wrist end {lowest:?} not outside"
            );
            // It starts inside the torso, at the shoulder: the joint sits under the shoulder
            // point, within the shoulders' width, over the armpit.
            let [x, _, z] = axis.joint;
            assert!(
                side * x > 0.0 && side * x < lm.shoulder_x,
                "joint {:?}",
                axis.joint
            );
            assert!(z > lm.armpit_z && z < lm.shoulder_z, "joint {:?}", axis.joint);
            // The wrist is `length` from the shoulder point.
            let shoulder = [side * lm.shoulder_x, lm.shoulder_y, lm.shoulder_z];
            let arms_m = m.arms.unwrap_or_else(|| panic!("arms were asked for"));
            let reach = (0..3)
                .map(|i| (axis.wrist[i] - shoulder[i]).powi(2))
                .sum::<f64>()
                .sqrt();
            assert!(
                relative(reach, arms_m.length) < 1e-9,
                "wrist {reach} from the shoulder point"
            );
            let angle = (side * (axis.wrist[0] - axis.joint[0])).atan2(axis.joint[2] - axis.wrist[2]);
            assert!((angle.to_degrees() - arms_m.angle_degrees).abs() < 1e-9);
        }
        // Mirror images of each other.
        assert!(relative(arms[0].volume(), arms[1].volume()) < 1e-12);
    }
}

fn temporary(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("cloth-garment-{}-{name}", std::process::id()))
}

#[test]
fn written_obj_reads_back_as_the_same_surfaces() {
    let mannequin = build(&Measurements::default().with_arms());
    let path = temporary("mannequin.obj");
    mannequin
        .write_obj(&path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let read = TriSurface::read(&path, &SurfaceOptions::default());
    let text = std::fs::read_to_string(&path).unwrap_or_default();
    let _ = std::fs::remove_file(&path);
    let read = read.unwrap_or_else(|e| panic!("{e}"));
    let merged = mannequin.merged();
    // The file keeps the surfaces' numbering and their exact coordinates.
    assert_eq!(read.vertices(), merged.vertices());
    assert_eq!(read.triangles(), merged.triangles());
    let objects: Vec<&str> = text.lines().filter_map(|l| l.strip_prefix("o ")).collect();
    assert_eq!(objects, ["torso", "left_arm", "right_arm"]);
}

fn asset(file: &str) -> PathBuf {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/bodies")).join(file)
}

/// The shipped files are what the generator makes now; if this fails, regenerate them with
/// `cargo run --release -p cloth-garment --example mannequin`.
#[test]
fn shipped_assets_match_the_generator() {
    for (file, m) in [
        ("mannequin.obj", Measurements::default()),
        ("mannequin_arms.obj", Measurements::default().with_arms()),
    ] {
        let path = asset(file);
        let read = TriSurface::read(&path, &SurfaceOptions::default())
            .unwrap_or_else(|e| panic!("{e} (regenerate with the mannequin example)"));
        let generated = build(&m).merged();
        assert_eq!(
            read.vertices().len(),
            generated.vertices().len(),
            "{file} is stale"
        );
        assert_eq!(
            read.triangles().len(),
            generated.triangles().len(),
            "{file} is stale"
        );
        let (a, b) = (read.volume(), generated.volume());
        assert!(relative(a, b) < 1e-9, "{file} is stale: volume {a} vs {b}");
        let size = std::fs::metadata(&path).map(|md| md.len()).unwrap_or(u64::MAX);
        assert!(size < 1_500_000, "{file} is {size} bytes");
    }
}

/// Bodies at the edges of what validation admits still build, with their girths.
#[test]
fn unusual_but_valid_bodies_build() {
    let apple = Measurements {
        height: 1.60,
        bust: 1.20,
        waist: 1.17,
        hip: 0.98,
        shoulder_width: 0.38,
        neck_girth: 0.42,
        arms: None,
    };
    let narrow = Measurements {
        shoulder_width: 0.15 * 1.68 + 1e-9,
        neck_girth: 0.3 * 1.68,
        ..Measurements::default()
    };
    let tall_man = Measurements {
        height: 2.2,
        bust: 0.98,
        waist: 0.84,
        hip: 0.96,
        shoulder_width: 0.5,
        neck_girth: 0.41,
        arms: None,
    };
    let arms = |angle_degrees: f64| {
        let mut m = Measurements::default().with_arms();
        if let Some(a) = m.arms.as_mut() {
            a.angle_degrees = angle_degrees;
        }
        m
    };
    for m in [apple, narrow, tall_man, arms(10.0), arms(90.0)] {
        let mannequin = build(&m);
        let lm = mannequin.landmarks();
        for (z, target) in [(lm.bust_z, m.bust), (lm.waist_z, m.waist), (lm.hip_z, m.hip)] {
            assert!(relative(mannequin.girth_at(z), target) < 1e-9, "{m:?} at {z}");
        }
        assert_eq!(mannequin.arms().len(), if m.arms.is_some() { 2 } else { 0 });
    }
}

#[test]
fn measurements_read_from_toml_with_defaults() {
    let m: Measurements =
        toml::from_str("bust = 1.0\n[arms]\nangle_degrees = 30.0\n").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(m.bust, 1.0);
    assert_eq!(m.height, Measurements::default().height);
    let arms = m.arms.unwrap_or_else(|| panic!("arms were given"));
    assert_eq!(arms.angle_degrees, 30.0);
    assert_eq!(arms.length, ArmMeasurements::default().length);
    assert!(toml::from_str::<Measurements>("busts = 1.0").is_err());
}
