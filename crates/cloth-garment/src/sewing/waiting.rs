//! Seam pairs placed with a stranger's cloth between their sides wait for it to leave.
//! GarmentCode lays the flared cuffs of both trouser legs flat over one another
//! (rand_1_035, rand_1_009): the right leg's flounce, a strip of 72 cm, runs from outside
//! the right leg to over the left one, so the left leg's flounce lies between the sides of
//! the right one's inner seam, and the other way round. Gathered onto their cuffs, the two
//! strips slide past each other out of each other's way; but pulled from the first step,
//! those seams closed round the other leg's flounce before the gathering had moved it, and
//! held it there (035 stopped 84 mm open). So a pair whose sides have between them, where
//! the panels were placed, the cloth of a panel sewn to neither side's panel (but to
//! another, so the seams move it) is not pulled until nothing lies between them, or until
//! the other seams have closed or stalled at the strongest pull (then it is pulled as any
//! other, and what lies between is met as the sewing meets caught cloth). A panel sewn to
//! a side's panel lies round the seam as the garment is made (a skirt under its
//! waistband's side seams, a hood over the shoulders): it is not in the way, and those
//! seams are pulled from the first step. Only the first attempt waits (see `sew_once`).

use crate::garment::Garment;
use cloth_core::{ParamError, Simulation, Vec3};

/// A seam some of whose pairs waited for the cloth between their sides to leave.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SeamWait {
    pub seam: String,
    /// How many of its pairs waited.
    pub pairs: usize,
    /// The sewing step after which the last of them was pulled; `None` while one waits.
    pub pulled_after: Option<u64>,
    /// Whether the cloth had left every one of them by then (if not, they were pulled when
    /// the other seams had closed, or stalled at the strongest pull).
    pub cleared: bool,
}

/// The pairs of [`Garment::seam_pairs`] waiting, each pair's own weight, and what waited.
pub(super) struct Waiting {
    all: Vec<[usize; 2]>,
    /// The seam of each pair of `all`.
    seam_of: Vec<usize>,
    weights: Vec<f64>,
    /// Indices into `all` of the pairs waiting, ascending, each with its entry in `seams`.
    pairs: Vec<(usize, usize)>,
    seams: Vec<SeamWait>,
    strangers: Strangers,
}

/// The seam of each pair of [`Garment::seam_pairs`].
fn seams_of_pairs(garment: &Garment) -> Vec<usize> {
    garment
        .seams
        .iter()
        .enumerate()
        .flat_map(|(s, seam)| std::iter::repeat_n(s, seam.pairs.len()))
        .collect()
}

/// Which panels are strangers to a pair: sewn to neither side's panel, but to some other.
struct Strangers {
    panel_of: Vec<usize>,
    triangle_panel: Vec<usize>,
    panels: usize,
    /// `sewn[a * panels + b]`: panels `a` and `b` share a seam.
    sewn: Vec<bool>,
    has_seams: Vec<bool>,
}

impl Strangers {
    /// The strangers of `garment`, whose seams' pairs are `all`.
    fn of(garment: &Garment, all: &[[usize; 2]]) -> Self {
        let mut panel_of = vec![0; garment.mesh.vertex_count()];
        for (t, &p) in garment.mesh.triangles().iter().zip(&garment.triangle_panel) {
            t.iter().for_each(|&i| panel_of[i] = p);
        }
        let n = garment.panel_names.len();
        let mut sewn = vec![false; n * n];
        let mut has_seams = vec![false; n];
        for &[a, b] in all {
            let (pa, pb) = (panel_of[a], panel_of[b]);
            sewn[pa * n + pb] = true;
            sewn[pb * n + pa] = true;
            has_seams[pa] = true;
            has_seams[pb] = true;
        }
        Self {
            panel_of,
            triangle_panel: garment.triangle_panel.clone(),
            panels: n,
            sewn,
            has_seams,
        }
    }

