//! Sharp body features against cloth triangles. Particle contacts alone let a cube's
//! corner or a table's edge poke between the particles of a coarse sheet. Each sharp
//! feature under a cloth triangle, closer than the contact thickness, pushes the triangle
//! out through a stiff one-sided spring on the gap, shared among the triangle's particles by
//! barycentric weight and part of the implicit solve (so the cloth draped over an edge
//! rests on it instead of being kicked off every step), with Coulomb friction against the
//! triangle's sliding over it. A feature found through a triangle
//! at the end of a step is pushed back out at once, with an inelastic impulse (Bridson,
//! Fedkiw & Anderson 2002).

use super::particle_contacts::SLIP_SPEED;
use super::{SharpFeature, StepEnd};
use crate::forces::ForceOutputs;
use crate::math::{Mat3, Vec3};
use crate::spatial::{Aabb, Bvh};

/// Features within `(1 + BAND)` thicknesses of a triangle are in contact.
const BAND: f64 = 0.5;

/// The largest Coulomb coefficient a feature's friction takes: an infinite one (no slip)
/// would be an infinite drag; ten holds the cloth against anything it meets.
const MAX_FRICTION: f64 = 10.0;

/// The least cosine between a cloth triangle's normal and a feature's for the triangle to
/// count as lying over the feature (60 degrees).
const MIN_FACING: f64 = 0.5;

/// A triangle is skipped unless some vertex is within its longest edge plus the largest
/// contact thickness of a body (by the particles' gap bounds), or if a vertex's bound is
/// infinite (a particle passing through the body, which features leave alone).
fn near_body(tri: &[usize; 3], p: &[Vec3; 3], gap_bound: &impl Fn(usize) -> f64, max_thickness: f64) -> bool {
    if tri.iter().any(|&i| gap_bound(i) == f64::INFINITY) {
        return false;
    }
    let longest = (p[1] - p[0])
        .norm()
        .max((p[2] - p[1]).norm())
        .max((p[0] - p[2]).norm());
    let nearest = tri.iter().map(|&i| gap_bound(i)).fold(f64::INFINITY, f64::min);
    nearest <= longest + max_thickness
}

/// The sharp features of the bodies at one time, with a hierarchy over them so that a
/// cloth triangle meets only the features near it (a scanned body has thousands: 3,233 on
/// GarmentCode's mean body, where trying each against every triangle near the body took
/// 40 % of a garment's step).
#[derive(Debug, Default)]
pub(crate) struct FeatureSet {
    pub features: Vec<SharpFeature>,
    /// Built over the first features seen; the bodies are rigid and keep the set, so later
    /// times only refit it.
    tree: Option<Bvh>,
    /// The features found near one triangle, in ascending order.
    near: Vec<usize>,
}

impl FeatureSet {
    /// Takes the features of a new time (the same set as before, moved).
    pub fn update(&mut self, fill: impl FnOnce(&mut Vec<SharpFeature>)) {
        self.features.clear();
        fill(&mut self.features);
        let features = &self.features;
        if self.tree.as_ref().map(|t| t.len()) != Some(features.len()) {
            let centres: Vec<Vec3> = features.iter().map(|f| 0.5 * (f.a + f.b)).collect();
            self.tree = Some(Bvh::new(&centres));
        }
        if let Some(tree) = self.tree.as_mut() {
            tree.refit(|i| Aabb::of([features[i].a, features[i].b]));
        }
    }

    /// The features whose segments' boxes come within `margin` of the triangle's box, in
    /// ascending order, into `self.near`.
    fn gather_near(&mut self, p: &[Vec3; 3], margin: f64) {
        self.near.clear();
        let Some(tree) = self.tree.as_ref() else {
            return;
        };
        let query = Aabb::of(*p).inflated(margin);
        let near = &mut self.near;
        tree.query(&query, |i| near.push(i));
        near.sort_unstable();
    }
}

/// A sharp feature under a cloth triangle, frozen for one step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct FeatureContact {
    pub triangle: [usize; 3],
    pub weights: [f64; 3],
    pub normal: Vec3,
    /// The feature's deepest point under the triangle.
    pub point: Vec3,
    pub velocity: Vec3,
    pub thickness: f64,
    pub friction: f64,
}

