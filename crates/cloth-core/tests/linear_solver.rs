//! The block-sparse PCG against a direct sparse Cholesky, with each preconditioner, and
//! the constraint filter.

use cloth_core::linalg::{
    BlockSparse, Constraint, ConstraintError, ConstraintKind, Filter, FilteredSystem, Pcg, PcgSettings,
    Preconditioner,
};
use cloth_core::math::{Mat3, Vec3};
use cloth_core::parallelism::Parallelism;
use faer::prelude::*;
use faer::sparse::{SparseColMat, Triplet};
use faer::Side;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

const PRECONDITIONERS: [Preconditioner; 2] = [Preconditioner::BlockJacobi, Preconditioner::Multigrid];

/// A random SPD block system: a sum of random PSD 6x6 couplings over random pairs plus a
/// positive diagonal, like a mass matrix plus stiffness.
fn random_spd(n: usize, pairs: usize, rng: &mut StdRng) -> BlockSparse {
    let edges: Vec<(usize, usize)> = (0..pairs)
        .map(|_| loop {
            let (i, j) = (rng.random_range(0..n), rng.random_range(0..n));
            if i != j {
                break (i, j);
            }
        })
        .collect();
    let mut a = BlockSparse::from_pairs(n, edges.clone());
    for i in 0..n {
        let d = a.diag_slot(i);
        a.blocks_mut()[d] = Mat3::identity() * rng.random_range(0.01..1.0);
    }
    for (i, j) in edges {
        let g = nalgebra::SMatrix::<f64, 6, 6>::from_fn(|_, _| rng.random_range(-1.0..1.0));
        let h = g * g.transpose() * rng.random_range(1.0..100.0);
        for (bi, r) in [(0, i), (1, j)] {
            for (bj, c) in [(0, i), (1, j)] {
                let s = a.slot(r, c).unwrap();
                a.blocks_mut()[s] += h.fixed_view::<3, 3>(3 * bi, 3 * bj);
            }
        }
    }
    a
}

fn direct_solve(a: &BlockSparse, b: &[Vec3]) -> Vec<Vec3> {
    let n = a.n();
    let mut triplets = Vec::new();
    for r in 0..n {
        for s in a.row(r) {
            let c = a.col_of(s);
            for i in 0..3 {
                for j in 0..3 {
                    triplets.push(Triplet::new(3 * r + i, 3 * c + j, a.blocks()[s][(i, j)]));
                }
            }
        }
    }
    let m = SparseColMat::<usize, f64>::try_new_from_triplets(3 * n, 3 * n, &triplets).unwrap();
    let llt = m.sp_cholesky(Side::Lower).unwrap();
    let rhs = Mat::from_fn(3 * n, 1, |i, _| b[i / 3][i % 3]);
    let x = llt.solve(&rhs);
    (0..n)
        .map(|k| Vec3::new(x[(3 * k, 0)], x[(3 * k + 1, 0)], x[(3 * k + 2, 0)]))
        .collect()
}

fn max_diff(a: &[Vec3], b: &[Vec3]) -> f64 {
    a.iter().zip(b).map(|(p, q)| (p - q).norm()).fold(0.0, f64::max)
}
fn max_norm(a: &[Vec3]) -> f64 {
    a.iter().map(|p| p.norm()).fold(0.0, f64::max)
}

#[test]
fn pcg_agrees_with_sparse_cholesky() {
    let mut rng = StdRng::seed_from_u64(11);
    for (n, pairs) in [(5, 6), (40, 120), (300, 1200)] {
        let a = random_spd(n, pairs, &mut rng);
        let b: Vec<Vec3> = (0..n)
            .map(|_| Vec3::from_fn(|_, _| rng.random_range(-1.0..1.0)))
            .collect();
        let direct = direct_solve(&a, &b);
        for (par, preconditioner) in [Parallelism::Sequential, Parallelism::Rayon]
            .into_iter()
            .flat_map(|p| PRECONDITIONERS.map(|c| (p, c)))
        {
            let mut x = vec![Vec3::zeros(); n];
            let settings = PcgSettings {
                rel_tolerance: 1e-12,
                max_iterations: 20 * 3 * n,
                preconditioner,
            };
            let out = Pcg::new(n)
                .solve(
                    FilteredSystem {
                        matrix: &a,
                        filter: &Filter::new(n, 0),
                        rhs: &b,
                    },
                    &mut x,
                    &settings,
                    0.0,
                    par,
                )
                .unwrap();
            assert!(out.converged && out.rel_residual <= 1e-12, "{out:?}");
            let err = max_diff(&x, &direct) / max_norm(&direct);
            assert!(
                err < 1e-8,
                "n = {n}, {preconditioner:?}: PCG differs from Cholesky by {err:e}"
            );
        }
    }
}

