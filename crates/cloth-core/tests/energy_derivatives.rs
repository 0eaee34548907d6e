//! Finite-difference checks of every energy: forces against the energy, exact Jacobians
//! against the forces, at random states with stretched, compressed, sheared and folded
//! elements; PSD of the solver's Jacobians; zero net force and torque.

use cloth_core::energy::repulsion::{add_friction_drag, add_repulsion, ContactFrame, RepulsionLaw};
use cloth_core::energy::{
    bending, damping::add_damping, particle, shear::add_shear, stretch::add_stretch, stretch::ThreadLaw,
    HessianMode, Local, TriangleRest,
};
use cloth_core::{math::Vec3, BendingLaw, TensileLaw};
use nalgebra::{DMatrix, Rotation3, Vector2};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

const H: f64 = 1e-6;

fn random_rotation(rng: &mut StdRng) -> Rotation3<f64> {
    let axis = Vec3::new(
        rng.random_range(-1.0..1.0),
        rng.random_range(-1.0..1.0),
        rng.random_range(-1.0..1.0),
    );
    Rotation3::new(axis.normalize() * rng.random_range(0.0..3.0))
}

/// A random rest triangle (a few cm) and a deformed copy: `F = R * [[su, sh], [0, sv]]`
/// plus noise, with `su`, `sv` from compressed (0.7) to stretched (1.3) and shear up to
/// about 30 degrees.
fn random_triangle(rng: &mut StdRng) -> (TriangleRest, [Vec3; 3]) {
    loop {
        let uv: [Vector2<f64>; 3] =
            std::array::from_fn(|_| Vector2::new(rng.random_range(0.0..0.05), rng.random_range(0.0..0.05)));
        let Some(rest) = TriangleRest::new(uv) else {
            continue;
        };
        if rest.area < 2e-4 {
            continue;
        }
        let (su, sv, sh) = (
            rng.random_range(0.7..1.3),
            rng.random_range(0.7..1.3),
            rng.random_range(-0.6..0.6),
        );
        let rot = random_rotation(rng);
        let x = uv.map(|p| {
            let q = Vec3::new(su * p.x + sh * p.y, sv * p.y, 0.0);
            rot * q
                + Vec3::new(
                    rng.random_range(-1e-3..1e-3),
                    rng.random_range(-1e-3..1e-3),
                    rng.random_range(-1e-3..1e-3),
                )
        });
        return (rest, x);
    }
}

/// A random hinge folded by up to +-150 degrees, possibly with stretched faces.
fn random_hinge(rng: &mut StdRng) -> [Vec3; 4] {
    let fold: f64 = rng.random_range(-150f64..150.0).to_radians();
    let (l, w0, w1) = (
        rng.random_range(0.01..0.05),
        rng.random_range(0.005..0.04),
        rng.random_range(0.005..0.04),
    );
    let (s0, s1) = (rng.random_range(-0.02..0.02), rng.random_range(-0.02..0.02));
    let x0 = Vec3::zeros();
    let x1 = Vec3::new(l, 0.0, 0.0);
    let x2 = Vec3::new(l / 2.0 + s0, w0, 0.0);
    let x3 = Vec3::new(l / 2.0 + s1, -w1 * fold.cos(), w1 * fold.sin());
    let rot = random_rotation(rng);
    let shift = Vec3::new(rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0), 0.3);
    [x0, x1, x2, x3].map(|p| rot * p + shift)
}

fn flat<const N: usize>(x: &[Vec3; N]) -> Vec<f64> {
    x.iter().flat_map(|p| [p.x, p.y, p.z]).collect()
}
fn unflat<const N: usize>(q: &[f64]) -> [Vec3; N] {
    std::array::from_fn(|i| Vec3::new(q[3 * i], q[3 * i + 1], q[3 * i + 2]))
}

