//! Layers caught between a seam's sides while it closes (see [`cloth_core::LayerPass`]).
//! A layer is to end on the side of the closed seam where the rest of it lies: a collar
//! caught at a shoulder by its corner, lying over both shoulders round it, ends outside;
//! a lining whose edge slipped between the sides ends inside. So the layer's cloth round
//! the pair (past the part caught) is counted on either side of the seam's panels there,
//! outward being away from the bodies; lying outside, the side farther from the bodies is
//! let through it and the nearer one carries it out as the seam closes; inside, the other
//! way round. While it passes, the layer's cloth still on the wrong side of the side is
//! moved the way it is to go: the side's edge goes through the layer as the seam closes,
//! but nothing else takes the rest of the layer round the pair through the side, and the
//! two stayed crossed along the pass's border to the weld.

use crate::garment::Garment;
use cloth_core::{Collider, LayerPass, Neighbours, Proximity, Simulation, Vec3};
use std::collections::BTreeMap;

/// A layer of cloth found across a seam's pairs, and the panel let through it.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct CaughtLayer {
    /// The sewing step after which it was found.
    pub step: u64,
    /// The seam of the first pair it lay across.
    pub seam: String,
    /// The panel caught, and the panel let through it.
    pub layer: String,
    pub passing: String,
    /// How many of the seams' pairs it lay across.
    pub pairs: usize,
    /// The step after which the two were through each other and apart; `None` if they
    /// were not by the weld.
    pub passed: Option<u64>,
}

/// Rings of particles round the triangles found across a pair that make up the layer let
/// through, and round the pair's particle that make up the side let through it: enough
/// cloth on both that the side's edge comes out of the layer whole, not a few particles of
/// it hooked through.
const LAYER_RINGS: usize = 2;
const SIDE_RINGS: usize = 3;

/// Pairs nearer than this are closed, m: nothing lies between.
const CLOSED: f64 = 1e-6;

/// How far from the bodies a particle is looked at, m; beyond, it is as far as any.
const REACH: f64 = 0.2;

/// The speed at which a layer being let through is moved the way it is to go, m/s (see
/// [`Catcher::drive`]): a layer's thickness in a sewing step or two.
const DRIVE_SPEED: f64 = 0.03;

/// The layer's cloth counted for the side it lies on: within `LOOK` of the pair's middle,
/// and farther than `CAUGHT` from the pair's segment (the part caught between lies on
/// neither side), m.
const LOOK: f64 = 0.05;
const CAUGHT: f64 = 0.015;

/// The cloth found across the pairs of one panel's seams, caught from one other panel:
/// the particles of the triangles found, the particles of the side let through it, how
/// many pairs, and the first pair's seam.
struct Group {
    layer: Vec<usize>,
    side: Vec<usize>,
    pairs: usize,
    seam: usize,
    /// Votes for the layer's going outwards (positive) or inwards.
    way: f64,
}

/// A pair's two particles, the one whose side is let through a layer first, and the way
/// the layer is to go (1 outwards, -1 inwards).
type Chosen = ([usize; 2], f64);

/// Where a caught layer's cloth lies round the pair it was caught in.
enum Lies {
    Outside,
    Inside,
    Unknown,
}

/// The distance of `p` from the segment `a b`.
fn segment_distance(p: &Vec3, a: &Vec3, b: &Vec3) -> f64 {
    let ab = b - a;
    let t = if ab.norm_squared() > 0.0 {
        ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + t * ab)).norm()
}

/// The particle of `among` nearest particle `i` at `x`, if one is within `within` (m).
fn nearest(x: &[Vec3], among: &[usize], i: usize, within: f64) -> Option<usize> {
    among
        .iter()
        .map(|&q| (q, (x[q] - x[i]).norm()))
        .filter(|&(_, d)| d < within)
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(q, _)| q)
}

/// Finds the layers caught in the seams of a garment being sewn.
pub(super) struct Catcher {
    pairs: Vec<[usize; 2]>,
    /// The seam of each pair.
    seam_of: Vec<usize>,
    /// The panel of each particle.
    panel_of: Vec<usize>,
    /// Each particle's neighbours along the mesh's edges.
    neighbours: Neighbours,
    /// What was found, the simulation's pass for each, and the way its layer is to go:
    /// 1 outwards (away from the bodies), -1 inwards.
    found: Vec<CaughtLayer>,
    pass_of: Vec<usize>,
    way: Vec<f64>,
}