#[test]
fn pcg_reports_an_iteration_limit_without_failing() {
    for preconditioner in PRECONDITIONERS {
        iteration_limit(preconditioner);
    }
}

fn iteration_limit(preconditioner: Preconditioner) {
    let mut rng = StdRng::seed_from_u64(12);
    let a = random_spd(200, 800, &mut rng);
    let b = vec![Vec3::new(1.0, -1.0, 0.5); 200];
    let mut x = vec![Vec3::zeros(); 200];
    let out = Pcg::new(200)
        .solve(
            FilteredSystem {
                matrix: &a,
                filter: &Filter::new(200, 0),
                rhs: &b,
            },
            &mut x,
            &PcgSettings {
                rel_tolerance: 1e-14,
                max_iterations: 3,
                preconditioner,
            },
            0.0,
            Parallelism::Sequential,
        )
        .unwrap();
    assert!(!out.converged);
    assert_eq!(out.iterations, 3);
    // The reported residual is the true one of the returned iterate.
    let mut ax = vec![Vec3::zeros(); 200];
    a.mul(&x, &mut ax, Parallelism::Sequential);
    let r: f64 = ax
        .iter()
        .zip(&b)
        .map(|(l, r)| (l - r).norm_squared())
        .sum::<f64>()
        .sqrt();
    let bn: f64 = b.iter().map(|v| v.norm_squared()).sum::<f64>().sqrt();
    assert!(
        (out.rel_residual - r / bn).abs() < 1e-12,
        "{} vs {}",
        out.rel_residual,
        r / bn
    );
}

#[test]
fn filtered_solve_holds_constrained_components_and_solves_the_rest() {
    let mut rng = StdRng::seed_from_u64(13);
    let n = 60;
    let a = random_spd(n, 200, &mut rng);
    let b: Vec<Vec3> = (0..n)
        .map(|_| Vec3::from_fn(|_, _| rng.random_range(-1.0..1.0)))
        .collect();
    let v0: Vec<Vec3> = (0..n)
        .map(|_| Vec3::from_fn(|_, _| rng.random_range(-1.0..1.0)))
        .collect();
    let normal = Vec3::new(1.0, 2.0, -0.5).normalize();
    let line = Vec3::new(0.3, -1.0, 0.2).normalize();
    let constraints = [
        Constraint {
            particle: 3,
            kind: ConstraintKind::Fixed,
            velocity: Vec3::new(0.1, 0.2, 0.3),
        },
        Constraint {
            particle: 4,
            kind: ConstraintKind::Fixed,
            velocity: Vec3::zeros(),
        },
        Constraint {
            particle: 17,
            kind: ConstraintKind::Plane { normal },
            velocity: normal * 0.7,
        },
        Constraint {
            particle: 30,
            kind: ConstraintKind::Line { direction: line },
            velocity: Vec3::new(0.0, 0.0, -0.4),
        },
    ];
    let mut filter = Filter::new(n, 4);
    constraints.iter().for_each(|c| filter.push(c).unwrap());

    // The filtered step as the integrator does it.
    let mut z = vec![Vec3::zeros(); n];
    filter.velocity_change(&v0, &mut z);
    let mut az = vec![Vec3::zeros(); n];
    a.mul(&z, &mut az, Parallelism::Sequential);
    let mut rhs: Vec<Vec3> = b.iter().zip(&az).map(|(b, az)| b - az).collect();
    filter.project(&mut rhs);
    for preconditioner in PRECONDITIONERS {
        check_filtered_solve(&a, &filter, &constraints, &rhs, &b, &z, &v0, preconditioner);
    }
}

fn check_filtered_solve(
    a: &BlockSparse,
    filter: &Filter,
    constraints: &[Constraint],
    rhs: &[Vec3],
    b: &[Vec3],
    z: &[Vec3],
    v0: &[Vec3],
    preconditioner: Preconditioner,
) {
    let n = a.n();
    // PCG applies the filter inside its operator; the assembled matrix is left untouched.
    let mut y = vec![Vec3::zeros(); n];
    let out = Pcg::new(n)
        .solve(
            FilteredSystem {
                matrix: a,
                filter,
                rhs,
            },
            &mut y,
            &PcgSettings {
                rel_tolerance: 1e-13,
                max_iterations: 5000,
                preconditioner,
            },
            0.0,
            Parallelism::Rayon,
        )
        .unwrap();
    assert!(out.converged);
    filter.project(&mut y);
    let dv: Vec<Vec3> = y.iter().zip(z).map(|(y, z)| y + z).collect();
    let v1: Vec<Vec3> = v0.iter().zip(&dv).map(|(v, d)| v + d).collect();

    // Constrained components are exactly the prescribed ones.
    for c in constraints {
        let s = c.kind.free_projection();
        let held = (Mat3::identity() - s) * (v1[c.particle] - c.velocity);
        assert!(
            held.norm() < 1e-12,
            "particle {}: constrained part off by {held}",
            c.particle
        );
    }
    // Free components satisfy the equations: S (A dv - b) = 0.
    let mut adv = vec![Vec3::zeros(); n];
    a.mul(&dv, &mut adv, Parallelism::Sequential);
    let mut residual: Vec<Vec3> = adv.iter().zip(b).map(|(l, r)| l - r).collect();
    filter.project(&mut residual);
    assert!(
        max_norm(&residual) < 1e-9 * max_norm(b),
        "{preconditioner:?}: free residual {}",
        max_norm(&residual)
    );
}

