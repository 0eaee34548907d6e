//! Cloth at rest through itself, smoothed apart where it crosses.
//!
//! What a garment still crosses at rest, the drape's pull (intersection contour
//! minimisation, see `cloth_core`'s untangling) could not shorten: the crossings looked
//! at on GarmentCode's designs lie where the cloth folds through itself within a cell or
//! two (a front's corner pinched through itself under a hood, rand_1_069), or where an
//! insert twists through the skirt beside the seam that joins them (the godets of
//! rand_1_091). There the curve the two pieces cross along ends at particles they share, or
//! runs into pairs near for good, which the collision and the count exempt: it has no ends
//! to shrink from. Run on those rests with no forces at all, the pull moved nothing on
//! rand_1_069 (2 crossings kept) and left 12 of rand_1_091's 15.
//!
//! A fold or twist that tight is a kink, and a kink smooths out: each particle within two
//! rings of a crossing moved halfway to the mean of its neighbours, round after round,
//! cleared both (rand_1_069 in 6 rounds, no particle moved more than 9 mm; rand_1_091 in
//! 13, 17 mm), and rand_1_009's flounces (75 crossings, cleared in 34 rounds) and
//! rand_1_094's one crossing. Smoothing pulls cloth lying on a curved body inward, so no
//! particle is let into a body: a move that would enter one, or end within its contact
//! layer, ends on the layer. The drape then goes on from there, its collision holding
//! apart what no longer crosses.

use cloth_core::{math::Vec3, ClothMesh, Collider, Neighbours, ParticlePath, Proximity, SelfCrossings};

/// What smoothing the cloth apart did.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct Smoothing {
    /// Edge-triangle crossings before, and after the best round (the fewest).
    pub before: usize,
    pub left: usize,
    /// Rounds smoothed up to the best.
    pub rounds: usize,
    /// The farthest any particle was moved, m.
    pub most_moved: f64,
}

/// Particles within this many rings of a crossing's are smoothed.
const RINGS: usize = 2;

/// The most rounds: a kink that a hundred halvings towards its neighbours do not take
/// out is not one (rand_1_015's godets, 85 crossings, kept 24 after 100).
const ROUNDS: usize = 100;

/// How far towards its neighbours' mean a particle moves each round.
const WEIGHT: f64 = 0.5;

/// Smooths `mesh` at `x` apart where it passes through itself (pairs within `rest_radius`
/// in the flat cloth exempt, as the count exempts them; `seams` the pairs not welded):
/// each round, every particle within [`RINGS`] rings of a crossing, but those `fixed`,
/// moves [`WEIGHT`] of the way to its neighbours' mean, where `keep_out` (particle, from,
/// to) lets it go; until nothing crosses or [`ROUNDS`]. `x` is left at the round with the
/// fewest crossings (as it was if none had fewer).
pub(super) fn smooth_apart(
    mesh: &ClothMesh,
    seams: &[[usize; 2]],
    rest_radius: f64,
    x: &mut [Vec3],
    fixed: impl Fn(usize) -> bool,
    keep_out: impl Fn(usize, &Vec3, Vec3) -> Vec3,
) -> Smoothing {
    let crossings = SelfCrossings::new(mesh, seams, rest_radius);
    let crossings = |x: &[Vec3]| crossings.pairs(x);
    let mut pairs = crossings(x);
    let start = x.to_vec();
    let mut report = Smoothing {
        before: pairs.len(),
        left: pairs.len(),
        ..Smoothing::default()
    };
    if pairs.is_empty() {
        return report;
    }
    let neighbours = Neighbours::of(mesh);
    let mut best = start.clone();
    let mut old = start.clone();
    for round in 1..=ROUNDS {
        old.copy_from_slice(x);
        let mut seeds: Vec<usize> = pairs
            .iter()
            .flat_map(|&(e, t)| mesh.edges()[e].into_iter().chain(mesh.triangles()[t]))
            .collect();
        seeds.sort_unstable();
        seeds.dedup();
        for i in neighbours.around(seeds, RINGS) {
            let around = neighbours.of_vertex(i);
            if fixed(i) || around.is_empty() {
                continue;
            }
            let mean = around.iter().map(|&j| old[j]).sum::<Vec3>() / around.len() as f64;
            x[i] = keep_out(i, &old[i], old[i] + WEIGHT * (mean - old[i]));
        }
        pairs = crossings(x);
        if pairs.len() < report.left {
            report.left = pairs.len();
            report.rounds = round;
            best.copy_from_slice(x);
        }
        if pairs.is_empty() {
            break;
        }
    }
    x.copy_from_slice(&best);
    report.most_moved = start
        .iter()
        .zip(x.iter())
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    report
}