/// Checks gradient against the energy and the exact Hessian against the gradient.
fn check_derivatives<const N: usize>(
    label: &str,
    x: &[Vec3; N],
    eval: impl Fn(&[Vec3; N], HessianMode) -> Local<N>,
) {
    let local = eval(x, HessianMode::Exact);
    let q = flat(x);
    let grad = flat(&local.grad);
    let gscale = grad.iter().fold(0.0f64, |m, g| m.max(g.abs())).max(1e-300);
    let hess = local.hessian_dense();
    let hscale = hess.amax().max(1e-300);
    for k in 0..3 * N {
        let (mut qp, mut qm) = (q.clone(), q.clone());
        qp[k] += H;
        qm[k] -= H;
        let (lp, lm) = (
            eval(&unflat(&qp), HessianMode::Exact),
            eval(&unflat(&qm), HessianMode::Exact),
        );
        let fd = (lp.energy - lm.energy) / (2.0 * H);
        assert!(
            (fd - grad[k]).abs() <= 1e-5 * gscale,
            "{label}: dE/dq[{k}] = {} but finite differences give {fd}",
            grad[k]
        );
        let (gp, gm) = (flat(&lp.grad), flat(&lm.grad));
        for r in 0..3 * N {
            let fd = (gp[r] - gm[r]) / (2.0 * H);
            assert!(
                (fd - hess[(r, k)]).abs() <= 1e-5 * hscale,
                "{label}: d2E/dq[{r}]dq[{k}] = {} but finite differences give {fd}",
                hess[(r, k)]
            );
        }
    }
    assert!(
        (&hess - hess.transpose()).amax() <= 1e-9 * hscale,
        "{label}: exact Hessian not symmetric"
    );
}

fn assert_psd(label: &str, m: &DMatrix<f64>) {
    let scale = m.amax().max(1e-300);
    assert!(
        (m - m.transpose()).amax() <= 1e-12 * scale,
        "{label}: not symmetric"
    );
    let min = m.clone().symmetric_eigen().eigenvalues.min();
    assert!(
        min >= -1e-9 * scale,
        "{label}: eigenvalue {min} < 0 (scale {scale})"
    );
}

/// Rigid-motion invariance: zero net force and zero net torque.
fn assert_balanced<const N: usize>(label: &str, x: &[Vec3; N], local: &Local<N>) {
    let scale = local
        .grad
        .iter()
        .map(|g| g.norm())
        .fold(0.0, f64::max)
        .max(1e-300);
    let force: Vec3 = local.grad.iter().sum();
    let torque: Vec3 = x.iter().zip(&local.grad).map(|(p, g)| p.cross(g)).sum();
    let lever = x.iter().map(|p| p.norm()).fold(0.0, f64::max);
    assert!(force.norm() <= 1e-9 * scale, "{label}: net force {force}");
    assert!(
        torque.norm() <= 1e-9 * scale * lever,
        "{label}: net torque {torque}"
    );
}

fn laws() -> Vec<(&'static str, TensileLaw)> {
    vec![
        ("linear", TensileLaw::Linear { stiffness: 800.0 }),
        (
            "piecewise",
            TensileLaw::PiecewiseLinear {
                points: vec![[0.02, 5.0], [0.1, 60.0], [0.2, 400.0]],
            },
        ),
        (
            "power",
            TensileLaw::PowerLaw {
                strain_ref: 0.1,
                tension_ref: 50.0,
                exponent: 2.5,
            },
        ),
    ]
}

#[test]
fn stretch_forces_and_jacobians_match_finite_differences() {
    let mut rng = StdRng::seed_from_u64(1);
    for (name, law) in laws() {
        let other = TensileLaw::Linear { stiffness: 300.0 };
        let warp = ThreadLaw {
            tension: &law,
            compression: 40.0,
        };
        let weft = ThreadLaw {
            tension: &other,
            compression: 10.0,
        };
        for _ in 0..40 {
            let (rest, x) = random_triangle(&mut rng);
            let eval = |x: &[Vec3; 3], mode| {
                let mut l = Local::default();
                add_stretch(&rest, warp, weft, x, mode, &mut l);
                l
            };
            check_derivatives(&format!("stretch/{name}"), &x, eval);
            let projected = eval(&x, HessianMode::Projected);
            assert_psd(&format!("stretch/{name} projected"), &projected.hessian_dense());
            assert_balanced("stretch", &x, &projected);
        }
    }
}

