//! Panels that start inside the body: sewing would have to pull them through it.
//!
//! Two cases, told apart by how thick the body is along the panel's normal where the panel
//! is inside it. Through a thick part (the hips, a neck, a head: GarmentCode places skirts
//! 2 cm into the hips and collars 1 cm into the neck), the panel belongs outside it and
//! is moved out whole. Through a thin part (a hand or forearm: GarmentCode's wide skirts
//! at hip level cross the hands of its A-posed body, whose chord along the panel's normal
//! is 3 to 8 cm where the thick parts' is 14 cm or more), the garment belongs inside it,
//! and moved out the panel would be sewn round the hand: instead its particles inside the
//! body pass through it, untouched, until they are out (see [`PassThrough`]).

use super::Garment;
use cloth_collide::Bodies;
use cloth_core::{math::Vec3, PassThrough};

/// A panel that starts (partly) inside a body, with the fix.
#[derive(Debug, Clone, PartialEq)]
pub struct PlacementWarning {
    pub panel: String,
    pub body: String,
    /// How deep its deepest vertex is, m.
    pub depth: f64,
    /// Where that vertex is.
    pub point: Vec3,
    /// The direction to move the panel by `depth` plus a margin, to clear the body: the
    /// panel's mean front normal.
    pub outward: Vec3,
    /// How far the panel was moved along `outward` to clear the body before sewing, m
    /// (`None`: not moved, or not cleared by moving it).
    pub moved: Option<f64>,
    /// How many of its particles pass through a thin part of the body while sewn, instead
    /// (0: none).
    pub passing: usize,
}

impl std::fmt::Display for PlacementWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (tense, o) = (
            if self.moved.is_some() { "started" } else { "starts" },
            &self.outward,
        );
        write!(
            f,
            "panel '{}' {tense} {:.1} cm inside body '{}' (at {:.3}, {:.3}, {:.3} m): ",
            self.panel,
            100.0 * self.depth,
            self.body,
            self.point.x,
            self.point.y,
            self.point.z,
        )?;
        if self.passing > 0 {
            return write!(
                f,
                "a thin part of the body there (a hand, an arm), where {} of its particles are: \
                 it passes through the body while sewn, until it is out",
                self.passing
            );
        }
        match self.moved {
            Some(moved) => write!(
                f,
                "moved {:.1} cm along ({:.2}, {:.2}, {:.2}) before sewing",
                100.0 * moved,
                o.x,
                o.y,
                o.z
            ),
            None => write!(
                f,
                "move it {:.1} cm along ({:.2}, {:.2}, {:.2}) in its placement's translation, or \
                 increase its wrap radius",
                100.0 * (self.depth + 0.01),
                o.x,
                o.y,
                o.z
            ),
        }
    }
}

impl Garment {
    /// One warning per panel with vertices inside a body at its start (time 0).
    pub fn placement_warnings(&self, bodies: &Bodies) -> Vec<PlacementWarning> {
        let (members, facing) = (self.panel_members(), self.panel_facing());
        (0..self.panel_names.len())
            .filter_map(|panel| self.placement_warning(panel, &members[panel], facing[panel], bodies))
            .collect()
    }

