//! Closing seams the strongest pull cannot. A pull at 1,024 times its strength that still
//! leaves seams open is met by cloth that stiffens faster than the pull grows: a collar
//! cut shorter than the neckline it is sewn to (GarmentCode's rand_1_037 stopped 8.8 mm
//! open, rand_1_099 7.3 mm), a tube too small for the post it goes round. Where nothing
//! lies between the open pairs' sides, no layer or body is crossed by bringing them
//! together, so they are zipped: drawn towards each other by moving their particles, a
//! step at a time, each step's solve spreading the stretch into the cloth beside them,
//! until they meet. The drape then shows the stretch the design asks of the fabric.
//! Where only cloth lies between (a sleeve folded into the side seam under it), the pairs
//! are welded where they stand and the weld's crossings are let through (see
//! [`AtStrongest`]). Where a body lies between, or cloth across a gap wider than such a
//! weld reaches, the sewing fails instead, saying what lies between.

use crate::garment::{Garment, HeldOpen};
use cloth_core::{math::Vec3, Collider, ParamError, Simulation};

/// The pairs of `garment`'s seams farther apart than `tolerance` at `x`.
pub(super) fn open_pairs(garment: &Garment, x: &[Vec3], tolerance: f64) -> Vec<[usize; 2]> {
    garment
        .seam_pairs()
        .into_iter()
        .filter(|&[a, b]| (x[a] - x[b]).norm() > tolerance)
        .collect()
}

/// What lies between the sides of `pairs` in `sim`: cloth across any of them (the
/// self-collision's test, near particles left out), else a body one passes through, else
/// nothing.
pub(super) fn held_open(
    garment: &Garment,
    sim: &Simulation,
    bodies: &dyn Collider,
    pairs: &[[usize; 2]],
) -> HeldOpen {
    // The pairs are the garment's, and the simulation is of its mesh.
    let across = sim.cloth_across(pairs).unwrap_or_default();
    let mut panels: Vec<String> = across
        .iter()
        .map(|&(_, t)| garment.panel_names[garment.triangle_panel[t]].clone())
        .collect();
    panels.sort();
    panels.dedup();
    if !panels.is_empty() {
        HeldOpen::Cloth(panels)
    } else if through_body(sim, bodies, pairs) {
        HeldOpen::Body
    } else {
        HeldOpen::Nothing
    }
}

/// Whether the straight line between the sides of any of `pairs` in `sim` passes through
/// a body.
pub(super) fn through_body(sim: &Simulation, bodies: &dyn Collider, pairs: &[[usize; 2]]) -> bool {
    let x = sim.positions();
    pairs
        .iter()
        .any(|&[a, b]| bodies.segment_crossings(sim.time(), &x[a], &x[b]) > 0)
}

/// What closes seams stalled under the strongest pull.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum AtStrongest {
    /// Welded where they stand.
    Weld,
    /// Drawn together over steps (see [`Zip`]), then welded.
    Zip,
    /// Nothing: the sewing fails, naming how far the seams reached (m).
    Fail { reach: f64 },
}

impl AtStrongest {
    /// Chosen by the widest gap and what lies between the sides of the pairs wider than
    /// `weld` (m; a weld where they stand moves each particle at most half that): `cloth`
    /// across any of them, the `body` across any. Up to `weld` apart they are welded
    /// whatever lies between (the weld's crossings are cleared). A body between cannot be
    /// passed: beyond `weld` the sewing fails. With only cloth between, zipped they would
    /// be drawn through it as the self-collision holds them back, so up to `over_cloth`
    /// apart they are welded where they stand and the crossings the weld makes are let
    /// through in the drape, as a weld's nearer ones are (GarmentCode's rand_2_012, a side
    /// seam 5.9 mm open over its sleeve's cloth, and rand_4_010, a sleeve's seam to its
    /// bodice 8.4 mm open over the sleeve's own cloth, both came to rest clean); farther,
    /// the sewing fails. With nothing between, they are zipped however far apart: the
    /// straight way between the sides is clear, and the drape shows the stretch closing
    /// asks of the cloth round them. GarmentCode's rand_1_071 on `mean_all`, a sleeve
    /// whose end is cut to the wrist's girth and placed at the forearm, stopped 26 mm
    /// open, the ring round the arm through it asking 63 %: zipped, the garment came to
    /// rest clean but for a band where the sleeve meets its cuff, stretched up to 72 %
    /// along the sleeve and 63 % round it (under a hundredth of the cloth).
    pub(super) fn choose(gap: f64, weld: f64, over_cloth: f64, cloth: bool, body: bool) -> Self {
        if gap <= weld {
            Self::Weld
        } else if body {
            Self::Fail { reach: weld }
        } else if cloth {
            if gap <= over_cloth {
                Self::Weld
            } else {
                Self::Fail { reach: over_cloth }
            }
        } else {
            Self::Zip
        }
    }
}

