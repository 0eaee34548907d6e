//! Bodies: parameter errors that name the body and the field, poses and motion.

use cloth_collide::{Bodies, Body, BodyError, Motion, TriSurface};
use cloth_core::math::Vec3;
use cloth_core::{Collider, ParticlePath, Proximity};
use nalgebra::{Isometry3, Translation3, Unit, UnitQuaternion};

fn ball() -> Body {
    Body::new("ball", TriSurface::icosphere(0.5, 2).unwrap())
}

/// The error names the body and the field, and the message says both.
fn assert_names(err: BodyError, field: &str) {
    assert_eq!(err.body, "ball");
    assert_eq!(err.name, field);
    let message = err.to_string();
    assert!(message.contains("`ball`"), "{message}");
    assert!(message.contains(&format!("`{field}`")), "{message}");
}

#[test]
fn thickness_must_be_positive_and_finite() {
    for bad in [0.0, -1e-3, f64::NAN, f64::INFINITY] {
        assert_names(ball().with_thickness(bad).unwrap_err(), "thickness");
    }
    assert_eq!(ball().with_thickness(2e-3).unwrap().thickness(), 2e-3);
}

#[test]
fn friction_must_be_non_negative_and_may_be_infinite() {
    for bad in [-0.1, f64::NAN, f64::NEG_INFINITY] {
        assert_names(ball().with_friction(bad).unwrap_err(), "friction");
    }
    assert_eq!(ball().friction(), None, "the fabric's coefficient unless set");
    assert_eq!(ball().with_friction(0.0).unwrap().friction(), Some(0.0));
    assert_eq!(
        ball().with_friction(f64::INFINITY).unwrap().friction(),
        Some(f64::INFINITY)
    );
}

#[test]
fn sharp_angle_must_be_positive() {
    for bad in [0.0, -0.5, f64::NAN] {
        assert_names(ball().with_sharp_angle(bad).unwrap_err(), "sharp_angle");
    }
}

#[test]
fn poses_and_motions_must_be_finite() {
    let bad_pose = Isometry3::from_parts(Translation3::new(f64::NAN, 0.0, 0.0), UnitQuaternion::identity());
    assert_names(ball().with_pose(bad_pose).unwrap_err(), "pose");
    let spin = |rate: f64, center: Vec3| Motion::Spin {
        pose: Isometry3::identity(),
        center,
        axis: Unit::new_normalize(Vec3::z()),
        rate,
    };
    assert_names(
        ball().with_motion(spin(f64::NAN, Vec3::zeros())).unwrap_err(),
        "rate",
    );
    assert_names(
        ball()
            .with_motion(spin(1.0, Vec3::new(0.0, f64::INFINITY, 0.0)))
            .unwrap_err(),
        "center",
    );
    let linear = Motion::Linear {
        pose: Isometry3::identity(),
        velocity: Vec3::new(0.0, 0.0, f64::NAN),
    };
    assert_names(ball().with_motion(linear).unwrap_err(), "velocity");
}

#[test]
fn a_posed_body_is_where_its_pose_puts_it() {
    let pose = Isometry3::translation(1.0, 2.0, 3.0);
    let body = ball().with_pose(pose).unwrap();
    let centre = Vec3::new(1.0, 2.0, 3.0);
    // The icosphere's vertices are on the sphere, its faces inside it.
    let d = body.signed_distance(0.0, &centre);
    assert!((-0.5..-0.45).contains(&d), "centre at {d}");
    let outside = body.signed_distance(0.0, &(centre + Vec3::new(0.0, 0.0, 1.0)));
    assert!((0.5..0.55).contains(&outside), "1 m above the centre: {outside}");
}

#[test]
fn a_moving_body_moves_with_its_motion() {
    let body = ball()
        .with_motion(Motion::Linear {
            pose: Isometry3::identity(),
            velocity: Vec3::new(0.0, 0.0, 2.0),
        })
        .unwrap();
    let probe = Vec3::new(0.0, 0.0, 2.0);
    // At t = 1 the centre has reached the probe.
    assert!(body.signed_distance(0.0, &probe) > 1.4);
    assert!(body.signed_distance(1.0, &probe) < -0.45);
}

/// A trunk-sized block with a hand-sized one beside it, apart.
fn trunk_and_hand() -> Bodies {
    let trunk = TriSurface::cuboid(Vec3::new(0.2, 0.2, 0.2)).unwrap();
    let hand = TriSurface::cuboid(Vec3::new(0.02, 0.04, 0.045))
        .unwrap()
        .transformed(&Isometry3::translation(0.5, 0.0, 0.0));
    Bodies::new(vec![Body::new("body", TriSurface::merged(&[trunk, hand]))])
}

