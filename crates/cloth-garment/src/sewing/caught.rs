//! Layers caught between a seam's sides while it closes (see [`cloth_core::LayerPass`]).
//! A layer is to end on the side of the closed seam where the rest of it lies: a collar
//! caught at a shoulder by its corner, lying over both shoulders round it, ends outside;
//! a lining whose edge slipped between the sides ends inside. So the layer's cloth round
//! the pair (past the part caught) is counted on either side of the seam's panels there,
//! outward being away from the bodies; lying outside, the side farther from the bodies is
//! let through it and the nearer one carries it out as the seam closes; inside, the other
//! way round (a layer of one of the seam's own panels, folded over its edge, can only let
//! the other panel through, and goes whichever way that takes it). While it passes, the
//! layer's cloth still on the wrong side of the side is moved the way it is to go: the
//! side's edge goes through the layer as the seam closes, but nothing else takes the rest
//! of the layer round the pair through the side, and the two stayed crossed along the
//! pass's border to the weld.

use crate::garment::Garment;
use cloth_core::{math::Vec3, Collider, LayerPass, Neighbours, ParticlePath, Proximity, Simulation};
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
/// many pairs, the first pair's seam, and the pairs' votes for the way the layer goes
/// (outwards positive). One pass is driven one way, the majority's (outwards on a tie, the
/// way a layer went before its side was counted): split by each pair's way, neighbouring
/// pairs voting differently made two passes over the same cloth driven against each other.
struct Group {
    layer: Vec<usize>,
    side: Vec<usize>,
    pairs: usize,
    seam: usize,
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

/// The side let through a layer of panel `layer`, and the way the layer is to go, from the
/// side `chosen` first: that may be the layer's own panel (a panel caught in its own
/// seam), and then the other side is let through, and the layer goes the other way round
/// it. `None` if both sides are the layer's.
fn let_through(([first, second], way): Chosen, panel_of: &[usize], layer: usize) -> Option<(usize, f64)> {
    match [first, second].map(|i| panel_of[i] != layer) {
        [true, _] => Some((first, way)),
        [false, true] => Some((second, -way)),
        [false, false] => None,
    }
}

/// Which side of the seam's panels the cloth of panel `layer` lies on round `pair` at
/// `x` (each particle's panel in `panel_of`), by count of its particles within [`LOOK`] of
/// the pair's middle and farther than [`CAUGHT`] from its segment, each against the
/// nearest particle of the pair's panels within [`LOOK`] of it, outward along `outward`
/// there (away from the bodies); particles level with theirs count for neither side. A
/// layer of one of the pair's panels is all counted against the other panel, its cloth
/// beside the pair too: where it lies against that panel there is the side it keeps.
fn layer_lies(
    x: &[Vec3],
    panel_of: &[usize],
    [a, b]: [usize; 2],
    layer: usize,
    outward: &dyn Fn(usize) -> Option<Vec3>,
) -> Lies {
    let middle = 0.5 * (x[a] + x[b]);
    let panels = [panel_of[a], panel_of[b]];
    // A layer caught in its own panel's seam is counted against the other panel
    // only: its own particles would be their own nearest, on neither side.
    let seam_side: Vec<usize> = (0..x.len())
        .filter(|&i| {
            panel_of[i] != layer && panels.contains(&panel_of[i]) && (x[i] - middle).norm() < 2.0 * LOOK
        })
        .collect();
    let (mut out, mut inside) = (0usize, 0usize);
    let mut normals: BTreeMap<usize, Option<Vec3>> = BTreeMap::new();
    for i in (0..x.len()).filter(|&i| panel_of[i] == layer && (x[i] - middle).norm() < LOOK) {
        if segment_distance(&x[i], &x[a], &x[b]) < CAUGHT {
            continue;
        }
        let Some(q) = nearest(x, &seam_side, i, LOOK) else {
            continue;
        };
        let Some(n) = *normals.entry(q).or_insert_with(|| outward(q)) else {
            continue;
        };
        let off = (x[i] - x[q]).dot(&n);
        if off > 0.0 {
            out += 1;
        } else if off < 0.0 {
            inside += 1;
        }
    }
    match out.cmp(&inside) {
        std::cmp::Ordering::Greater => Lies::Outside,
        std::cmp::Ordering::Less => Lies::Inside,
        std::cmp::Ordering::Equal => Lies::Unknown,
    }
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
    /// The simulation's velocities as the drive changes them (scratch, kept between steps).
    velocities: Vec<Vec3>,
}

impl Catcher {
    pub(super) fn new(garment: &Garment) -> Self {
        let (mut pairs, mut seam_of) = (Vec::new(), Vec::new());
        for (k, seam) in garment.seams.iter().enumerate() {
            pairs.extend(seam.pairs.iter().copied());
            seam_of.extend(std::iter::repeat_n(k, seam.pairs.len()));
        }
        let panel_of = garment.particle_panels();
        Self {
            pairs,
            seam_of,
            panel_of,
            neighbours: Neighbours::of(&garment.mesh),
            found: Vec::new(),
            pass_of: Vec::new(),
            way: Vec::new(),
            velocities: Vec::new(),
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
        let near = |i: usize| match bodies.sweep(&ParticlePath::still(t, x[i]), 0.0, REACH) {
            Proximity::Near(p) => Some(p),
            Proximity::Far { .. } => None,
        };
        let distance = |i: usize| near(i).map_or(f64::INFINITY, |p| p.distance);
        let outward = |i: usize| near(i).map(|p| p.normal);
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
                    let (order, way) = match layer_lies(x, &self.panel_of, self.pairs[pair], layer, &outward)
                    {
                        Lies::Inside => ([by_distance[1], by_distance[0]], -1.0),
                        Lies::Outside | Lies::Unknown => (by_distance, 1.0),
                    };
                    sides = Some(((pair, layer), (order, way)));
                    (order, way)
                }
            };
            let Some((side, way)) = let_through((order, way), &self.panel_of, layer) else {
                continue;
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
        let ways: Vec<f64> = groups
            .values()
            .map(|g| if g.way >= 0.0 { 1.0 } else { -1.0 })
            .collect();
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

    /// Moves the cloth of each layer still being let through in `sim` the way it is to go,
    /// at [`DRIVE_SPEED`] at least: the side's edge goes through the layer as the seam
    /// closes, but nothing else takes the rest of the layer round the pair through the
    /// side (a collar lying over the shoulder beyond the seam's edge), and the pass would
    /// hold to the weld with the two through each other along its border.
    pub(super) fn drive(&mut self, sim: &mut Simulation, bodies: &dyn Collider) {
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
        let v = &mut self.velocities;
        v.clear();
        v.extend_from_slice(sim.velocities());
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
                let Proximity::Near(near) = bodies.sweep(&ParticlePath::still(t, x[i]), 0.0, REACH) else {
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
            let _ = sim.set_velocities(v);
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A seam's pair across x = 0 at z = 0 (particles 0 of panel 0 and 1 of panel 1),
    /// each panel's cloth beside it at z = 0 (2 of panel 0, 3 of panel 1), and a layer's
    /// cloth at the heights `layer` (z, m), 2 cm along y from the pair, of panel `panel`.
    fn seam_with_layer(layer: &[f64], panel: usize) -> (Vec<Vec3>, Vec<usize>) {
        let mut x = vec![
            Vec3::new(-0.005, 0.0, 0.0),
            Vec3::new(0.005, 0.0, 0.0),
            Vec3::new(-0.005, 0.02, 0.0),
            Vec3::new(0.005, 0.02, 0.0),
        ];
        let mut panel_of = vec![0, 1, 0, 1];
        for &z in layer {
            x.push(Vec3::new(0.004, 0.021, z));
            panel_of.push(panel);
        }
        (x, panel_of)
    }

    const UP: &dyn Fn(usize) -> Option<Vec3> = &|_| Some(Vec3::z());

    #[test]
    fn a_layer_is_counted_on_the_side_of_the_seams_panels_most_of_its_cloth_lies() {
        let (x, panel_of) = seam_with_layer(&[0.004, 0.005, -0.003], 2);
        assert!(matches!(layer_lies(&x, &panel_of, [0, 1], 2, UP), Lies::Outside));
        let (x, panel_of) = seam_with_layer(&[-0.004, -0.005, 0.003], 2);
        assert!(matches!(layer_lies(&x, &panel_of, [0, 1], 2, UP), Lies::Inside));
        // Level with the seam's panels: neither side.
        let (x, panel_of) = seam_with_layer(&[0.0, 0.0], 2);
        assert!(matches!(layer_lies(&x, &panel_of, [0, 1], 2, UP), Lies::Unknown));
        // No bodies near: unknown.
        let (x, panel_of) = seam_with_layer(&[0.004], 2);
        assert!(matches!(
            layer_lies(&x, &panel_of, [0, 1], 2, &|_| None),
            Lies::Unknown
        ));
    }

    #[test]
    fn a_layer_of_one_of_the_seams_panels_is_counted_against_the_other() {
        // The layer's cloth is panel 1's: panel 1's own particles beside the pair are not
        // its nearest (each would be level with itself), panel 0's are.
        let (x, panel_of) = seam_with_layer(&[0.004, 0.006], 1);
        assert!(matches!(layer_lies(&x, &panel_of, [0, 1], 1, UP), Lies::Outside));
        let (x, panel_of) = seam_with_layer(&[-0.004, -0.006], 1);
        assert!(matches!(layer_lies(&x, &panel_of, [0, 1], 1, UP), Lies::Inside));
    }

    #[test]
    fn a_side_of_the_layers_own_panel_hands_the_pass_to_the_other_side_the_other_way() {
        let panel_of = [0, 1, 2];
        // The outer side (particle 0, panel 0) first, the layer outwards.
        assert_eq!(let_through(([0, 1], 1.0), &panel_of, 2), Some((0, 1.0)));
        // The layer is panel 0's: panel 1 is let through, and the layer goes inwards.
        assert_eq!(let_through(([0, 1], 1.0), &panel_of, 0), Some((1, -1.0)));
        assert_eq!(let_through(([1, 0], -1.0), &panel_of, 1), Some((0, 1.0)));
        // Both sides the layer's: nothing to let through.
        assert_eq!(let_through(([0, 0], 1.0), &panel_of, 0), None);
    }
}
