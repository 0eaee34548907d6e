//! Where a garment's strain and crossings lie at the end of a run: the report's figures
//! panel by panel. A design finished but stretched past 5 % or through itself then names
//! the panels to look at: the skirt cut smaller than the hips, not the bodice above it;
//! the collar through the shoulder it was caught under.

use super::strain_summary::StrainSummary;
use cloth_core::{BodyIntersections, ClothMesh, StrainReport};
use serde::Serialize;
use std::collections::HashMap;

/// One panel's share of the cloth's strain and intersections.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PanelReport {
    pub panel: String,
    pub triangles: usize,
    /// Warp and weft strain over the panel's triangles, % (in the JSON, beside the rest).
    #[serde(flatten)]
    pub strain: StrainSummary,
    /// The cloth's edge-triangle pairs through each other with the edge or the triangle
    /// in this panel (a pair between two panels counts for both).
    pub self_intersections: usize,
    /// Crossings of the bodies by edges of this panel (an edge on a seam counts for both
    /// panels it joins).
    pub body_intersections: usize,
}

/// The report of every panel (`names`, each triangle's in `triangle_panel`) of `mesh` with
/// strains `strain`, the cloth's crossings of itself `self_pairs` (edge, triangle) and of
/// the bodies `body_edges` (edge, crossings), edges numbered as in [`ClothMesh::edges`].
pub fn panel_reports(
    names: &[String],
    triangle_panel: &[usize],
    mesh: &ClothMesh,
    strain: &StrainReport,
    self_pairs: &[(usize, usize)],
    body_edges: &[(usize, BodyIntersections)],
) -> Vec<PanelReport> {
    let mut triangles_of: Vec<Vec<usize>> = vec![Vec::new(); names.len()];
    for (t, &p) in triangle_panel.iter().enumerate() {
        triangles_of[p].push(t);
    }
    let edge_panels = edge_panels(mesh, triangle_panel);
    let mut self_count = vec![0; names.len()];
    for &(e, t) in self_pairs {
        let mut panels = edge_panels[e].clone();
        panels.push(triangle_panel[t]);
        panels.sort_unstable();
        panels.dedup();
        for p in panels {
            self_count[p] += 1;
        }
    }
    let mut body_count = vec![0; names.len()];
    for (e, crossings) in body_edges {
        for &p in &edge_panels[*e] {
            body_count[p] += crossings.crossings;
        }
    }
    names
        .iter()
        .enumerate()
        .filter(|(p, _)| !triangles_of[*p].is_empty())
        .map(|(p, name)| PanelReport {
            panel: name.clone(),
            triangles: triangles_of[p].len(),
            strain: StrainSummary::from_report(&strain.of_triangles(&triangles_of[p])),
            self_intersections: self_count[p],
            body_intersections: body_count[p],
        })
        .collect()
}

/// The panels of the triangles beside each edge of `mesh` (one, or two on a seam).
fn edge_panels(mesh: &ClothMesh, triangle_panel: &[usize]) -> Vec<Vec<usize>> {
    let mut by_ends: HashMap<[usize; 2], Vec<usize>> = HashMap::new();
    for (t, corners) in mesh.triangles().iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (corners[k], corners[(k + 1) % 3]);
            let panels = by_ends.entry([a.min(b), a.max(b)]).or_default();
            if !panels.contains(&triangle_panel[t]) {
                panels.push(triangle_panel[t]);
            }
        }
    }
    mesh.edges()
        .iter()
        .map(|&[a, b]| by_ends.get(&[a.min(b), a.max(b)]).cloned().unwrap_or_default())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use cloth_core::{math::Vec3, GridBuilder};

    /// A 1 m square sheet, 5 x 5 particles, cut into a left and a right panel at x = 0.5
    /// (the triangles' panels by their centres), the right one stretched 10 % along the
    /// warp (x): the particles right of the cut moved out.
    fn two_panels() -> (ClothMesh, Vec<usize>, Vec<Vec3>) {
        let mesh = GridBuilder::new(5, 5)
            .size(1.0, 1.0)
            .axes(Vec3::x(), Vec3::y())
            .build()
            .unwrap();
        let x = mesh.positions();
        let panel: Vec<usize> = mesh
            .triangles()
            .iter()
            .map(|t| usize::from(t.iter().map(|&i| x[i].x).sum::<f64>() / 3.0 > 0.5))
            .collect();
        let stretched = x
            .iter()
            .map(|p| Vec3::new(if p.x > 0.5 { 0.5 + 1.1 * (p.x - 0.5) } else { p.x }, p.y, p.z))
            .collect();
        (mesh, panel, stretched)
    }

    fn names() -> Vec<String> {
        vec!["left".into(), "right".into()]
    }

    fn edge(mesh: &ClothMesh, x: &[Vec3], test: impl Fn(&Vec3, &Vec3) -> bool) -> usize {
        mesh.edges()
            .iter()
            .position(|&[a, b]| test(&x[a], &x[b]))
            .expect("such an edge")
    }

    #[test]
    fn each_panel_has_the_strain_of_its_own_triangles() {
        let (mesh, panel, x) = two_panels();
        let strain = StrainReport::new(&mesh, &x);
        let reports = panel_reports(&names(), &panel, &mesh, &strain, &[], &[]);
        let [left, right] = [&reports[0], &reports[1]];
        assert_eq!((left.panel.as_str(), right.panel.as_str()), ("left", "right"));
        assert_eq!(left.triangles + right.triangles, mesh.triangles().len());
        assert!(
            left.strain.p99_warp.abs() < 1e-9 && left.strain.p99_weft.abs() < 1e-9,
            "{left:?}"
        );
        assert!(
            (right.strain.p99_warp - 10.0).abs() < 1e-9 && right.strain.p99_weft.abs() < 1e-9,
            "{right:?}"
        );
        assert_eq!(right.strain.p99(), (right.strain.p99_warp, "warp"));
        assert_eq!((left.self_intersections, left.body_intersections), (0, 0));
    }

    #[test]
    fn a_crossing_counts_for_every_panel_it_touches() {
        let (mesh, panel, x) = two_panels();
        let placed = mesh.positions();
        let strain = StrainReport::new(&mesh, &x);
        // An edge inside the left panel, and one on the cut (between both panels' triangles).
        let inside = edge(&mesh, placed, |a, b| a.x < 0.3 && b.x < 0.3);
        let on_cut = edge(&mesh, placed, |a, b| a.x == 0.5 && b.x == 0.5);
        let right_triangle = panel.iter().position(|&p| p == 1).unwrap();
        let left_triangle = panel.iter().position(|&p| p == 0).unwrap();
        let twice = BodyIntersections {
            crossings: 2,
            thin_parts_passed: 0,
        };
        let reports = panel_reports(
            &names(),
            &panel,
            &mesh,
            &strain,
            &[(inside, left_triangle), (inside, right_triangle)],
            &[(inside, twice), (on_cut, twice)],
        );
        // Left: both pairs (its edge in each); right: the one with its triangle.
        assert_eq!(reports[0].self_intersections, 2);
        assert_eq!(reports[1].self_intersections, 1);
        // Left: its own edge's two crossings and the cut's; right: the cut's.
        assert_eq!(reports[0].body_intersections, 4);
        assert_eq!(reports[1].body_intersections, 2);
    }
}
