//! The end-of-step impact passes: every pair that passed through each other is put back
//! on its side and loses its approach speed; pairs still crossing after
//! [`super::IMPULSE_PASSES`] become impact zones that move as one.

use super::ccd::{self, Impact, Paths};
use super::cone::Cone;
use super::cone_tree::Search;
use super::contour::Motion;
use super::{owned_edge_pairs, owned_particles, SelfContacts, IMPULSE_PASSES, ZONE_PASSES};
use crate::contact::StepEnd;
use crate::math::union_find::find;
use crate::math::Vec3;
use crate::spatial::Aabb;

/// What the impact passes did in one step.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct ImpactCounts {
    /// Impacts answered by impulses.
    pub impacts: usize,
    /// Particles moved as part of an impact zone.
    pub zone_particles: usize,
    /// Particles stopped where they started the step, the last resort.
    pub frozen: usize,
    /// Impacts left that nothing could stop (particles moved by their pins).
    pub unresolved: usize,
    /// The passes found more impacts than their budget and stopped, leaving a state the
    /// caller must not keep.
    pub over_budget: bool,
}

/// A zone's sums: mass and mass-weighted displacement of its free members, and count and
/// summed displacement of the members that do not yield (pinned, or held by a body).
#[derive(Debug, Clone, Copy, Default)]
struct ZoneSum {
    mass: f64,
    moment: Vec3,
    held: usize,
    held_motion: Vec3,
}

#[derive(Debug, Clone)]
pub(super) struct Scratch {
    dirty: Vec<bool>,
    impacts: Vec<Impact>,
    zone: Vec<u32>,
    zoned: Vec<u32>,
    in_zone: Vec<bool>,
    sums: Vec<ZoneSum>,
    /// How far the passes moved each particle this step, and the particles they moved.
    shift: Vec<f64>,
    pub shifted: Vec<u32>,
    frozen: Vec<bool>,
    frozen_list: Vec<u32>,
}

impl Scratch {
    /// Adds `d` to how far the passes moved particle `i`.
    fn note_shift(&mut self, i: usize, d: f64) {
        if d > 0.0 && self.shift[i] == 0.0 {
            self.shifted.push(i as u32);
        }
        self.shift[i] += d;
    }

    pub fn new(n: usize) -> Self {
        Self {
            dirty: vec![false; n],
            impacts: Vec::new(),
            zone: Vec::new(),
            zoned: Vec::new(),
            in_zone: vec![false; n],
            sums: Vec::new(),
            shift: vec![0.0; n],
            shifted: Vec::new(),
            frozen: vec![false; n],
            frozen_list: Vec::new(),
        }
    }
}