impl FeatureContact {
    fn gap(&self, x: &[Vec3]) -> f64 {
        let cloth: Vec3 = (0..3).map(|k| self.weights[k] * x[self.triangle[k]]).sum();
        self.normal.dot(&(cloth - self.point))
    }
}

/// The feature contacts of a step: every feature under a cloth triangle within the
/// thickness (and not through it by more than the thickness, which is the cloth lying on
/// the far side of a feature, not touching it).
pub(crate) fn detect_features<G: Fn(usize) -> f64>(
    set: &mut FeatureSet,
    triangles: &[[usize; 3]],
    x: &[Vec3],
    reach: FeatureReach<G>,
    friction: impl Fn(Option<f64>, usize) -> f64,
    out: &mut Vec<FeatureContact>,
) {
    let FeatureReach {
        gap_bound,
        max_thickness,
    } = reach;
    out.clear();
    if set.features.is_empty() {
        return;
    }
    for tri in triangles {
        let p = tri.map(|i| x[i]);
        if !near_body(tri, &p, &gap_bound, max_thickness) {
            continue;
        }
        set.gather_near(&p, (1.0 + BAND) * max_thickness);
        for &k in &set.near {
            let f = &set.features[k];
            if !boxes_overlap(&p, f, (1.0 + BAND) * f.thickness) {
                continue;
            }
            let Some(ends) = feature_under_triangle(&p, f) else {
                continue;
            };
            for hit in ends.into_iter().flatten() {
                if hit.gap < (1.0 + BAND) * f.thickness && hit.gap > -f.thickness {
                    out.push(FeatureContact {
                        triangle: *tri,
                        weights: hit.weights,
                        normal: hit.normal,
                        point: hit.point,
                        velocity: f.velocity,
                        thickness: f.thickness,
                        // A triangle's fabric is its corners'.
                        friction: friction(f.friction, tri[0]),
                    });
                }
            }
        }
    }
}

/// The penalty `E = k/2 (d - g)^2` of each contact whose gap `g` is under its thickness
/// `d`: forces into `force` and `K v` into `kv` (K = k w w^T n n^T with the weights and
/// normal frozen, so it is PSD). For an implicit step of length `h`, also `h^2 K` into the
/// matrix and the friction: a drag `c = mu p / max(|u|, SLIP_SPEED)` against the
/// triangle's tangential velocity `u` over the feature at the step's start, `p` the
/// spring's push, so it slides against `mu p` and is held when slower than
/// [`SLIP_SPEED`]; its force goes into `force` and `h c w w^T (I - n n^T)` into the
/// matrix. Unlike the particles' friction it predicts nothing: the drag lags the sliding
/// speed by a step, so a triangle slowing down feels less than `mu p`, and one pulled
/// free of its hold (by more than `mu p`) gains speed from [`SLIP_SPEED`] by the ratio
/// of the pull to `mu p` each step. An explicit step would need that drag to be tiny to stay stable, so it has no
/// friction at features. Returns the energy.
pub(crate) fn add_penalty(
    contacts: &[FeatureContact],
    stiffness: f64,
    x: &[Vec3],
    v: &[Vec3],
    out: ForceOutputs<'_, '_>,
) -> f64 {
    let ForceOutputs {
        force,
        hv: kv,
        stiffness: target,
    } = out;
    let mut implicit = target.map(|t| (t.matrix, t.h));
    let mut energy = 0.0;
    for c in contacts {
        let depth = c.thickness - c.gap(x);
        if depth <= -BAND * c.thickness {
            continue;
        }
        // Just outside the thickness the spring exerts nothing yet, but its stiffness is
        // already in the step's Jacobian: a triangle closing in meets the spring within the
        // step instead of overshooting into it and being thrown back the next.
        let depth = depth.max(0.0);
        energy += 0.5 * stiffness * depth * depth;
        let (w, n, t) = (c.weights, c.normal, c.triangle);
        let closing: f64 = (0..3).map(|k| w[k] * n.dot(&v[t[k]])).sum();
        for a in 0..3 {
            force[t[a]] += (stiffness * depth * w[a]) * n;
            kv[t[a]] += (stiffness * w[a] * closing) * n;
        }
        let Some((m, h)) = implicit.as_mut() else {
            continue;
        };
        let tangential = Mat3::identity() - n * n.transpose();
        let relative = (0..3).map(|k| w[k] * v[t[k]]).sum::<Vec3>() - c.velocity;
        let sliding = tangential * relative;
        let drag = c.friction.min(MAX_FRICTION) * stiffness * depth / sliding.norm().max(SLIP_SPEED);
        for a in 0..3 {
            force[t[a]] -= (drag * w[a]) * sliding;
        }
        let block = (*h * *h * stiffness) * (n * n.transpose()) + (*h * drag) * tangential;
        for a in 0..3 {
            for b in 0..3 {
                // Both particles share the triangle, so the block exists.
                if let Some(slot) = m.slot(t[a], t[b]) {
                    m.blocks_mut()[slot] += (w[a] * w[b]) * block;
                }
            }
        }
    }
    energy
}