/// Whether the way through `points` (from one side of an open pair to the other) goes
/// round a body at time `t`: whether from its centre, for most of its points, the line to
/// the point passes an odd number of the body's triangles, the centre inside the body
/// that the way goes round and the points outside it.
pub(super) fn goes_round(bodies: &dyn Collider, t: f64, points: &[Vec3]) -> bool {
    if points.is_empty() {
        return false;
    }
    let centre = points.iter().sum::<Vec3>() / points.len() as f64;
    let inside = points
        .iter()
        .filter(|p| bodies.segment_crossings(t, &centre, p) % 2 == 1)
        .count();
    2 * inside > points.len()
}

/// Open pairs being drawn shut over a number of steps: before step `k` of `steps`, each
/// pair's gap is cut to at most `(1 - (k + 1) / steps)` of what it was when the zip
/// began, its sides moved symmetrically about their midpoint. Between the moves the
/// solve carries the cloth beside them along, so no cell takes the whole jump at once.
/// A holding zip goes on drawing them together before every step once they are shut.
pub(super) struct Zip {
    pairs: Vec<[usize; 2]>,
    start: Vec<f64>,
    steps: u64,
    done: u64,
    hold: bool,
    /// Scratch for the positions moved, kept between steps.
    x: Vec<Vec3>,
}

impl Zip {
    /// A zip of `pairs` at `x` over `steps` steps (at least one).
    pub(super) fn new(pairs: Vec<[usize; 2]>, x: &[Vec3], steps: u64) -> Self {
        let start = pairs.iter().map(|&[a, b]| (x[a] - x[b]).norm()).collect();
        Self {
            pairs,
            start,
            steps: steps.max(1),
            done: 0,
            hold: false,
            x: Vec::new(),
        }
    }

    /// As [`Zip::new`], holding the pairs shut once drawn.
    pub(super) fn holding(pairs: Vec<[usize; 2]>, x: &[Vec3], steps: u64) -> Self {
        Self {
            hold: true,
            ..Self::new(pairs, x, steps)
        }
    }

    /// Whether every step of the zip has been taken.
    pub(super) fn finished(&self) -> bool {
        self.done >= self.steps
    }

    /// Draws the pairs in for the next step (see [`Zip`]).
    pub(super) fn draw(&mut self, sim: &mut Simulation) -> Result<(), ParamError> {
        if self.finished() && !self.hold {
            return Ok(());
        }
        self.done = (self.done + 1).min(self.steps);
        let left = 1.0 - self.done as f64 / self.steps as f64;
        self.x.clear();
        self.x.extend_from_slice(sim.positions());
        for (&[a, b], &start) in self.pairs.iter().zip(&self.start) {
            draw_pair(&mut self.x, a, b, left * start);
        }
        sim.set_positions(&self.x)
    }
}

/// Moves `a` and `b` symmetrically about their midpoint to at most `gap` apart.
fn draw_pair(x: &mut [Vec3], a: usize, b: usize, gap: f64) {
    let d = x[b] - x[a];
    let now = d.norm();
    if now <= gap {
        return;
    }
    let shift = 0.5 * (now - gap) / now * d;
    x[a] += shift;
    x[b] -= shift;
}

#[cfg(test)]
mod tests {
    use super::*;
    use cloth_core::{Fabric, GridBuilder, SimulationBuilder};

    /// A 3 x 3 sheet, 10 cm square, and its opposite corners as a pair.
    fn sheet() -> (Simulation, [usize; 2]) {
        let mesh = GridBuilder::new(3, 3).size(0.1, 0.1).build().unwrap();
        let sim = SimulationBuilder::new(mesh, Fabric::cotton_like())
            .build()
            .unwrap();
        (sim, [0, 8])
    }

    fn gap(sim: &Simulation, [a, b]: [usize; 2]) -> f64 {
        (sim.positions()[a] - sim.positions()[b]).norm()
    }

    /// Moves `pair` apart by `by` along x, as the cloth round a seam drawn in may.
    fn pull_apart(sim: &mut Simulation, [a, b]: [usize; 2], by: f64) {
        let mut x = sim.positions().to_vec();
        x[a].x -= by;
        x[b].x += by;
        sim.set_positions(&x).unwrap();
    }