impl SelfContacts {
    /// Resolves the pairs that pass through each other on the straight paths of `end`
    /// (changing its end positions and velocities). Pinned particles do not yield to
    /// impacts; particles a body holds do not yield into it. `stop` is asked as the search
    /// for impacts goes (a pass over cloth placed through itself can take minutes): the
    /// passes end when it says so, leaving a state the caller must not keep. So they do
    /// when, given a `budget`, they have found more impacts than it in all.
    pub fn resolve(
        &mut self,
        end: &mut StepEnd<'_>,
        budget: Option<usize>,
        stop: impl Fn() -> bool + Sync,
    ) -> ImpactCounts {
        let mut counts = ImpactCounts::default();
        for &i in &self.response.shifted {
            self.response.shift[i as usize] = 0.0;
        }
        self.response.shifted.clear();
        let mut found = 0;
        for pass in 0.. {
            // Pairs ending too close are put right by impulses only; zones and the last
            // resort are for pairs passing through each other.
            let impulses = pass < IMPULSE_PASSES;
            self.find_impacts(end, pass == 0, impulses, &stop);
            if stop() {
                break;
            }
            let impacts = std::mem::take(&mut self.response.impacts);
            let sc = &mut self.response;
            sc.dirty.fill(false);
            if impacts.is_empty() {
                self.response.impacts = impacts;
                break;
            }
            found += impacts.len();
            if budget.is_some_and(|b| found > b) {
                counts.impacts = found;
                counts.over_budget = true;
                self.response.impacts = impacts;
                break;
            }
            for c in &impacts {
                for (k, &p) in c.particles.iter().enumerate() {
                    if c.weights[k] != 0.0 {
                        sc.dirty[p as usize] = true;
                    }
                }
            }
            if impulses {
                for c in &impacts {
                    self.impulse(c, end);
                }
                counts.impacts += impacts.len();
            } else if pass < IMPULSE_PASSES + ZONE_PASSES {
                counts.zone_particles = self.move_zones(&impacts, end);
            } else if self.freeze(&impacts, end) == 0 {
                // Nothing left to stop: what crosses now is the pins' doing.
                counts.unresolved = impacts.len();
                self.response.impacts = impacts;
                break;
            }
            self.response.impacts = impacts;
        }
        let sc = &mut self.response;
        for &i in &sc.zoned {
            sc.in_zone[i as usize] = false;
        }
        sc.zoned.clear();
        for &i in &sc.frozen_list {
            sc.frozen[i as usize] = false;
        }
        counts.frozen = sc.frozen_list.len();
        sc.frozen_list.clear();
        counts
    }

    /// The last resort, for impacts the zones did not end: their particles stay where
    /// they started the step, at rest. The start had nothing passing through itself, so
    /// freezing more and more of the cloth ends with nothing crossing. Returns how many
    /// particles it froze now.
    fn freeze(&mut self, impacts: &[Impact], end: &mut StepEnd<'_>) -> usize {
        let (x0, x1, v1, pinned) = (end.x0, &mut *end.x1, &mut *end.v1, end.pinned);
        let mut count = 0;
        for c in impacts {
            for k in 0..4 {
                let i = c.particles[k] as usize;
                if c.weights[k] == 0.0 || pinned[i] || self.response.frozen[i] {
                    continue;
                }
                self.response.frozen[i] = true;
                self.response.frozen_list.push(i as u32);
                self.response.note_shift(i, (x1[i] - x0[i]).norm());
                x1[i] = x0[i];
                v1[i] = Vec3::zeros();
                count += 1;
            }
        }
        count
    }