/// Where a particle moved straight from `from` to `to` at time `t` ends, kept out of
/// `bodies`: on the contact layer where the move enters a body or ends within its layer
/// (past the bodies' thin parts, which are not there for it, if it `passes_thin_parts`).
pub(super) fn kept_out(
    bodies: &dyn Collider,
    t: f64,
    passes_thin_parts: bool,
    from: &Vec3,
    to: Vec3,
) -> Vec3 {
    let near = if passes_thin_parts {
        bodies.sweep_past_thin_parts(&ParticlePath::new(t, *from, t, to), 0.0, 0.0)
    } else {
        bodies.sweep(&ParticlePath::new(t, *from, t, to), 0.0, 0.0)
    };
    match near {
        Proximity::Near(p) if p.crossed || p.gap() < 0.0 => p.point + p.thickness * p.normal,
        _ => to,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use cloth_collide::{Bodies, Body, TriSurface};
    use cloth_core::{self_intersecting_pairs, GridBuilder};

    /// A sheet of `n` by `n` cells of 1 cm folded back over itself 1 cm apart (the fold
    /// along its middle row), with one particle of the upper layer pushed `depth` down:
    /// the upper layer's crossings through the lower are the spike's.
    fn folded_with_spike(n: usize, depth: f64) -> (ClothMesh, Vec<Vec3>, usize) {
        let mesh = GridBuilder::new(n + 1, n + 1)
            .spacing(0.01, 0.01)
            .build()
            .unwrap();
        let half = n / 2;
        let fold = |p: &Vec3| {
            let j = (p.y / 0.01).round() as usize;
            if j <= half {
                *p
            } else {
                // Back over the lower half, 1 cm up, rounding the fold.
                Vec3::new(p.x, (2 * half - j) as f64 * 0.01, 0.01)
            }
        };
        let mut x: Vec<Vec3> = mesh.positions().iter().map(fold).collect();
        // The fold's row itself half-way up, so the bend is not flat.
        for (p, q) in x.iter_mut().zip(mesh.positions()) {
            if (q.y / 0.01).round() as usize == half {
                p.y += 0.005;
                p.z = 0.005;
            }
        }
        let spike = (half + half / 2) * (n + 1) + half;
        x[spike].z -= depth;
        (mesh, x, spike)
    }

    #[test]
    fn a_spike_through_the_layer_under_it_is_smoothed_back_out() {
        let (mesh, mut x, spike) = folded_with_spike(10, 0.02);
        let before = x.clone();
        let crossing = self_intersecting_pairs(&mesh, &[], 0.0, &x).len();
        assert!(crossing > 0);
        let report = smooth_apart(&mesh, &[], 0.0, &mut x, |_| false, |_, _, to| to);
        assert_eq!(report.before, crossing);
        assert_eq!(report.left, 0);
        assert!(report.rounds >= 1 && report.rounds <= ROUNDS);
        assert!(self_intersecting_pairs(&mesh, &[], 0.0, &x).is_empty());
        // Back up into its own layer, the layer under it untouched but for the spike's
        // own neighbourhood; no particle moved farther than the spike was pushed.
        assert!(x[spike].z > 0.0, "{}", x[spike].z);
        let moved = |i: usize| (x[i] - before[i]).norm();
        assert!((0..x.len()).all(|i| moved(i) <= 0.02 + 1e-12));
        assert!((report.most_moved - (0..x.len()).map(moved).fold(0.0, f64::max)).abs() < 1e-15);
        let far = (0..x.len()).filter(|&i| (before[i] - before[spike]).norm() > 0.05);
        for i in far {
            assert_eq!(x[i], before[i], "particle {i}, far from the spike, moved");
        }
    }

    #[test]
    fn cloth_not_through_itself_is_left_as_it_is() {
        let (mesh, mut x, _) = folded_with_spike(10, 0.0);
        let before = x.clone();
        let report = smooth_apart(&mesh, &[], 0.0, &mut x, |_| false, |_, _, to| to);
        assert_eq!(report, Smoothing::default());
        assert_eq!(x, before);
    }

    #[test]
    fn fixed_particles_stay_and_the_best_round_is_kept() {
        // The spike fixed: nothing takes it out, and what is kept is the round with the
        // fewest crossings, or nothing moved if none had fewer.
        let (mesh, mut x, spike) = folded_with_spike(10, 0.02);
        let before = x.clone();
        let report = smooth_apart(&mesh, &[], 0.0, &mut x, |i| i == spike, |_, _, to| to);
        assert_eq!(x[spike], before[spike]);
        assert!(report.left > 0 && report.left <= report.before);
        assert_eq!(self_intersecting_pairs(&mesh, &[], 0.0, &x).len(), report.left);
        if report.rounds == 0 {
            assert_eq!(x, before);
        }
    }

    #[test]
    fn a_move_into_a_body_ends_on_its_contact_layer() {
        // A box with its top at z = 0.1 and a contact layer of 2 mm.
        let bodies = Bodies::new(vec![Body::new(
            "box",
            TriSurface::cuboid(Vec3::new(0.5, 0.5, 0.1)).unwrap(),
        )
        .with_thickness(0.002)
        .unwrap()]);
        let from = Vec3::new(0.0, 0.0, 0.103);
        // Into the box: stopped on the layer where it entered.
        let into = kept_out(&bodies, 0.0, false, &from, Vec3::new(0.01, 0.0, 0.09));
        assert!((into.z - 0.102).abs() < 1e-9, "{into:?}");
        // Within the layer: lifted onto it.
        let within = kept_out(&bodies, 0.0, false, &from, Vec3::new(0.01, 0.0, 0.101));
        assert!((within - Vec3::new(0.01, 0.0, 0.102)).norm() < 1e-9, "{within:?}");
        // Clear of it: where it was going.
        let clear = Vec3::new(0.01, 0.0, 0.104);
        assert_eq!(kept_out(&bodies, 0.0, false, &from, clear), clear);
    }
}