/// How near the bodies each triangle may be: a lower bound on each particle's gap to them,
/// and their largest thickness (a triangle farther than both is passed over).
pub(crate) struct FeatureReach<G> {
    pub gap_bound: G,
    pub max_thickness: f64,
}

/// Pushes back out every cloth triangle that a feature went through during the step
/// `end` (by no more than the step's motion could carry it, from the outer side of
/// the triangle at the step's start); returns how many. `x_solved` is `end.x1` before any
/// push.
pub(crate) fn resolve_features<G: Fn(usize) -> f64>(
    set: &mut FeatureSet,
    triangles: &[[usize; 3]],
    end: &mut StepEnd<'_>,
    x_solved: &[Vec3],
    inv_mass: &[f64],
    reach: FeatureReach<G>,
) -> usize {
    let FeatureReach {
        gap_bound,
        max_thickness,
    } = reach;
    let (h, x_start) = (end.h, end.x0);
    let (x_new, v_new) = (&mut *end.x1, &mut *end.v1);
    if set.features.is_empty() {
        return 0;
    }
    let mut pushed = 0;
    for tri in triangles {
        let mut p = tri.map(|i| x_new[i]);
        if !near_body(tri, &p, &gap_bound, max_thickness) {
            continue;
        }
        // The step's own motion, not the pushes of the triangles before.
        let moved = tri
            .iter()
            .map(|&i| (x_solved[i] - x_start[i]).norm())
            .fold(0.0, f64::max);
        // Features are taken in ascending order, each against the triangle as the pushes
        // before it left it; after a push the features near its new place are gathered
        // again, from the next index on.
        set.gather_near(&p, max_thickness + moved);
        let mut at = 0;
        while at < set.near.len() {
            let k = set.near[at];
            at += 1;
            let f = &set.features[k];
            if !boxes_overlap(&p, f, f.thickness + moved) {
                continue;
            }
            let Some(hit) = feature_under_triangle(&p, f).and_then(deepest) else {
                continue;
            };
            // Deeper than this step's motion could carry it: the cloth is legitimately on
            // the other side of the feature, not pushed through it now.
            if hit.gap >= 0.0 || hit.gap < -(f.thickness + moved) {
                continue;
            }
            let w = hit.weights;
            let denom: f64 = (0..3).map(|c| w[c] * w[c] * inv_mass[tri[c]]).sum();
            if denom <= 0.0 {
                continue;
            }
            // A feature the triangle was already beyond when the step started (by more
            // than the thickness) was not carried through by the step: a push may have
            // put it there. Pushed out of such features too, a cuff between a hand's
            // fingers was handed on from one to the next, 528 pushes in a step, and
            // stretched to 26 times its length (GarmentCode's rand_1_094, which then
            // diverged).
            if started_beyond(
                tri.map(|i| x_start[i]),
                &hit,
                hit.point - h * f.velocity,
                f.thickness,
            ) {
                continue;
            }
            let push = f.thickness - hit.gap;
            let cloth_velocity: Vec3 = (0..3).map(|c| w[c] * v_new[tri[c]]).sum();
            let into = (cloth_velocity - f.velocity).dot(&hit.normal).min(0.0);
            for c in 0..3 {
                let share = w[c] * inv_mass[tri[c]] / denom;
                x_new[tri[c]] += (push * share) * hit.normal;
                v_new[tri[c]] -= (into * share) * hit.normal;
            }
            p = tri.map(|i| x_new[i]);
            pushed += 1;
            set.gather_near(&p, max_thickness + moved);
            at = set.near.partition_point(|&j| j <= k);
        }
    }
    pushed
}