#[test]
fn stretch_projection_is_exact_in_extension() {
    // Pure extension: T >= 0 everywhere, so nothing is clamped.
    let rest = TriangleRest::new([
        Vector2::new(0.0, 0.0),
        Vector2::new(0.02, 0.0),
        Vector2::new(0.0, 0.02),
    ])
    .unwrap();
    let x = [
        Vec3::zeros(),
        Vec3::new(0.023, 0.0, 0.0),
        Vec3::new(0.0, 0.021, 0.0),
    ];
    let law = TensileLaw::Linear { stiffness: 500.0 };
    let t = ThreadLaw {
        tension: &law,
        compression: 50.0,
    };
    let (mut e, mut p) = (Local::default(), Local::default());
    add_stretch(&rest, t, t, &x, HessianMode::Exact, &mut e);
    add_stretch(&rest, t, t, &x, HessianMode::Projected, &mut p);
    assert!((e.hessian_dense() - p.hessian_dense()).amax() <= 1e-12 * e.hessian_dense().amax());
}

#[test]
fn shear_forces_and_jacobians_match_finite_differences() {
    let mut rng = StdRng::seed_from_u64(2);
    for _ in 0..60 {
        let (rest, x) = random_triangle(&mut rng);
        let eval = |x: &[Vec3; 3], mode| {
            let mut l = Local::default();
            add_shear(&rest, 25.0, x, mode, &mut l);
            l
        };
        check_derivatives("shear", &x, eval);
        let projected = eval(&x, HessianMode::Projected);
        assert_psd("shear projected", &projected.hessian_dense());
        assert_balanced("shear", &x, &projected);
    }
}

#[test]
fn shear_energy_is_the_source_form() {
    // A right triangle with legs l1, l2 sheared by phi: T = mu_s (l1 l2 / 2) phi^2, mu_s = G/2.
    let (l1, l2, phi, g) = (0.03f64, 0.02f64, 0.2f64, 12.0);
    let rest = TriangleRest::new([
        Vector2::new(0.0, 0.0),
        Vector2::new(l1, 0.0),
        Vector2::new(0.0, l2),
    ])
    .unwrap();
    // w_v turned by phi towards w_u, lengths kept.
    let x = [
        Vec3::zeros(),
        Vec3::new(l1, 0.0, 0.0),
        Vec3::new(l2 * phi.sin(), l2 * phi.cos(), 0.0),
    ];
    let mut l = Local::default();
    add_shear(&rest, g, &x, HessianMode::None, &mut l);
    let expected = (g / 2.0) * (l1 * l2 / 2.0) * phi * phi;
    assert!(
        (l.energy - expected).abs() <= 1e-12 * expected,
        "{} vs {expected}",
        l.energy
    );
}

#[test]
fn bending_forces_and_jacobians_match_finite_differences() {
    let mut rng = StdRng::seed_from_u64(3);
    for law in [BendingLaw::Quadratic, BendingLaw::SourceCosine] {
        for _ in 0..60 {
            let x = random_hinge(&mut rng);
            let eval = |x: &[Vec3; 4], mode| {
                let mut l = Local::default();
                bending::add_bending(law, 2e-5, x, mode, &mut l);
                l
            };
            check_derivatives(&format!("bending/{law:?}"), &x, eval);
            let projected = eval(&x, HessianMode::Projected);
            assert_psd(&format!("bending/{law:?} projected"), &projected.hessian_dense());
            assert_balanced("bending", &x, &projected);
        }
    }
}

