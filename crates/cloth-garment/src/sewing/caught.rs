//! Layers caught between a seam's sides while it closes (see [`cloth_core::LayerPass`]).
//! Of the two sides, the one farther from the bodies is let through the layer: the nearer
//! one carries it out along with it as the seam closes, so it ends outside the seam, where
//! GarmentCode means its hoods, collars and sleeves to hang.

use crate::garment::Garment;
use cloth_core::{Collider, LayerPass, Neighbours, Proximity, Simulation};
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

/// The cloth found across the pairs of one panel's seams, caught from one other panel:
/// the particles of the triangles found, the particles of the side let through it, how
/// many pairs, and the first pair's seam.
struct Group {
    layer: Vec<usize>,
    side: Vec<usize>,
    pairs: usize,
    seam: usize,
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
    /// What was found, and the simulation's pass for each.
    found: Vec<CaughtLayer>,
    pass_of: Vec<usize>,
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
        let triangles = garment.mesh.triangles();
        let mut groups: BTreeMap<(usize, usize), Group> = BTreeMap::new();
        // The pair last looked at (they come sorted by pair), outer side first.
        let mut sides: Option<(usize, [usize; 2])> = None;
        for (k, tri) in across {
            let pair = open[k];
            let [outer, inner] = match sides {
                Some((last, sides)) if last == pair => sides,
                _ => {
                    let [a, b] = self.pairs[pair];
                    let by_distance = if distance(a) > distance(b) { [a, b] } else { [b, a] };
                    sides = Some((pair, by_distance));
                    by_distance
                }
            };
            let layer = garment.triangle_panel[tri];
            let side = match [outer, inner].into_iter().find(|&i| self.panel_of[i] != layer) {
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
                });
            group.layer.extend_from_slice(&triangles[tri]);
            group.side.push(side);
            group.pairs += 1;
        }
        let (first, first_found) = (sim.layer_passes().len(), self.found.len());
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
        self.found.extend(caught);
        self.found.len() - first_found
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