/// Whether the cloth point of `hit` lay beyond the feature point `was` by more than
/// `thickness` on the triangle at `start` (a triangle edge-on there says nothing).
fn started_beyond(start: [Vec3; 3], hit: &FeatureHit, was: Vec3, thickness: f64) -> bool {
    let cross = (start[1] - start[0]).cross(&(start[2] - start[0]));
    let Some(normal) = cross.try_normalize(1e-300) else {
        return false;
    };
    let normal = if normal.dot(&hit.normal) < 0.0 {
        -normal
    } else {
        normal
    };
    let cloth: Vec3 = (0..3).map(|k| hit.weights[k] * start[k]).sum();
    normal.dot(&(cloth - was)) < -thickness
}

/// Whether the triangle's box meets the feature's, grown by `margin`.
fn boxes_overlap(p: &[Vec3; 3], f: &SharpFeature, margin: f64) -> bool {
    (0..3).all(|k| {
        let lo = p[0][k].min(p[1][k]).min(p[2][k]);
        let hi = p[0][k].max(p[1][k]).max(p[2][k]);
        let flo = f.a[k].min(f.b[k]) - margin;
        let fhi = f.a[k].max(f.b[k]) + margin;
        lo <= fhi && flo <= hi
    })
}

/// One end of the part of a feature whose projection on a triangle's plane falls inside it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct FeatureHit {
    /// Barycentric weights of the projection.
    pub weights: [f64; 3],
    /// The triangle's unit normal, turned to the feature's outward side.
    pub normal: Vec3,
    /// Height of the triangle's plane above the feature point along `normal` (negative:
    /// the feature is through the cloth).
    pub gap: f64,
    /// The feature point.
    pub point: Vec3,
}

/// The part of a feature under a triangle, by its ends (one for a corner). Along a segment
/// the projected barycentric weights and the height are affine, so clipping the segment to
/// the triangle's prism is exact, and springs at both ends of the clipped part hold it off
/// the cloth smoothly: the penalty does not jump from one end to the other as the segment
/// tilts through parallel to the cloth.
pub(crate) fn feature_under_triangle(p: &[Vec3; 3], f: &SharpFeature) -> Option<[Option<FeatureHit>; 2]> {
    let e1 = p[1] - p[0];
    let e2 = p[2] - p[0];
    let cross = e1.cross(&e2);
    let area2 = cross.norm();
    if area2 <= 1e-14 * (e1.norm_squared() + e2.norm_squared()) {
        return None;
    }
    let mut normal = cross / area2;
    if normal.dot(&f.normal) < 0.0 {
        normal = -normal;
    }
    // A triangle steeper than this to the feature's normal is not lying on it: which side
    // it is on is the particles' contacts' to say, and pushed out along its own normal it
    // would go mostly sideways. Near edge-on (down to 0.05), a hood crumpled against an
    // ear was pushed by one feature after another, 1,546 pushes in a step and 13,552 in
    // the next, until the cloth left at 100 m/s.
    if normal.dot(&f.normal) < MIN_FACING {
        return None;
    }
    let (d00, d01, d11) = (e1.dot(&e1), e1.dot(&e2), e2.dot(&e2));
    let det = d00 * d11 - d01 * d01;
    let bary = |q: &Vec3| {
        let d = q - p[0];
        let (d20, d21) = (d.dot(&e1), d.dot(&e2));
        let w1 = (d11 * d20 - d01 * d21) / det;
        let w2 = (d00 * d21 - d01 * d20) / det;
        [1.0 - w1 - w2, w1, w2]
    };
    let wa = bary(&f.a);
    let wb = bary(&f.b);
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    for k in 0..3 {
        let slope = wb[k] - wa[k];
        if slope.abs() < 1e-15 {
            if wa[k] < 0.0 {
                return None;
            }
        } else if slope > 0.0 {
            lo = lo.max(-wa[k] / slope);
        } else {
            hi = hi.min(-wa[k] / slope);
        }
    }
    if lo > hi {
        return None;
    }
    let end = |s: f64| {
        let q = f.a + s * (f.b - f.a);
        FeatureHit {
            weights: [0, 1, 2].map(|k| wa[k] + s * (wb[k] - wa[k])),
            normal,
            gap: normal.dot(&(p[0] - q)),
            point: q,
        }
    };
    let second = (hi - lo > 1e-9).then(|| end(hi));
    Some([Some(end(lo)), second])
}