    #[test]
    fn a_holding_zip_draws_its_pairs_in_again_once_shut_and_a_plain_one_lets_them_go() {
        for hold in [false, true] {
            let (mut sim, pair) = sheet();
            let start = gap(&sim, pair);
            let mut zip = if hold {
                Zip::holding(vec![pair], sim.positions(), 2)
            } else {
                Zip::new(vec![pair], sim.positions(), 2)
            };
            zip.draw(&mut sim).unwrap();
            assert!((gap(&sim, pair) - 0.5 * start).abs() < 1e-12);
            zip.draw(&mut sim).unwrap();
            assert!(zip.finished());
            assert!(gap(&sim, pair) < 1e-12);
            pull_apart(&mut sim, pair, 0.01);
            zip.draw(&mut sim).unwrap();
            let after = gap(&sim, pair);
            if hold {
                assert!(after < 1e-12, "held: {after}");
            } else {
                assert!(after > 0.019, "let go: {after}");
            }
        }
    }

    #[test]
    fn seams_stalled_at_the_strongest_pull_are_welded_zipped_or_failed_by_their_gap_and_what_lies_between() {
        let (weld, over_cloth) = (0.005, 0.01);
        let choose = |gap, cloth, body| AtStrongest::choose(gap, weld, over_cloth, cloth, body);
        // Within a weld's reach: welded, whatever lies between.
        for (cloth, body) in [(false, false), (true, false), (false, true), (true, true)] {
            assert_eq!(choose(0.004, cloth, body), AtStrongest::Weld);
        }
        // Beyond it, within the reach of a weld over cloth: nothing between is zipped,
        // cloth alone welded over.
        assert_eq!(choose(0.008, false, false), AtStrongest::Zip);
        assert_eq!(choose(0.008, true, false), AtStrongest::Weld);
        // A body between, alone or beside cloth, is never passed.
        assert_eq!(choose(0.008, false, true), AtStrongest::Fail { reach: weld });
        assert_eq!(choose(0.008, true, true), AtStrongest::Fail { reach: weld });
        // Beyond that reach, cloth between is not welded over, nor a body passed...
        assert_eq!(choose(0.03, true, false), AtStrongest::Fail { reach: over_cloth });
        assert_eq!(choose(0.03, false, true), AtStrongest::Fail { reach: weld });
        // ...but with nothing between, the seams are zipped however far apart.
        assert_eq!(choose(0.03, false, false), AtStrongest::Zip);
        assert_eq!(choose(0.3, false, false), AtStrongest::Zip);
    }

    #[test]
    fn a_way_round_a_post_goes_round_it_and_a_way_beside_it_does_not() {
        use cloth_collide::{Bodies, Body, TriSurface};
        // A post of 5 cm radius along z, and ways of 24 points 1 cm outside it.
        let post = Bodies::new(vec![Body::new(
            "post",
            TriSurface::cylinder(0.05, 0.2, 48).unwrap(),
        )]);
        let arc = |from: f64, to: f64, centre: Vec3| -> Vec<Vec3> {
            (0..24)
                .map(|k| {
                    let a = from + (to - from) * k as f64 / 23.0;
                    centre + 0.06 * Vec3::new(a.cos(), a.sin(), 0.0)
                })
                .collect()
        };
        // All the way round but for the gap: round it.
        assert!(goes_round(&post, 0.0, &arc(0.3, 6.0, Vec3::zeros())));
        // The same, tilted out of the post's cross-section by a few degrees: still round.
        let tilted: Vec<Vec3> = arc(0.3, 6.0, Vec3::zeros())
            .into_iter()
            .map(|p| p + Vec3::new(0.0, 0.0, 0.1 * p.x))
            .collect();
        assert!(goes_round(&post, 0.0, &tilted));
        // A way turning round a corner on one side, as round the junction of three seams
        // beside the post: its centre outside the post.
        assert!(!goes_round(&post, 0.0, &arc(0.0, 6.0, Vec3::new(0.2, 0.0, 0.0))));
        assert!(!goes_round(&post, 0.0, &arc(-0.5, 0.5, Vec3::zeros())));
        assert!(!goes_round(&post, 0.0, &[]));
    }

    #[test]
    fn a_pair_drawn_in_keeps_its_midpoint_and_a_pair_already_close_is_left() {
        let mut x = vec![Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.03, 0.04, 0.0)];
        draw_pair(&mut x, 0, 1, 0.01);
        assert!(((x[1] - x[0]).norm() - 0.01).abs() < 1e-12);
        assert!(((x[0] + x[1]) / 2.0 - Vec3::new(0.015, 0.02, 0.0)).norm() < 1e-12);
        let before = x.clone();
        draw_pair(&mut x, 0, 1, 0.02);
        assert_eq!(x, before);
        draw_pair(&mut x, 0, 1, 0.0);
        assert!((x[0] - x[1]).norm() < 1e-12);
    }
}