    /// Whether triangle `t` across `pair` is a stranger's. Only a panel the seams move can
    /// leave: one sewn to nothing stays where it was placed, and waiting for it would only
    /// put off the pull.
    fn across(&self, pair: [usize; 2], t: usize) -> bool {
        let p = self.triangle_panel[t];
        self.has_seams[p]
            && pair.iter().all(|&i| {
                let q = self.panel_of[i];
                q != p && !self.sewn[q * self.panels + p]
            })
    }
}

impl Waiting {
    /// The pairs of `garment`'s seams with cloth of a panel sewn to neither side's panel
    /// between their sides in `sim` (the panels as placed), set not to pull; `weights` are
    /// the pairs' own shares of the pull.
    pub(super) fn new(
        garment: &Garment,
        sim: &mut Simulation,
        weights: Vec<f64>,
    ) -> Result<Self, ParamError> {
        let all = garment.seam_pairs();
        let seam_of = seams_of_pairs(garment);
        let strangers = Strangers::of(garment, &all);
        let mut waiting: Vec<usize> = sim
            .cloth_across(&all)?
            .into_iter()
            .filter(|&(k, t)| strangers.across(all[k], t))
            .map(|(k, _)| k)
            .collect();
        waiting.dedup();
        let mut seams: Vec<SeamWait> = Vec::new();
        let mut entry_of = vec![usize::MAX; garment.seams.len()];
        let pairs = waiting
            .into_iter()
            .map(|k| {
                let s = seam_of[k];
                if entry_of[s] == usize::MAX {
                    entry_of[s] = seams.len();
                    seams.push(SeamWait {
                        seam: garment.seams[s].name.clone(),
                        pairs: 0,
                        pulled_after: None,
                        cleared: true,
                    });
                }
                seams[entry_of[s]].pairs += 1;
                (k, entry_of[s])
            })
            .collect();
        let waiting = Self {
            all,
            seam_of,
            weights,
            pairs,
            seams,
            strangers,
        };
        waiting.set_weights(sim)?;
        Ok(waiting)
    }

    /// No pair of `garment`'s seams waiting, `weights` their shares of the pull, after an
    /// attempt at sewing in which the seams `waited` did.
    pub(super) fn none(garment: &Garment, weights: Vec<f64>, waited: Vec<SeamWait>) -> Self {
        let all = garment.seam_pairs();
        Self {
            strangers: Strangers::of(garment, &all),
            all,
            seam_of: seams_of_pairs(garment),
            weights,
            pairs: Vec::new(),
            seams: waited,
        }
    }

    /// Whether any pair is waiting.
    pub(super) fn any(&self) -> bool {
        !self.pairs.is_empty()
    }

    /// The seams that waited so far.
    pub(super) fn seams(&self) -> &[SeamWait] {
        &self.seams
    }

    /// The seam with the widest gap at `x` of the pairs being pulled, and the gap, m.
    pub(super) fn widest_pulled(&self, x: &[Vec3]) -> (usize, f64) {
        let mut waiting = self.pairs.iter().map(|&(k, _)| k).peekable();
        let mut widest = (0, 0.0f64);
        for (k, &[a, b]) in self.all.iter().enumerate() {
            if waiting.peek() == Some(&k) {
                waiting.next();
            } else if (x[a] - x[b]).norm() > widest.1 {
                widest = (self.seam_of[k], (x[a] - x[b]).norm());
            }
        }
        widest
    }

    /// Pulls the waiting pairs with no stranger's cloth between their sides in `sim` now,
    /// after sewing step `step`.
    pub(super) fn update(&mut self, sim: &mut Simulation, step: u64) -> Result<(), ParamError> {
        if self.pairs.is_empty() {
            return Ok(());
        }
        let asked: Vec<[usize; 2]> = self.pairs.iter().map(|&(k, _)| self.all[k]).collect();
        // Sorted by pair.
        let mut across: Vec<usize> = sim
            .cloth_across(&asked)?
            .into_iter()
            .filter(|&(j, t)| self.strangers.across(asked[j], t))
            .map(|(j, _)| j)
            .collect();
        across.dedup();
        let before = self.pairs.len();
        let mut j = 0;
        self.pairs.retain(|_| {
            let keep = across.binary_search(&j).is_ok();
            j += 1;
            keep
        });
        if self.pairs.len() < before {
            self.note_pulled(step);
            self.set_weights(sim)?;
        }
        Ok(())
    }