/// The deeper of a feature's ends under a triangle.
fn deepest(ends: [Option<FeatureHit>; 2]) -> Option<FeatureHit> {
    ends.into_iter().flatten().min_by(|a, b| a.gap.total_cmp(&b.gap))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::BlockSparse;

    fn feature_under_triangle_deepest(p: &[Vec3; 3], f: &SharpFeature) -> Option<FeatureHit> {
        feature_under_triangle(p, f).and_then(deepest)
    }

    fn feature(a: Vec3, b: Vec3) -> SharpFeature {
        SharpFeature {
            a,
            b,
            normal: Vec3::z(),
            velocity: Vec3::zeros(),
            thickness: 0.01,
            friction: Some(0.5),
        }
    }
    const TRI: [Vec3; 3] = [
        Vec3::new(0.0, 0.0, 0.1),
        Vec3::new(1.0, 0.0, 0.1),
        Vec3::new(0.0, 1.0, 0.1),
    ];

    /// Penalty and friction of a feature moving at 0.2 m/s along x, 4 mm into the 10 mm
    /// layer under a triangle moving at `v` (every vertex), with and without an implicit
    /// step.
    fn penalty_with(v: Vec3, implicit: bool) -> (Vec<Vec3>, BlockSparse) {
        let contact = FeatureContact {
            triangle: [0, 1, 2],
            weights: [0.2, 0.3, 0.5],
            normal: Vec3::z(),
            point: Vec3::zeros(),
            velocity: Vec3::new(0.2, 0.0, 0.0),
            thickness: 0.01,
            friction: 0.5,
        };
        let x = [Vec3::new(0.0, 0.0, 0.006); 3];
        let (mut force, mut kv) = (vec![Vec3::zeros(); 3], vec![Vec3::zeros(); 3]);
        let mut m = BlockSparse::from_pairs(3, [(0, 1), (1, 2), (0, 2)]);
        let out = ForceOutputs {
            force: &mut force,
            hv: &mut kv,
            stiffness: implicit.then_some(crate::forces::StiffnessTarget {
                matrix: &mut m,
                h: 0.01,
            }),
        };
        add_penalty(&[contact], 100.0, &x, &[v; 3], out);
        (force, m)
    }

    #[test]
    fn feature_friction_is_coulomb_against_the_sliding() {
        let (w, k, depth, mu, h) = ([0.2, 0.3, 0.5], 100.0, 0.004, 0.5, 0.01);
        let p = k * depth;
        // Sliding over the feature at 0.3 m/s along x (and closing along the normal, which
        // friction ignores): each vertex takes its share of mu p against the sliding, and
        // of the push along n.
        let (force, m) = penalty_with(Vec3::new(0.5, 0.0, -0.1), true);
        let drag = mu * p / 0.3;
        for a in 0..3 {
            let expected = Vec3::new(-mu * p * w[a], 0.0, p * w[a]);
            assert!((force[a] - expected).norm() < 1e-12, "{a}: {:?}", force[a]);
            for b in 0..3 {
                let slot = m.slot(a, b).expect("triangle block");
                let tangential = Mat3::from_diagonal(&Vec3::new(1.0, 1.0, 0.0));
                let normal = Mat3::from_diagonal(&Vec3::new(0.0, 0.0, 1.0));
                let expected = w[a] * w[b] * (h * h * k * normal + h * drag * tangential);
                assert!((m.blocks()[slot] - expected).norm() < 1e-12, "block {a}{b}");
            }
        }
        // Slower than SLIP_SPEED: held by a drag of mu p / SLIP_SPEED.
        let slow = 0.5 * SLIP_SPEED;
        let (force, _) = penalty_with(Vec3::new(0.2, slow, 0.0), true);
        let total: Vec3 = force.iter().sum();
        assert!((total.y + mu * p * 0.5).abs() < 1e-12, "held by {total:?}");
        // No friction without an implicit step.
        let (force, _) = penalty_with(Vec3::new(0.3, 0.0, 0.0), false);
        assert!(force.iter().all(|f| f.x == 0.0 && f.y == 0.0), "{force:?}");
    }

    #[test]
    fn corner_under_a_triangle() {
        let hit = feature_under_triangle_deepest(
            &TRI,
            &feature(Vec3::new(0.25, 0.25, 0.0), Vec3::new(0.25, 0.25, 0.0)),
        )
        .expect("under");
        assert!((hit.gap - 0.1).abs() < 1e-14);
        assert!((hit.weights[0] - 0.5).abs() < 1e-14 && (hit.weights[1] - 0.25).abs() < 1e-14);
        assert!(feature_under_triangle_deepest(
            &TRI,
            &feature(Vec3::new(0.8, 0.8, 0.0), Vec3::new(0.8, 0.8, 0.0))
        )
        .is_none());
    }

    #[test]
    fn a_triangle_steeper_than_sixty_degrees_to_the_feature_is_not_over_it() {
        // The triangle turned about its x edge by `tilt` from facing the feature's normal
        // (z), a corner under its middle.
        let tilted = |tilt: f64| {
            let up = Vec3::new(0.0, tilt.cos(), tilt.sin());
            [Vec3::zeros(), Vec3::x(), up].map(|p| p + Vec3::new(0.0, 0.0, 0.1))
        };
        let under = |tilt: f64| {
            let p = tilted(tilt);
            let centre = (p[0] + p[1] + p[2]) / 3.0 - 0.05 * Vec3::z();
            feature_under_triangle_deepest(&p, &feature(centre, centre))
        };
        assert!(under(50f64.to_radians()).is_some());
        // cos 70 degrees = 0.34 < 0.5: pushed along its own normal, the triangle would go
        // mostly sideways.
        assert!(under(70f64.to_radians()).is_none());
    }

    #[test]
    fn edge_clipped_to_the_triangle_takes_its_highest_point() {
        // Rising edge from (-1, 0.2, 0) to (2, 0.2, 0.3): inside the triangle for x in [0, 0.8];
        // its highest point there is at x = 0.8, z = 0.18, which pokes through the plane z = 0.1.
        let hit = feature_under_triangle_deepest(
            &TRI,
            &feature(Vec3::new(-1.0, 0.2, 0.0), Vec3::new(2.0, 0.2, 0.3)),
        )
        .expect("under");
        assert!((hit.gap - (0.1 - 0.18)).abs() < 1e-12, "{hit:?}");
        assert!((hit.weights[1] - 0.8).abs() < 1e-12 && (hit.weights[0]).abs() < 1e-12);
    }

    #[test]
    fn the_hierarchy_finds_every_feature_contact_trying_all_features_finds() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand::rngs::StdRng::seed_from_u64(7);
        let mut point = |scale: f64| Vec3::new(rng.random(), rng.random(), rng.random()) * scale;
        // 2,000 short edges and corners of a body in a 10 cm cube, under 1,000 triangles of
        // cloth of 2 cm lying about in it.
        let features: Vec<SharpFeature> = (0..2000)
            .map(|k| {
                let a = point(0.1);
                let b = if k % 5 == 0 { a } else { a + point(0.01) };
                feature(a, b)
            })
            .collect();
        let mut x = Vec::new();
        for _ in 0..1000 {
            let c = point(0.1);
            x.push(c);
            x.push(c + Vec3::new(0.02, 0.0, 0.0) + point(0.005));
            x.push(c + Vec3::new(0.0, 0.02, 0.0) + point(0.005));
        }
        let triangles: Vec<[usize; 3]> = (0..1000).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
        let mut set = FeatureSet::default();
        set.update(|out| out.extend_from_slice(&features));
        let mut found = Vec::new();
        let reach = FeatureReach {
            gap_bound: |_| 0.0,
            max_thickness: 0.01,
        };
        detect_features(
            &mut set,
            &triangles,
            &x,
            reach,
            |own: Option<f64>, _| own.unwrap_or(0.3),
            &mut found,
        );
        let mut all = Vec::new();
        for tri in &triangles {
            let p = tri.map(|i| x[i]);
            for f in &features {
                if !boxes_overlap(&p, f, (1.0 + BAND) * f.thickness) {
                    continue;
                }
                for hit in feature_under_triangle(&p, f).into_iter().flatten().flatten() {
                    if hit.gap < (1.0 + BAND) * f.thickness && hit.gap > -f.thickness {
                        all.push((*tri, hit.point));
                    }
                }
            }
        }
        assert!(
            all.len() > 100,
            "{} contacts: the scene tests too little",
            all.len()
        );
        let got: Vec<_> = found.iter().map(|c| (c.triangle, c.point)).collect();
        assert_eq!(got, all);
    }

    /// The triangle `TRI` come down 15 cm in a step at 1 m/s through `features`, pushed
    /// back out: how many pushes, and its particles' positions and velocities after.
    fn pushed_out_of(features: Vec<SharpFeature>) -> (usize, Vec<Vec3>, Vec<Vec3>) {
        let start = TRI.to_vec();
        let mut x: Vec<Vec3> = TRI.iter().map(|p| p - Vec3::new(0.0, 0.0, 0.15)).collect();
        let solved = x.clone();
        let mut v = vec![Vec3::new(0.0, 0.0, -1.0); 3];
        let mut set = FeatureSet::default();
        set.update(|out| out.extend(features));
        let mut support = vec![Vec3::zeros(); 3];
        let mut end = StepEnd {
            t0: 0.0,
            h: 0.01,
            x0: &start,
            x1: &mut x,
            v1: &mut v,
            masses: &[1.0; 3],
            pinned: &[false; 3],
            support: &mut support,
            par: crate::parallelism::Parallelism::Sequential,
        };
        let reach = FeatureReach {
            gap_bound: |_| 0.0,
            max_thickness: 0.01,
        };
        let n = resolve_features(&mut set, &[[0, 1, 2]], &mut end, &solved, &[1.0; 3], reach);
        (n, x, v)
    }

    #[test]
    fn a_corner_through_a_triangle_is_pushed_out() {
        let corner = Vec3::new(0.3, 0.3, 0.0);
        let (n, x, v) = pushed_out_of(vec![feature(corner, corner)]);
        assert_eq!(n, 1);
        // The cloth point over the corner sits at the thickness, and no longer moves into it.
        let w = [0.4, 0.3, 0.3];
        let xc: Vec3 = (0..3).map(|k| w[k] * x[k]).sum();
        let vc: Vec3 = (0..3).map(|k| w[k] * v[k]).sum();
        assert!((xc - Vec3::new(0.3, 0.3, 0.01)).norm() < 1e-12, "{xc:?}");
        assert!(vc.z.abs() < 1e-12, "{vc:?}");
    }

    #[test]
    fn a_stack_of_features_pushes_a_triangle_out_of_those_the_step_carried_it_through_only() {
        // The triangle came down 15 cm through a column of corners 1.5 cm apart, from
        // above every one up to z = 0.105; each corner is within the thickness of where
        // the push before would leave it.
        let corner = |k: usize| Vec3::new(0.3, 0.3, -0.045 + 0.015 * k as f64);
        let (n, x, _) = pushed_out_of((0..60).map(|k| feature(corner(k), corner(k))).collect());
        // Out of every corner it went through, the last (z = 0.105, within the thickness
        // under it at the start) included; not on to the next, which it started under:
        // each corner handing it on to the next, it went over a metre up.
        let p = [x[0], x[1], x[2]];
        let gap = |k: usize| {
            let f = feature(corner(k), corner(k));
            feature_under_triangle_deepest(&p, &f).map_or(f64::NAN, |hit| hit.gap)
        };
        assert_eq!(n, 11);
        // At the thickness over the last, to the micrometre the push's tilt of the
        // triangle (its corners moved by their weights) takes off.
        assert!((gap(10) - 0.01).abs() < 1e-6, "{}", gap(10));
        assert!(
            (0..10).all(|k| gap(k) > 0.01),
            "{:?}",
            (0..10).map(gap).collect::<Vec<_>>()
        );
        assert!(gap(11) < 0.0, "{}", gap(11));
    }
}