#[test]
fn bend_angle_is_signed_and_zero_when_flat() {
    let mut rng = StdRng::seed_from_u64(4);
    for _ in 0..20 {
        let fold: f64 = rng.random_range(-170f64..170.0);
        let f = fold.to_radians();
        let x = [
            Vec3::zeros(),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.4, 1.0, 0.0),
            Vec3::new(0.6, -f.cos(), f.sin()),
        ];
        let d = bending::dihedral(&x, false).unwrap();
        assert!(
            (d.psi.abs() - f.abs()).abs() < 1e-12,
            "fold {fold} gave {}",
            d.psi.to_degrees()
        );
    }
    let flat = [
        Vec3::zeros(),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.4, 1.0, 0.0),
        Vec3::new(0.6, -1.0, 0.0),
    ];
    let d = bending::dihedral(&flat, false).unwrap();
    assert_eq!(d.psi, 0.0);
    // When flat the solver's Hessian is the exact one.
    let (mut e, mut p) = (Local::default(), Local::default());
    bending::add_bending(BendingLaw::SourceCosine, 1e-5, &flat, HessianMode::Exact, &mut e);
    bending::add_bending(
        BendingLaw::SourceCosine,
        1e-5,
        &flat,
        HessianMode::Projected,
        &mut p,
    );
    assert!((e.hessian_dense() - p.hessian_dense()).amax() <= 1e-12 * e.hessian_dense().amax());
}

#[test]
fn source_bending_law_is_mu_b_cos_squared_half_angle() {
    // B = mu_b cos^2(theta/2), theta the angle between the halves; mu_b = 2k.
    let k = 3e-5;
    for theta_deg in [179.0f64, 150.0, 90.0, 45.0] {
        let theta = theta_deg.to_radians();
        let psi = std::f64::consts::PI - theta;
        let x = [
            Vec3::zeros(),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.5, 1.0, 0.0),
            Vec3::new(0.5, -psi.cos(), psi.sin()),
        ];
        let mut l = Local::default();
        bending::add_bending(BendingLaw::SourceCosine, k, &x, HessianMode::None, &mut l);
        let expected = 2.0 * k * (theta / 2.0).cos().powi(2);
        assert!(
            (l.energy - expected).abs() <= 1e-12 * expected.max(1e-12),
            "theta {theta_deg}: {} vs {expected}",
            l.energy
        );
    }
}

#[test]
fn tensile_laws_are_consistent() {
    for (name, law) in laws() {
        law.validate("law").unwrap();
        for strain in [0.001, 0.015, 0.05, 0.12, 0.25] {
            let r = law.extension(strain);
            let (p, m) = (law.extension(strain + H), law.extension(strain - H));
            let dt = (p.energy - m.energy) / (2.0 * H);
            assert!(
                (dt - r.tension).abs() <= 1e-6 * r.tension.abs().max(1.0),
                "{name}: dW/de {dt} vs T {}",
                r.tension
            );
            let ds = (p.tension - m.tension) / (2.0 * H);
            assert!(
                (ds - r.slope).abs() <= 1e-5 * r.slope.abs().max(1.0),
                "{name}: dT/de {ds} vs slope {}",
                r.slope
            );
            assert!(
                (law.strain_at(r.tension) - strain).abs() < 1e-9,
                "{name}: inverse at {strain}"
            );
        }
    }
    let bad = TensileLaw::PiecewiseLinear {
        points: vec![[0.1, 5.0], [0.05, 8.0]],
    };
    assert!(bad.validate("warp").unwrap_err().to_string().contains("warp"));
}