fn is_near(p: Proximity) -> bool {
    matches!(p, Proximity::Near(_))
}

#[test]
fn cloth_passing_thin_parts_meets_only_the_thick_ones() {
    let bodies = trunk_and_hand();
    // Each block has 12 triangles: the hand, under 10 cm every way through, is half the
    // surface.
    let thin = bodies.bodies()[0].thin_fraction();
    assert!((thin - 0.5).abs() < 1e-12, "{thin}");
    // A path through the hand crosses it, unless it passes thin parts.
    let (a, b) = (Vec3::new(0.45, 0.0, 0.0), Vec3::new(0.55, 0.0, 0.0));
    assert!(is_near(bodies.sweep(
        &ParticlePath::new(0.0, a, 0.0, b),
        0.0,
        0.01
    )));
    assert!(!is_near(bodies.sweep_past_thin_parts(
        &ParticlePath::new(0.0, a, 0.0, b),
        0.0,
        0.01
    )));
    // A path into the trunk crosses it either way.
    let (a, b) = (Vec3::new(0.25, 0.0, 0.0), Vec3::new(0.15, 0.0, 0.0));
    for p in [
        bodies.sweep(&ParticlePath::new(0.0, a, 0.0, b), 0.0, 0.01),
        bodies.sweep_past_thin_parts(&ParticlePath::new(0.0, a, 0.0, b), 0.0, 0.01),
    ] {
        match p {
            Proximity::Near(hit) => assert!(hit.crossed && (hit.point.x - 0.2).abs() < 1e-9, "{hit:?}"),
            Proximity::Far { .. } => panic!("the trunk was not met"),
        }
    }
    // A body with no thin part is all thick.
    let trunk = Body::new("trunk", TriSurface::cuboid(Vec3::new(0.2, 0.2, 0.2)).unwrap());
    assert_eq!(trunk.thin_fraction(), 0.0);
}

#[test]
fn a_thinned_layer_is_thin_on_a_broad_curve_and_stays_thick_on_a_tight_one() {
    // The floor and the edge must be positive, the floor at most the thickness (3 mm).
    for bad in [0.0, -1e-3, 4e-3, f64::NAN] {
        assert_names(
            ball().with_thinned_layer(0.015, bad).unwrap_err(),
            "min_thickness",
        );
    }
    for bad in [0.0, f64::INFINITY] {
        assert_names(ball().with_thinned_layer(bad, 1e-3).unwrap_err(), "edge_length");
    }
    // A ball of 50 cm: an edge of 1.5 cm dips 0.06 mm below its ends, so the layer is
    // the floor and that. A particle 2 mm out is in the layer of the uniform 3 mm but
    // clear of the thinned one, by the 2 mm less the layer there.
    let broad = Body::new("ball", TriSurface::icosphere(0.5, 5).unwrap());
    let dip = 0.015f64.powi(2) / (8.0 * 0.5);
    let x = Vec3::new(0.0, 0.0, 0.502);
    let gap = |body: Body| match Bodies::new(vec![body]).sweep(&ParticlePath::still(0.0, x), 0.0, 0.01) {
        Proximity::Near(p) => p.gap(),
        far => panic!("{far:?}"),
    };
    let d = broad.signed_distance(0.0, &x);
    assert!((gap(broad.clone()) - (d - 0.003)).abs() < 1e-12);
    let thinned = broad.clone().with_thinned_layer(0.015, 1e-3).unwrap();
    assert!(
        (thinned.min_thickness() - 1e-3 - dip).abs() < 0.05 * dip,
        "{}",
        thinned.min_thickness()
    );
    let layer = d - gap(thinned.clone());
    assert!((layer - 1e-3 - dip).abs() < 0.05 * dip, "{layer}");
    // The thickness set afterwards is the new ceiling, the layer made again under it.
    let ceiling = thinned.with_thickness(1.02e-3).unwrap();
    assert_eq!(ceiling.thickness(), 1.02e-3);
    assert_eq!(ceiling.min_thickness(), 1.02e-3);
    // A ball of 1 cm: the dip (2.8 mm) and the floor are over the 3 mm, which holds.
    let tight = Body::new("ball", TriSurface::icosphere(0.01, 3).unwrap())
        .with_thinned_layer(0.015, 1e-3)
        .unwrap();
    assert_eq!(tight.min_thickness(), 0.003);
}