#[test]
fn two_constraints_on_one_particle_unite_their_directions() {
    let n = 3;
    let mut filter = Filter::new(n, 4);
    let (a, b) = (Vec3::z(), Vec3::x());
    filter
        .push(&Constraint {
            particle: 1,
            kind: ConstraintKind::Plane { normal: a },
            velocity: Vec3::new(0.0, 0.0, 0.5),
        })
        .unwrap();
    filter
        .push(&Constraint {
            particle: 1,
            kind: ConstraintKind::Plane { normal: b },
            velocity: Vec3::new(-0.2, 0.0, 0.0),
        })
        .unwrap();
    assert_eq!(filter.len(), 1);
    let mut v = vec![Vec3::new(9.0, 0.3, 9.0); n];
    filter.enforce_velocity(&mut v);
    // Free only along y; x and z held at their prescribed values.
    assert!((v[1] - Vec3::new(-0.2, 0.3, 0.5)).norm() < 1e-12, "{}", v[1]);
    assert_eq!(v[0], Vec3::new(9.0, 0.3, 9.0));
    // A pin on top of a contact holds everything.
    filter
        .push(&Constraint {
            particle: 1,
            kind: ConstraintKind::Fixed,
            velocity: Vec3::new(-0.2, 0.1, 0.5),
        })
        .unwrap();
    let mut v = vec![Vec3::new(9.0, 9.0, 9.0); n];
    filter.enforce_velocity(&mut v);
    assert!((v[1] - Vec3::new(-0.2, 0.1, 0.5)).norm() < 1e-12);
    // Degenerate directions are refused with the particle named.
    let err = filter.push(&Constraint {
        particle: 2,
        kind: ConstraintKind::Plane {
            normal: Vec3::zeros(),
        },
        velocity: Vec3::zeros(),
    });
    let err = err.unwrap_err();
    assert_eq!(err, ConstraintError::NotFinite { particle: 2 });
    assert!(err.to_string().contains("particle 2"), "{err}");
    filter.clear();
    assert!(filter.is_empty());
}

#[test]
fn nearly_parallel_contacts_do_not_blow_up_and_pins_win() {
    let mut filter = Filter::new(1, 2);
    let tilt = 5e-5f64;
    let (a, b) = (Vec3::z(), Vec3::new(tilt.sin(), 0.0, tilt.cos()));
    filter
        .push(&Constraint {
            particle: 0,
            kind: ConstraintKind::Plane { normal: a },
            velocity: a * 0.0,
        })
        .unwrap();
    filter
        .push(&Constraint {
            particle: 0,
            kind: ConstraintKind::Plane { normal: b },
            velocity: b * 0.01,
        })
        .unwrap();
    let v0 = Vec3::new(0.3, -0.2, 7.0);
    let mut v = vec![v0];
    filter.enforce_velocity(&mut v);
    // One constraint direction (the mean normal), met half way in the least-squares
    // sense; the tangential velocity is untouched.
    let n = (a + b).normalize();
    assert!((n.dot(&v[0]) - 0.005).abs() < 1e-9, "{}", v[0]);
    let tangential = |u: Vec3| u - n * n.dot(&u);
    assert!((tangential(v[0]) - tangential(v0)).norm() < 1e-12, "{}", v[0]);

    let mut filter = Filter::new(1, 2);
    let pin = Vec3::new(0.1, 0.2, 0.3);
    filter
        .push(&Constraint {
            particle: 0,
            kind: ConstraintKind::Fixed,
            velocity: pin,
        })
        .unwrap();
    filter
        .push(&Constraint {
            particle: 0,
            kind: ConstraintKind::Plane { normal: a },
            velocity: Vec3::zeros(),
        })
        .unwrap();
    let mut v = vec![Vec3::new(9.0, 9.0, 9.0)];
    filter.enforce_velocity(&mut v);
    assert_eq!(v[0], pin);
}