#[test]
fn damping_and_drag_are_consistent_and_dissipative() {
    let mut rng = StdRng::seed_from_u64(5);
    let (rest, x) = random_triangle(&mut rng);
    let law = TensileLaw::Linear { stiffness: 700.0 };
    let t = ThreadLaw {
        tension: &law,
        compression: 70.0,
    };
    let mut local = Local::default();
    add_stretch(&rest, t, t, &x, HessianMode::Projected, &mut local);
    add_shear(&rest, 20.0, &x, HessianMode::Projected, &mut local);
    let beta = 0.01;
    let v: [Vec3; 3] = std::array::from_fn(|_| {
        Vec3::new(
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
        )
    });
    let force = |v: &[Vec3; 3]| {
        let (mut f, mut kv) = ([Vec3::zeros(); 3], [Vec3::zeros(); 3]);
        add_damping(beta, &local, v, &mut f, &mut kv);
        f
    };
    let f = force(&v);
    let power: f64 = f.iter().zip(&v).map(|(f, v)| f.dot(v)).sum();
    assert!(power <= 0.0, "damping does work {power}");
    // dF/dv = -beta K by finite differences.
    let k = local.hessian_dense();
    let q = flat(&v);
    for c in 0..9 {
        let (mut qp, mut qm) = (q.clone(), q.clone());
        qp[c] += H;
        qm[c] -= H;
        let (fp, fm) = (flat(&force(&unflat(&qp))), flat(&force(&unflat(&qm))));
        for r in 0..9 {
            let fd = (fp[r] - fm[r]) / (2.0 * H);
            assert!((fd + beta * k[(r, c)]).abs() <= 1e-6 * beta * k.amax());
        }
    }
    // Drag: F = -c A (v - wind), dF/dv = -c A I.
    let (wind, vi) = (Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.2, -0.3, 0.5));
    let (f, c) = particle::drag(0.5, 0.01, &vi, &wind);
    let (fp, _) = particle::drag(0.5, 0.01, &(vi + Vec3::new(0.0, H, 0.0)), &wind);
    assert!(((fp - f) / H + c * Vec3::y()).norm() < 1e-8);
    assert!(f.dot(&(vi - wind)) < 0.0);
    // Gravity: F = -dE/dx = m g.
    let (m, g, p) = (0.2, Vec3::new(0.0, 0.0, -9.81), Vec3::new(0.1, 0.2, 0.3));
    let fd = (particle::gravity_energy(m, &g, &(p + Vec3::z() * H))
        - particle::gravity_energy(m, &g, &(p - Vec3::z() * H)))
        / (2.0 * H);
    assert!((-fd - m * g.z).abs() < 1e-8);
}

