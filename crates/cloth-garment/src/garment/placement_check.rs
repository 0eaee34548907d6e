//! Panels that start inside the body: sewing would have to pull them through it.

use super::Garment;
use cloth_collide::Bodies;
use cloth_core::Vec3;

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
}

impl std::fmt::Display for PlacementWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if let Some(moved) = self.moved {
            return write!(
                f,
                "panel '{}' started {:.1} cm inside body '{}' (at {:.3}, {:.3}, {:.3} m): moved {:.1} cm \
                 along ({:.2}, {:.2}, {:.2}) before sewing",
                self.panel,
                100.0 * self.depth,
                self.body,
                self.point.x,
                self.point.y,
                self.point.z,
                100.0 * moved,
                self.outward.x,
                self.outward.y,
                self.outward.z
            );
        }
        let clear = 100.0 * (self.depth + 0.01);
        write!(
            f,
            "panel '{}' starts {:.1} cm inside body '{}' (at {:.3}, {:.3}, {:.3} m): move it {:.1} cm \
             along ({:.2}, {:.2}, {:.2}) in its placement's translation, or increase its wrap radius",
            self.panel,
            100.0 * self.depth,
            self.body,
            self.point.x,
            self.point.y,
            self.point.z,
            clear,
            self.outward.x,
            self.outward.y,
            self.outward.z
        )
    }
}

impl Garment {
    /// One warning per panel with vertices inside a body at its start (time 0).
    pub fn placement_warnings(&self, bodies: &Bodies) -> Vec<PlacementWarning> {
        let x = self.mesh.positions();
        let mut deepest: Vec<Option<(f64, usize, usize)>> = vec![None; self.panel_names.len()];
        let mut panel_of = vec![usize::MAX; x.len()];
        for (t, tri) in self.mesh.triangles().iter().enumerate() {
            tri.iter().for_each(|&i| panel_of[i] = self.triangle_panel[t]);
        }
        // Panels face out of the garment (+z of their frames), and their triangles are
        // wound counter-clockwise seen from the front: the area-weighted normal points out.
        let mut facing = vec![Vec3::zeros(); self.panel_names.len()];
        for (t, tri) in self.mesh.triangles().iter().enumerate() {
            let [a, b, c] = tri.map(|i| x[i]);
            facing[self.triangle_panel[t]] += (b - a).cross(&(c - a));
        }
        for (i, p) in x.iter().enumerate() {
            if let Some((d, body)) = bodies.signed_distance(0.0, p) {
                let slot = &mut deepest[panel_of[i]];
                if d < 0.0 && slot.is_none_or(|(depth, _, _)| -d > depth) {
                    *slot = Some((-d, i, body));
                }
            }
        }
        deepest
            .iter()
            .enumerate()
            .filter_map(|(panel, found)| {
                let (depth, i, body) = (*found)?;
                let b = &bodies.bodies()[body];
                let outward = facing[panel].try_normalize(1e-12).unwrap_or(Vec3::x());
                Some(PlacementWarning {
                    panel: self.panel_names[panel].clone(),
                    body: b.name().to_string(),
                    depth,
                    point: x[i],
                    outward,
                    moved: None,
                })
            })
            .collect()
    }

    /// Moves each panel that starts inside a body out along its front normal, rigidly (its
    /// shape untouched), until none of it is inside and its deepest point clears the body
    /// by [`CLEARANCE`]. GarmentCode places panels up to 4.8 cm inside its bodies; sewn
    /// from there, the body's contacts and the seams pull the panel through itself and
    /// the body (rand_1_018 diverged in its second sewing step). Returns a warning per
    /// panel that started inside, saying how far it moved; a panel that moving does not
    /// clear within [`MAX_MOVE`] stays where it was, its warning with the fix as before.
    pub fn move_out_of(&mut self, bodies: &Bodies) -> Vec<PlacementWarning> {
        let mut warnings = self.placement_warnings(bodies);
        let mut members: Vec<Vec<usize>> = vec![Vec::new(); self.panel_names.len()];
        let mut seen = vec![false; self.mesh.vertex_count()];
        for (t, tri) in self.mesh.triangles().iter().enumerate() {
            for &i in tri {
                if !std::mem::replace(&mut seen[i], true) {
                    members[self.triangle_panel[t]].push(i);
                }
            }
        }
        for w in &mut warnings {
            let Some(panel) = self.panel_names.iter().position(|p| *p == w.panel) else {
                continue;
            };
            let ids = &members[panel];
            let deepest = |x: &[Vec3]| {
                ids.iter()
                    .filter_map(|&i| bodies.signed_distance(0.0, &x[i]).map(|(d, _)| d))
                    .fold(f64::INFINITY, f64::min)
            };
            let mut moved = 0.0;
            let mut shift = Vec3::zeros();
            // A panel crossing the body at a slant clears it a little less than each move.
            for _ in 0..8 {
                let clearance = deepest(self.mesh.positions());
                if clearance >= CLEARANCE || moved > MAX_MOVE {
                    break;
                }
                let step = (CLEARANCE - clearance).max(0.25 * CLEARANCE);
                self.mesh.translate_vertices(ids, w.outward * step);
                shift += w.outward * step;
                moved += step;
            }
            if deepest(self.mesh.positions()) >= CLEARANCE {
                w.moved = Some(moved);
            } else {
                self.mesh.translate_vertices(ids, -shift);
            }
        }
        warnings
    }
}

/// How far a panel moved out of a body clears it, m.
pub const CLEARANCE: f64 = 0.01;

/// The farthest a panel is moved out of a body, m.
pub const MAX_MOVE: f64 = 0.2;