impl Catcher {
    pub(super) fn new(garment: &Garment) -> Self {
        let n = garment.mesh.vertex_count();
        let (mut pairs, mut seam_of) = (Vec::new(), Vec::new());
        for (k, seam) in garment.seams.iter().enumerate() {
            pairs.extend(seam.pairs.iter().copied());
            seam_of.extend(std::iter::repeat_n(k, seam.pairs.len()));
        }
        let mut panel_of = vec![0; n];
        for (t, tri) in garment.mesh.triangles().iter().enumerate() {
            for &i in tri {
                panel_of[i] = garment.triangle_panel[t];
            }
        }
        Self {
            pairs,
            seam_of,
            panel_of,
            neighbours: Neighbours::of(&garment.mesh),
            found: Vec::new(),
            pass_of: Vec::new(),
            way: Vec::new(),
        }
    }

    /// Finds the cloth lying across the seams' open pairs of `sim` after sewing step
    /// `step`, not already let through, and lets a side of each through it; returns how
    /// many layers were found.
    pub(super) fn catch(
        &mut self,
        garment: &Garment,
        sim: &mut Simulation,
        bodies: &dyn Collider,
        step: u64,
    ) -> usize {
        let x = sim.positions();
        let open: Vec<usize> = (0..self.pairs.len())
            .filter(|&k| {
                let [a, b] = self.pairs[k];
                (x[a] - x[b]).norm() > CLOSED
            })
            .collect();
        let segments: Vec<[usize; 2]> = open.iter().map(|&k| self.pairs[k]).collect();
        // The seams' pairs are the garment's particles, and the simulation is of its mesh.
        let across = sim.cloth_across(&segments).unwrap_or_default();
        if across.is_empty() {
            return 0;
        }
        let holding: Vec<&LayerPass> = sim
            .layer_passes()
            .iter()
            .filter(|p| p.ended.is_none())
            .map(|p| &p.pass)
            .collect();
        let t = sim.time();
        let distance = |i: usize| match bodies.sweep(t, &x[i], t, &x[i], 0.0, REACH) {
            Proximity::Near(p) => p.distance,
            Proximity::Far { .. } => f64::INFINITY,
        };
        let outward = |i: usize| match bodies.sweep(t, &x[i], t, &x[i], 0.0, REACH) {
            Proximity::Near(p) => Some(p.normal),
            Proximity::Far { .. } => None,
        };
        let triangles = garment.mesh.triangles();
        let mut groups: BTreeMap<(usize, usize), Group> = BTreeMap::new();
        // The (pair, layer) last looked at (they come sorted by pair), the side to let
        // through first.
        let mut sides: Option<((usize, usize), Chosen)> = None;
        for (k, tri) in across {
            let pair = open[k];
            let layer = garment.triangle_panel[tri];
            let (order, way) = match sides {
                Some((last, chosen)) if last == (pair, layer) => chosen,
                _ => {
                    let [a, b] = self.pairs[pair];
                    let by_distance = if distance(a) > distance(b) { [a, b] } else { [b, a] };
                    let (order, way) = match self.layer_lies(x, self.pairs[pair], layer, &outward) {
                        Lies::Inside => ([by_distance[1], by_distance[0]], -1.0),
                        Lies::Outside | Lies::Unknown => (by_distance, 1.0),
                    };
                    sides = Some(((pair, layer), (order, way)));
                    (order, way)
                }
            };
            let side = match order.into_iter().find(|&i| self.panel_of[i] != layer) {
                Some(side) => side,
                None => continue,
            };
            // A pass's particles are sorted (see `Neighbours::around`).
            let covered = holding.iter().any(|p| {
                p.side.binary_search(&side).is_ok()
                    && triangles[tri].iter().all(|i| p.layer.binary_search(i).is_ok())
            });
            if covered {
                continue;
            }
            let group = groups
                .entry((layer, self.panel_of[side]))
                .or_insert_with(|| Group {
                    layer: Vec::new(),
                    side: Vec::new(),
                    pairs: 0,
                    seam: self.seam_of[pair],
                    way: 0.0,
                });
            group.layer.extend_from_slice(&triangles[tri]);
            group.side.push(side);
            group.pairs += 1;
            group.way += way;
        }
        let (first, first_found) = (sim.layer_passes().len(), self.found.len());
        let ways: Vec<f64> = groups.values().map(|g| g.way.signum()).collect();
        let (passes, caught): (Vec<LayerPass>, Vec<CaughtLayer>) = groups
            .into_iter()
            .map(|((layer, passing), group)| {
                let pass = LayerPass {
                    layer: self.neighbours.around(group.layer, LAYER_RINGS),
                    side: self.neighbours.around(group.side, SIDE_RINGS),
                };
                let caught = CaughtLayer {
                    step,
                    seam: garment.seams[group.seam].name.clone(),
                    layer: garment.panel_names[layer].clone(),
                    passing: garment.panel_names[passing].clone(),
                    pairs: group.pairs,
                    passed: None,
                };
                (pass, caught)
            })
            .unzip();
        // Grown along the garment's own edges, the passes hold the simulation's particles.
        if sim.add_layer_passes(passes).is_err() {
            return 0;
        }
        self.pass_of.extend(first..first + caught.len());
        self.way.extend(ways);
        self.found.extend(caught);
        self.found.len() - first_found
    }