    /// The impacts on the paths of `end`: of every pair (`full`), or of the pairs
    /// with a dirty particle; with `closing`, pairs ending too close too.
    fn find_impacts(
        &mut self,
        end: &StepEnd<'_>,
        full: bool,
        closing: bool,
        stop: &(impl Fn() -> bool + Sync),
    ) {
        let (x0, x1, par): (&[Vec3], &[Vec3], _) = (end.x0, end.x1, end.par);
        let topo = &self.topology;
        let touch = self.touch;
        // Near enough to cross, or to end the step too close.
        let pad = if closing {
            touch.max(ccd::MIN_SEPARATION * self.reach)
        } else {
            touch
        };
        let swept = |i: u32| Aabb::of([x0[i as usize], x1[i as usize]]);
        let over = |ids: &[u32]| ids.iter().fold(Aabb::empty(), |b, &i| b.union(&swept(i)));
        self.tree.refit(
            |t| over(&topo.triangles[t]).inflated(0.5 * pad),
            |t| {
                // The normal over the step, (u0 + t du) x (v0 + t dv), is a quadratic with
                // Bernstein coefficients u0 x v0, (u0 x v1 + u1 x v0) / 2 and u1 x v1: the
                // cone of these three holds it throughout.
                let [a, b, c] = topo.triangles[t].map(|i| (x0[i as usize], x1[i as usize]));
                let (u, v) = ((b.0 - a.0, b.1 - a.1), (c.0 - a.0, c.1 - a.1));
                Cone::along(u.0.cross(&v.0))
                    .merge(&Cone::along(u.1.cross(&v.1)))
                    .merge(&Cone::along(u.0.cross(&v.1) + u.1.cross(&v.0)))
            },
        );
        let dirty = &self.response.dirty;
        if !full {
            self.tree
                .mark(|t| topo.triangles[t].iter().any(|&i| dirty[i as usize]));
        }
        let search = Search {
            topology: topo,
            motion: Motion { start: x0, end: x1 },
            only_dirty: !full,
        };
        self.tree.plan(&search);
        let half = &self.half_thickness;
        let distance =
            |p: [u32; 4]| move |w: &[f64; 4]| (0..4).map(|k| w[k].abs() * half[p[k] as usize]).sum::<f64>();
        let paths = |p: [u32; 4]| Paths {
            start: p.map(|i| x0[i as usize]),
            end: p.map(|i| x1[i as usize]),
        };
        // In a pass after the first, only pairs with a particle moved since.
        let fresh = |p: &[u32]| full || p.iter().any(|&i| dirty[i as usize]);
        let tree = &self.tree;
        let mut impacts = std::mem::take(&mut self.response.impacts);
        self.impact_search
            .run(&tree.tasks, par, &mut impacts, |task, found| {
                if stop() {
                    return;
                }
                tree.triangle_pairs(task, &search, |s, t| {
                    if s == t {
                        return;
                    }
                    for (i, t) in owned_particles(topo, s, t).chain(owned_particles(topo, t, s)) {
                        let tri = topo.triangles[t];
                        let p = [i as u32, tri[0], tri[1], tri[2]];
                        if !fresh(&p)
                            || !swept(i as u32).inflated(pad).overlaps(&over(&tri))
                            || topo.vertex_triangle_exempt(i, t)
                        {
                            continue;
                        }
                        found.extend(ccd::particle_triangle(
                            p,
                            &paths(p),
                            touch,
                            closing.then(|| distance(p)),
                        ));
                    }
                    for (e, f) in owned_edge_pairs(topo, s, t) {
                        let (edge, other) = (topo.edges[e], topo.edges[f]);
                        let p = [edge[0], edge[1], other[0], other[1]];
                        if !fresh(&p)
                            || !over(&edge).inflated(pad).overlaps(&over(&other))
                            || topo.edge_edge_exempt(e, f)
                        {
                            continue;
                        }
                        found.extend(ccd::edge_edge(p, &paths(p), touch, closing.then(|| distance(p))));
                    }
                });
            });
        self.response.impacts = impacts;
    }

    /// One impact's inelastic impulse: the pair is moved back along the normal to its
    /// target gap and its approach along the normal stopped, with Coulomb friction on the
    /// impulse.
    fn impulse(&mut self, c: &Impact, end: &mut StepEnd<'_>) {
        let (x1, v1, masses, pinned, support) =
            (&mut *end.x1, &mut *end.v1, end.masses, end.pinned, &*end.support);
        let (w, p, n) = (c.weights, c.particles.map(|i| i as usize), c.normal);
        // Each particle moves along `w n`: a pinned one not at all, one a body holds not
        // into the body.
        let inv_mass: [f64; 4] = std::array::from_fn(|k| {
            let i = p[k];
            if pinned[i] || w[k] * n.dot(&support[i]) < 0.0 {
                0.0
            } else {
                1.0 / masses[i]
            }
        });
        let denom: f64 = (0..4).map(|k| w[k] * w[k] * inv_mass[k]).sum();
        if denom <= 0.0 {
            return;
        }
        // The least change of the particles that closes the gap moves each by `w im / denom`
        // times the gap's change: more than the whole change where the pair's only free
        // particle has a small weight (a triangle held by a body at two corners, hit near
        // them), which would fling it. No particle is moved more than the gap is; what that
        // leaves undone is found again and falls to an impact zone.
        let lever = (0..4).map(|k| w[k].abs() * inv_mass[k]).fold(0.0, f64::max) / denom;
        let denom = denom * lever.max(1.0);
        let relative = |u: &[Vec3]| (0..4).map(|k| w[k] * u[p[k]]).sum::<Vec3>();
        let short = c.target - n.dot(&relative(x1));
        if short > 0.0 {
            let lambda = short / denom;
            for k in 0..4 {
                let dx = (lambda * w[k] * inv_mass[k]) * n;
                x1[p[k]] += dx;
                self.response.note_shift(p[k], dx.norm());
            }
        }
        let mean = |values: &[f64]| 0.5 * (0..4).map(|k| w[k].abs() * values[p[k]]).sum::<f64>();
        let u = relative(v1);
        let approach = -u.dot(&n);
        if approach > 0.0 {
            let sliding = u + approach * n;
            let speed = sliding.norm();
            let cut = if speed > 0.0 {
                (mean(&self.friction) * approach / speed).min(1.0)
            } else {
                0.0
            };
            let change = approach * n - cut * sliding;
            for k in 0..4 {
                v1[p[k]] += (w[k] * inv_mass[k] / denom) * change;
            }
        }
    }