    /// Pulls every waiting pair, after sewing step `step`: the others have closed, or
    /// stalled.
    pub(super) fn release(&mut self, sim: &mut Simulation, step: u64) -> Result<(), ParamError> {
        for &(_, e) in &self.pairs {
            self.seams[e].cleared = false;
        }
        self.pairs.clear();
        self.note_pulled(step);
        self.set_weights(sim)
    }

    /// Notes step `step` for the seams none of whose pairs waits any more.
    fn note_pulled(&mut self, step: u64) {
        for (e, seam) in self.seams.iter_mut().enumerate() {
            if seam.pulled_after.is_none() && !self.pairs.iter().any(|&(_, f)| f == e) {
                seam.pulled_after = Some(step);
            }
        }
    }

    /// Sets the pull's weights in `sim`: none for the pairs waiting.
    fn set_weights(&self, sim: &mut Simulation) -> Result<(), ParamError> {
        let mut weights = self.weights.clone();
        for &(k, _) in &self.pairs {
            weights[k] = 0.0;
        }
        sim.set_seam_weights(&weights)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::garment::GarmentBuilder;
    use crate::pattern::Pattern;
    use cloth_core::{Fabric, SeamPull, SimulationBuilder};

    /// How the panel across the tube's gap is sewn.
    #[derive(Clone, Copy, PartialEq)]
    enum Stranger {
        /// To a tab of its own, away from the tube: the seams move it.
        ToTab,
        /// To the tube's front.
        ToFront,
        /// To nothing.
        Free,
    }

    /// A tube of two 20 x 10 cm panels, 10 cm apart, sewn at both sides (the right side at
    /// x = 10 cm, the left at -10), a 10 x 14 cm panel across the right side's gap in the
    /// plane between them, sewn as `stranger` says, and a tab beside it, 5 mm away.
    fn tube_and_stranger(stranger: Stranger) -> Garment {
        let square = r#"[
    { start = [0, 0], name = "hem" },
    { start = [10, 0], name = "right" },
    { start = [10, 14], name = "top" },
    { start = [0, 14], name = "left" },
]"#;
        let strip = r#"[
    { start = [-10, 0], name = "hem" },
    { start = [10, 0], name = "right" },
    { start = [10, 10], name = "top" },
    { start = [-10, 10], name = "left" },
]"#;
        let mut text = format!(
            r#"
units = "cm"
[[panels]]
name = "front"
outline = {strip}
placement = {{ translation = [0, 0, 5] }}

[[panels]]
name = "back"
outline = {strip}
placement = {{ rotation = [0, 180, 0], translation = [0, 0, -5] }}

[[panels]]
name = "stranger"
outline = {square}
placement = {{ translation = [5, -2, 0] }}

[[panels]]
name = "tab"
outline = {square}
placement = {{ translation = [15.5, -2, 0] }}

[[seams]]
a = {{ panel = "front", edge = "right" }}
b = {{ panel = "back", edge = "left" }}

[[seams]]
a = {{ panel = "front", edge = "left" }}
b = {{ panel = "back", edge = "right" }}
"#
        );
        let (a, b) = match stranger {
            Stranger::ToTab => (("stranger", "right"), ("tab", "left")),
            Stranger::ToFront => (("stranger", "top"), ("front", "hem")),
            Stranger::Free => (("tab", "top"), ("front", "hem")),
        };
        text += &format!(
            "\n[[seams]]\na = {{ panel = \"{}\", edge = \"{}\" }}\nb = {{ panel = \"{}\", edge = \"{}\" }}\n",
            a.0, a.1, b.0, b.1
        );
        let pattern = Pattern::from_toml_str(&text, "tube.toml").unwrap();
        GarmentBuilder::new(pattern).edge_length(0.025).build().unwrap()
    }

    fn simulation(garment: &Garment) -> Simulation {
        let mut sim = SimulationBuilder::new(garment.mesh.clone(), Fabric::cotton_like())
            .seams(garment.seam_pairs())
            .build()
            .unwrap();
        sim.set_seam_pull(SeamPull {
            stiffness: 20.0,
            reach: 0.01,
            damping: 0.0,
        })
        .unwrap();
        sim
    }

    /// The widest gap of seam `s`'s pairs in `sim`, m.
    fn gap(garment: &Garment, sim: &Simulation, s: usize) -> f64 {
        let x = sim.positions();
        garment.seams[s]
            .pairs
            .iter()
            .map(|&[a, b]| (x[a] - x[b]).norm())
            .fold(0.0, f64::max)
    }

    #[test]
    fn pairs_with_a_strangers_cloth_between_wait_until_it_leaves() {
        let garment = tube_and_stranger(Stranger::ToTab);
        let mut sim = simulation(&garment);
        let weights = vec![1.0; garment.seam_pairs().len()];
        let mut waiting = Waiting::new(&garment, &mut sim, weights).unwrap();
        // The right side's pairs at heights the stranger spans wait; the left side's do not.
        assert!(waiting.any());
        assert_eq!(waiting.seams().len(), 1);
        assert_eq!(waiting.seams()[0].seam, garment.seams[0].name);
        assert!(waiting.seams()[0].pairs > 0);
        let (right, left) = (gap(&garment, &sim, 0), gap(&garment, &sim, 1));
        for step in 1..=5 {
            sim.step().unwrap();
            waiting.update(&mut sim, step).unwrap();
        }
        assert!(waiting.any(), "the stranger is still there");
        assert!(gap(&garment, &sim, 1) < 0.9 * left, "the left side is pulled");
        let (seam, widest) = waiting.widest_pulled(sim.positions());
        assert_eq!(seam, 1);
        assert!(widest < gap(&garment, &sim, 0));
        // The waiting pairs are not pulled: the widest of the right side keeps its gap.
        assert!((gap(&garment, &sim, 0) - right).abs() < 0.1 * right);
        // The stranger taken away, the pairs are let go.
        let stranger: Vec<usize> = garment.panel_members()[2].clone();
        let mut x = sim.positions().to_vec();
        stranger.iter().for_each(|&i| x[i].x += 1.0);
        sim.set_positions(&x).unwrap();
        waiting.update(&mut sim, 5).unwrap();
        assert!(!waiting.any());
        assert_eq!(waiting.seams()[0].pulled_after, Some(5));
        assert!(waiting.seams()[0].cleared);
        let right = gap(&garment, &sim, 0);
        for step in 6..=10 {
            sim.step().unwrap();
            waiting.update(&mut sim, step).unwrap();
        }
        assert!(gap(&garment, &sim, 0) < 0.9 * right, "the right side is pulled");
    }

    #[test]
    fn a_panel_sewn_to_a_side_or_to_nothing_is_not_waited_for_and_released_pairs_are_told_not_cleared() {
        for stranger in [Stranger::ToFront, Stranger::Free] {
            let garment = tube_and_stranger(stranger);
            let mut sim = simulation(&garment);
            let weights = vec![1.0; garment.seam_pairs().len()];
            assert!(!Waiting::new(&garment, &mut sim, weights).unwrap().any());
        }

        let garment = tube_and_stranger(Stranger::ToTab);
        let mut sim = simulation(&garment);
        let weights = vec![1.0; garment.seam_pairs().len()];
        let mut waiting = Waiting::new(&garment, &mut sim, weights).unwrap();
        waiting.release(&mut sim, 7).unwrap();
        assert!(!waiting.any());
        assert_eq!(waiting.seams()[0].pulled_after, Some(7));
        assert!(!waiting.seams()[0].cleared);
    }
}