    /// Which side of the seam's panels the cloth of panel `layer` lies on round `pair`
    /// at `x`, by count of its particles within [`LOOK`] of the pair's middle and farther
    /// than [`CAUGHT`] from its segment, each against the nearest particle of the pair's
    /// panels within [`LOOK`] of it, outward along `outward` there (away from the bodies).
    fn layer_lies(
        &self,
        x: &[Vec3],
        [a, b]: [usize; 2],
        layer: usize,
        outward: &dyn Fn(usize) -> Option<Vec3>,
    ) -> Lies {
        let middle = 0.5 * (x[a] + x[b]);
        let panels = [self.panel_of[a], self.panel_of[b]];
        let seam_side: Vec<usize> = (0..x.len())
            .filter(|&i| panels.contains(&self.panel_of[i]) && (x[i] - middle).norm() < 2.0 * LOOK)
            .collect();
        let (mut out, mut inside) = (0usize, 0usize);
        let mut normals: BTreeMap<usize, Option<Vec3>> = BTreeMap::new();
        for i in (0..x.len()).filter(|&i| self.panel_of[i] == layer && (x[i] - middle).norm() < LOOK) {
            if segment_distance(&x[i], &x[a], &x[b]) < CAUGHT {
                continue;
            }
            let Some(q) = nearest(x, &seam_side, i, LOOK) else {
                continue;
            };
            let Some(n) = *normals.entry(q).or_insert_with(|| outward(q)) else {
                continue;
            };
            if (x[i] - x[q]).dot(&n) > 0.0 {
                out += 1;
            } else {
                inside += 1;
            }
        }
        match out.cmp(&inside) {
            std::cmp::Ordering::Greater => Lies::Outside,
            std::cmp::Ordering::Less => Lies::Inside,
            std::cmp::Ordering::Equal => Lies::Unknown,
        }
    }

    /// Moves the cloth of each layer still being let through in `sim` the way it is to go,
    /// at [`DRIVE_SPEED`] at least: the side's edge goes through the layer as the seam
    /// closes, but nothing else takes the rest of the layer round the pair through the
    /// side (a collar lying over the shoulder beyond the seam's edge), and the pass would
    /// hold to the weld with the two through each other along its border.
    pub(super) fn drive(&self, sim: &mut Simulation, bodies: &dyn Collider) {
        let passes = sim.layer_passes();
        // Called before every sewing step: nothing copied while no pass holds.
        if !self
            .pass_of
            .iter()
            .any(|&k| passes.get(k).is_some_and(|p| p.ended.is_none()))
        {
            return;
        }
        let (t, x) = (sim.time(), sim.positions());
        let mut v = sim.velocities().to_vec();
        let mut moved = false;
        for (&k, &way) in self.pass_of.iter().zip(&self.way) {
            let Some(p) = passes.get(k).filter(|p| p.ended.is_none()) else {
                continue;
            };
            for &i in &p.pass.layer {
                // Only the layer's cloth still on the wrong side of the side's nearest.
                let Some(q) = nearest(x, &p.pass.side, i, CAUGHT) else {
                    continue;
                };
                let Proximity::Near(near) = bodies.sweep(t, &x[i], t, &x[i], 0.0, REACH) else {
                    continue;
                };
                let dir = way * near.normal;
                if (x[i] - x[q]).dot(&dir) > 0.0 {
                    continue;
                }
                let along = v[i].dot(&dir);
                if along < DRIVE_SPEED {
                    v[i] += (DRIVE_SPEED - along) * dir;
                    moved = true;
                }
            }
        }
        // The velocities are the simulation's own, one per particle, finite: refused only
        // were they not, and then the layer is left as it moves.
        if moved {
            let _ = sim.set_velocities(&v);
        }
    }

    /// Notes which of the layers found have passed in `sim`, and returns them all.
    pub(super) fn update(&mut self, sim: &Simulation) -> &[CaughtLayer] {
        let passes = sim.layer_passes();
        for (caught, &k) in self.found.iter_mut().zip(&self.pass_of) {
            caught.passed = passes.get(k).and_then(|p| p.ended);
        }
        &self.found
    }
}