    /// Clears the bodies of the panels that start inside them. A panel through a thick
    /// part is moved out along its front normal, rigidly (its shape untouched), until none
    /// of it is inside and its deepest point clears the body by [`CLEARANCE`]: GarmentCode
    /// places panels up to 4.8 cm inside its bodies, and sewn from there the body's contacts
    /// and the seams pull the panel through itself and the body (rand_1_018 diverged in
    /// its second sewing step). A panel that moving does not clear within [`MAX_MOVE`]
    /// stays where it was, its warning with the fix as before. A panel through thin parts
    /// only (the body's chord along its normal under [`THIN`] at the median of its
    /// particles inside) stays, and passes through them (see [`Garment::passing`]).
    /// Returns a warning per panel that started inside, saying what was done.
    pub fn move_out_of(&mut self, bodies: &Bodies) -> Vec<PlacementWarning> {
        let (members, facing) = (self.panel_members(), self.panel_facing());
        let mut warnings = Vec::new();
        for (panel, ids) in members.iter().enumerate() {
            let Some(mut w) = self.placement_warning(panel, ids, facing[panel], bodies) else {
                continue;
            };
            let x = self.mesh.positions();
            let inside: Vec<usize> = ids
                .iter()
                .copied()
                .filter(|&i| bodies.signed_distance(0.0, &x[i]).is_some_and(|(d, _)| d < 0.0))
                .collect();
            let mut chords: Vec<f64> = inside.iter().map(|&i| chord(bodies, &x[i], &w.outward)).collect();
            chords.sort_by(f64::total_cmp);
            if chords.get(chords.len() / 2).is_some_and(|&c| c < THIN) {
                w.passing = inside.len();
                self.passing.push(PassThrough {
                    members: ids.clone(),
                    until_out: true,
                });
                warnings.push(w);
                continue;
            }
            let clearance = |x: &[Vec3]| {
                ids.iter()
                    .filter_map(|&i| bodies.signed_distance(0.0, &x[i]).map(|(d, _)| d))
                    .fold(f64::INFINITY, f64::min)
            };
            let mut moved = 0.0;
            // A panel crossing the body at a slant clears it a little less than each move.
            for _ in 0..8 {
                let now = clearance(self.mesh.positions());
                if now >= CLEARANCE || moved > MAX_MOVE {
                    break;
                }
                let step = (CLEARANCE - now).max(0.25 * CLEARANCE);
                self.mesh.translate_vertices(ids, w.outward * step);
                moved += step;
            }
            if clearance(self.mesh.positions()) >= CLEARANCE {
                w.moved = Some(moved);
            } else {
                self.mesh.translate_vertices(ids, -w.outward * moved);
            }
            warnings.push(w);
        }
        warnings
    }

    /// The warning for `panel` (its particles `ids`), if any of it is inside a body.
    fn placement_warning(
        &self,
        panel: usize,
        ids: &[usize],
        outward: Vec3,
        bodies: &Bodies,
    ) -> Option<PlacementWarning> {
        let x = self.mesh.positions();
        let (d, i, body) = ids
            .iter()
            .filter_map(|&i| bodies.signed_distance(0.0, &x[i]).map(|(d, body)| (d, i, body)))
            .min_by(|a, b| a.0.total_cmp(&b.0))?;
        (d < 0.0).then(|| PlacementWarning {
            panel: self.panel_names[panel].clone(),
            body: bodies.bodies()[body].name().to_string(),
            depth: -d,
            point: x[i],
            outward,
            moved: None,
            passing: 0,
        })
    }
}

/// The body's chord through `x` (inside it) along `direction`, both ways, m, measured in
/// steps of [`CHORD_STEP`] and given up at [`THIN`].
fn chord(bodies: &Bodies, x: &Vec3, direction: &Vec3) -> f64 {
    let mut length = 0.0;
    for dir in [*direction, -*direction] {
        let mut s = 0.0;
        while length + s < THIN {
            s += CHORD_STEP;
            if bodies
                .signed_distance(0.0, &(x + s * dir))
                .is_some_and(|(d, _)| d > 0.0)
            {
                break;
            }
        }
        length += s;
    }
    length
}

/// Where the body's chord along a panel's normal is under this, m, it is a thin part (a
/// hand, an arm) that the panel passes through rather than is moved out of.
pub const THIN: f64 = 0.1;

/// Steps along a chord, m.
const CHORD_STEP: f64 = 0.005;

/// How far a panel moved out of a body clears it, m.
pub const CLEARANCE: f64 = 0.01;

/// The farthest a panel is moved out of a body, m.
pub const MAX_MOVE: f64 = 0.2;