    /// Merges the particles of `impacts` into impact zones (with the zones they were in)
    /// and moves every zone as one, by its free members' mass-weighted displacement, or
    /// if it has members that do not yield, by theirs. Returns the particles in zones.
    fn move_zones(&mut self, impacts: &[Impact], end: &mut StepEnd<'_>) -> usize {
        let (x0, x1, v1, masses, pinned, support, h) = (
            end.x0,
            &mut *end.x1,
            &mut *end.v1,
            end.masses,
            end.pinned,
            &*end.support,
            end.h,
        );
        let n = self.topology.particles();
        let sc = &mut self.response;
        if sc.zoned.is_empty() {
            sc.zone.clear();
            sc.zone.extend(0..n as u32);
            sc.sums.resize(n, ZoneSum::default());
        }
        for c in impacts {
            let members = (0..4).filter(|&k| c.weights[k] != 0.0).map(|k| c.particles[k]);
            let mut root = None;
            for i in members {
                if !std::mem::replace(&mut sc.in_zone[i as usize], true) {
                    sc.zoned.push(i);
                }
                let r = find(&mut sc.zone, i);
                match root {
                    None => root = Some(r),
                    Some(q) if q != r => {
                        let (lo, hi) = (q.min(r), q.max(r));
                        sc.zone[hi as usize] = lo;
                        root = Some(lo);
                    }
                    _ => {}
                }
            }
        }
        for k in 0..sc.zoned.len() {
            let r = find(&mut sc.zone, sc.zoned[k]) as usize;
            sc.sums[r] = ZoneSum::default();
        }
        for k in 0..sc.zoned.len() {
            let i = sc.zoned[k] as usize;
            let r = find(&mut sc.zone, i as u32) as usize;
            let dx = x1[i] - x0[i];
            let s = &mut sc.sums[r];
            if !pinned[i] && support[i] == Vec3::zeros() {
                let m = masses[i];
                s.mass += m;
                s.moment += m * dx;
            } else {
                s.held += 1;
                s.held_motion += dx;
            }
        }
        for k in 0..sc.zoned.len() {
            let i = sc.zoned[k] as usize;
            if pinned[i] {
                continue;
            }
            let r = find(&mut sc.zone, i as u32) as usize;
            let s = sc.sums[r];
            let d = if s.held > 0 {
                s.held_motion / s.held as f64
            } else {
                s.moment / s.mass
            };
            let old = x1[i];
            x1[i] = x0[i] + d;
            v1[i] = d / h;
            sc.dirty[i] = true;
            sc.note_shift(i, (x1[i] - old).norm());
        }
        sc.zoned.len()
    }

    /// The particles the last [`SelfContacts::resolve`] moved, with how far (summed over
    /// its passes).
    pub fn shifted(&self) -> impl Iterator<Item = (usize, f64)> + '_ {
        self.response
            .shifted
            .iter()
            .map(|&i| (i as usize, self.response.shift[i as usize]))
    }
}
