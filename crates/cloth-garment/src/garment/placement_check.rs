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
}

impl std::fmt::Display for PlacementWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
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
                })
            })
            .collect()
    }
}