/// Two layers' contact (see `cloth_core::energy::repulsion`): a particle over a random
/// triangle, at gaps from inside the law's linear knee to beyond its distance, with the
/// contact's frozen normal off the true gap direction. The geometry is a few cm so the
/// finite-difference step resolves the hardening law's curvature.
#[test]
fn repulsion_and_friction_between_layers_match_finite_differences() {
    let mut rng = StdRng::seed_from_u64(11);
    let law = RepulsionLaw {
        stiffness: 150.0,
        distance: 0.05,
    };
    let knee = law.distance
        * (RepulsionLaw::LEAST_GAP + RepulsionLaw::LINEAR_BELOW * (1.0 - RepulsionLaw::LEAST_GAP));
    for k in 0..60 {
        let (_, t) = random_triangle(&mut rng);
        let t = t.map(|p| 2.0 * p);
        let n = (t[1] - t[0]).cross(&(t[2] - t[0])).normalize();
        let b = {
            let raw: [f64; 3] = std::array::from_fn(|_| rng.random_range(0.05..1.0));
            let sum: f64 = raw.iter().sum();
            raw.map(|r| r / sum)
        };
        let foot = b[0] * t[0] + b[1] * t[1] + b[2] * t[2];
        // Gaps inside the knee, hardening, near and beyond the distance.
        let gap = match k % 4 {
            0 => rng.random_range(0.3..0.6) * law.distance,
            1 => rng.random_range(0.65..0.9) * law.distance,
            2 => rng.random_range(0.9..1.0) * law.distance,
            _ => rng.random_range(1.0..1.8) * law.distance,
        };
        if (gap - knee).abs() < 1e-4 {
            continue;
        }
        let tilt = Vec3::new(rng.random_range(-0.2..0.2), rng.random_range(-0.2..0.2), 0.0);
        let frame = ContactFrame {
            weights: [1.0, -b[0], -b[1], -b[2]],
            normal: (n + 0.3 * tilt.cross(&n)).normalize(),
        };
        // The particle sits `gap` along the frame's normal from the triangle's point.
        let p = foot + gap * frame.normal;
        let x = [p, t[0], t[1], t[2]];
        let spring = |x: &[Vec3; 4], _| {
            let mut l = Local::default();
            add_repulsion(&frame, &law, x, &mut l);
            l
        };
        check_derivatives("repulsion", &x, spring);
        let local = spring(&x, HessianMode::Exact);
        assert_psd("repulsion", &local.hessian_dense());
        let net: Vec3 = local.grad.iter().sum();
        assert!(net.norm() <= 1e-9 * local.grad[0].norm(), "net force {net}");
        assert!((frame.gap(&x) - gap).abs() < 1e-12);

        let v: [Vec3; 4] = std::array::from_fn(|_| {
            Vec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            )
        });
        let drag = rng.random_range(0.1..50.0);
        let friction = |v: &[Vec3; 4], _| {
            let mut l = Local::default();
            add_friction_drag(&frame, drag, v, &mut l);
            l
        };
        check_derivatives("friction drag", &v, friction);
        let local = friction(&v, HessianMode::Exact);
        assert_psd("friction drag", &local.hessian_dense());
        // The drag acts across the normal only, against the sliding: it dissipates.
        let force: Vec<Vec3> = local.grad.iter().map(|g| -g).collect();
        let power: f64 = force.iter().zip(&v).map(|(f, v)| f.dot(v)).sum();
        assert!(power <= 0.0, "friction does work {power}");
        let along: f64 = force.iter().map(|f| f.dot(&frame.normal).abs()).sum();
        assert!(along <= 1e-9 * force.iter().map(|f| f.norm()).sum::<f64>());
    }
}

#[test]
fn the_repulsion_law_is_a_spring_at_the_distance_that_hardens_without_bound() {
    let law = RepulsionLaw {
        stiffness: 80.0,
        distance: 5e-4,
    };
    let d = law.distance;
    let (e, f, s) = law.at(d);
    assert!(e.abs() < 1e-18 && f.abs() < 1e-15, "{e} {f}");
    assert!((s - law.stiffness).abs() < 1e-9 * law.stiffness);
    // Pressed to three quarters, the force is twice a linear spring's; towards the least
    // gap (half the distance) it grows like 1 / (g - d / 2).
    let (_, f75, _) = law.at(0.75 * d);
    assert!((f75 / (law.stiffness * 0.25 * d) - 2.0).abs() < 1e-9, "{f75}");
    let (_, f65, _) = law.at(0.65 * d);
    let (_, f70, _) = law.at(0.70 * d);
    assert!((f65 / f70 - (0.35 * 0.2) / (0.15 * 0.3)).abs() < 1e-9);
    // Its stiffness at the knee is sixteen times the spring's, and stays so below.
    let (_, _, s_knee) = law.at(d * 0.625);
    assert!((s_knee / law.stiffness - 16.0).abs() < 1e-9);
    assert_eq!(law.at(0.3 * d).2, s_knee);
    // Beyond the distance it pulls (the contact is one spring within a step), and below the
    // knee it goes on straight: energy, force and stiffness continuous there.
    assert!(law.at(1.2 * d).1 < 0.0);
    let knee = d * (RepulsionLaw::LEAST_GAP + RepulsionLaw::LINEAR_BELOW * (1.0 - RepulsionLaw::LEAST_GAP));
    let (above, below) = (law.at(knee + 1e-12), law.at(knee - 1e-12));
    for (a, b) in [(above.0, below.0), (above.1, below.1), (above.2, below.2)] {
        assert!((a - b).abs() <= 1e-6 * a.abs().max(1e-30), "{a} vs {b}");
    }
    assert!(law.at(0.3 * d).1 > law.at(knee).1);
}
