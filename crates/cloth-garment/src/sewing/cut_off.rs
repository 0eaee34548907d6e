//! Cloth cut off by a crossing. Where cloth goes through other cloth, the edges of each
//! that pierce the other trace their intersection on it. A part of the cloth that those
//! edges cut off from the rest of it (a collar's corner through a shoulder, the curve
//! running across the corner from edge to edge) lies on the wrong side of what it
//! crosses: the rest of its cloth lies on the other (the smaller region of a global
//! intersection analysis, as Baraff, Witkin and Kass untangle cloth). Moved through as one
//! piece, along the crossed triangles' normal, it ends on the side of the rest, and no
//! edge of it is left through anything. Moving particles one at a time out along the
//! bodies' normal (see `weld_crossings`) cannot do that: a corner caught between a
//! shoulder's sides, moved out, drags its neighbours through.

use crate::garment::Welded;
use cloth_core::{components, math::Vec3, ClothMesh, Neighbours, SelfCrossings};

/// The most particles a region cut off may have: a corner or a flap, not a panel.
const MOST_PARTICLES: usize = 400;

/// How far past the plane of the crossings a region is moved, m.
const MARGIN: f64 = 1e-3;

/// Rounds of finding and moving regions: a move may uncover another region under it.
const ROUNDS: usize = 3;

/// A part of the cloth cut off from the rest by edges through other cloth: its particles,
/// and the crossings on its border (the particle inside, the particle outside, the
/// triangle the edge between them goes through).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Region {
    pub particles: Vec<usize>,
    pub border: Vec<(usize, usize, usize)>,
}

/// The regions that the edges of `pairs` (edge of `welded`'s mesh, triangle), removed,
/// cut off from the largest part of their panel, each of at most [`MOST_PARTICLES`]. The
/// panels are the charts of the unwelded mesh (`charts`, its vertex `i` the welded
/// particle `welded.particle_of[i]`): welded, a region beside a seam (a collar's corner
/// caught at the shoulder it is sewn to) is still joined to the rest through the other
/// panels of the seam.
pub(super) fn regions(welded: &Welded, charts: &Neighbours, pairs: &[(usize, usize)]) -> Vec<Region> {
    let of = &welded.particle_of;
    let n = of.len();
    let edges = welded.mesh.edges();
    let mut cut: Vec<[usize; 2]> = pairs.iter().map(|&(e, _)| edges[e]).collect();
    cut.sort_unstable();
    cut.dedup();
    let is_cut = |a: usize, b: usize| {
        let (a, b) = (of[a], of[b]);
        cut.binary_search(&[a.min(b), a.max(b)]).is_ok()
    };
    // Whole panels first, then the parts of each the cut edges leave joined.
    let panel = components(n, |i| charts.of_vertex(i).iter().copied());
    let part = components(n, |i| {
        charts
            .of_vertex(i)
            .iter()
            .copied()
            .filter(move |&j| !is_cut(i, j))
    });
    let parts = 1 + part.iter().copied().max().unwrap_or(0);
    let mut size = vec![0usize; parts];
    for &p in &part {
        size[p] += 1;
    }
    // The largest part of each panel stays.
    let mut main: Vec<Option<usize>> = vec![None; n];
    for i in 0..n {
        let best = &mut main[panel[i]];
        if best.is_none_or(|b| size[part[i]] > size[b]) {
            *best = Some(part[i]);
        }
    }
    let mut found: Vec<Region> = Vec::new();
    let mut region_of: Vec<Option<usize>> = vec![None; parts];
    for i in 0..n {
        let p = part[i];
        if main[panel[i]] == Some(p) || size[p] > MOST_PARTICLES {
            continue;
        }
        let k = *region_of[p].get_or_insert_with(|| {
            found.push(Region {
                particles: Vec::new(),
                border: Vec::new(),
            });
            found.len() - 1
        });
        found[k].particles.push(of[i]);
    }
    // The border: each cut chart edge from a region out, with the triangle its welded
    // edge goes through.
    let mut through: Vec<([usize; 2], usize)> = pairs.iter().map(|&(e, t)| (edges[e], t)).collect();
    through.sort_unstable();
    for i in 0..n {
        let Some(k) = region_of[part[i]] else {
            continue;
        };
        for &j in charts.of_vertex(i) {
            if part[j] == part[i] {
                continue;
            }
            let (a, b) = (of[i], of[j]);
            let key = [a.min(b), a.max(b)];
            let first = through.partition_point(|&(e, _)| e < key);
            for &(_, t) in through[first..].iter().take_while(|&&(e, _)| e == key) {
                found[k].border.push((a, b, t));
            }
        }
    }
    for r in &mut found {
        r.particles.sort_unstable();
        r.particles.dedup();
        r.border.sort_unstable();
        r.border.dedup();
    }
    found.retain(|r| !r.border.is_empty());
    found
}

/// The move that takes `region` of `x` through the cloth its border crosses: along the
/// crossed triangles' mean normal (turned to the region's side), from the region's side
/// to [`MARGIN`] past the plane through the crossings; `None` if it would move it farther
/// than `most` (m) or the crossings give no side.
pub(super) fn move_through(mesh: &ClothMesh, x: &[Vec3], region: &Region, most: f64) -> Option<Vec3> {
    let triangles = mesh.triangles();
    let (mut normal, mut centre) = (Vec3::zeros(), Vec3::zeros());
    for &(inside, outside, t) in &region.border {
        let [p, q, r] = triangles[t].map(|i| x[i]);
        let n = (q - p).cross(&(r - p)).try_normalize(1e-12)?;
        let (hi, ho) = ((x[inside] - p).dot(&n), (x[outside] - p).dot(&n));
        if hi == ho {
            return None;
        }
        // Where the edge goes through the triangle's plane.
        centre += x[inside] + hi / (hi - ho) * (x[outside] - x[inside]);
        normal += if hi > 0.0 { n } else { -n };
    }
    centre /= region.border.len() as f64;
    let normal = normal.try_normalize(1e-9)?;
    let height = region
        .particles
        .iter()
        .map(|&i| (x[i] - centre).dot(&normal))
        .fold(f64::NEG_INFINITY, f64::max);
    let by = height.max(0.0) + MARGIN;
    (by <= most).then(|| -by * normal)
}

/// Moves the regions of `welded` that its crossings `pairs` cut off from their panels
/// (`charts`, see [`regions`]) through what they cross, each only if that leaves fewer
/// crossings (as `crossings`, made for `welded`'s mesh, finds them), none farther than
/// `most` (m). Returns how many were moved, and the crossings left.
pub(super) fn clear(
    welded: &mut Welded,
    charts: &Neighbours,
    mut pairs: Vec<(usize, usize)>,
    crossings: &SelfCrossings,
    most: f64,
) -> (usize, Vec<(usize, usize)>) {
    let crossings = |mesh: &ClothMesh| crossings.pairs(mesh.positions());
    let mut moved = 0;
    for _ in 0..ROUNDS {
        if pairs.is_empty() {
            break;
        }
        let mut any = false;
        for region in regions(welded, charts, &pairs) {
            let mesh = &mut welded.mesh;
            let Some(by) = move_through(mesh, mesh.positions(), &region, most) else {
                continue;
            };
            mesh.translate_vertices(&region.particles, by);
            let after = crossings(mesh);
            if after.len() < pairs.len() {
                pairs = after;
                moved += 1;
                any = true;
            } else {
                mesh.translate_vertices(&region.particles, -by);
            }
        }
        if !any {
            break;
        }
    }
    (moved, pairs)
}

#[cfg(test)]
mod tests {
    use super::*;
    use cloth_core::self_intersecting_pairs;
    use nalgebra::Vector2;

    /// A square sheet of `k` by `k` cells of 1 cm at height 0, and a strip of 1 by 6
    /// cells standing on edge across it, along x from the sheet's middle, its lower
    /// `below` cells under the sheet: the strip's corner caught through the sheet.
    fn caught_corner(k: usize, below: usize) -> (ClothMesh, usize) {
        let mut x = Vec::new();
        let mut tris = Vec::new();
        let h = 0.01;
        for j in 0..=k {
            for i in 0..=k {
                x.push(Vec3::new(i as f64 * h, j as f64 * h, 0.0));
            }
        }
        let at = |i: usize, j: usize| j * (k + 1) + i;
        for j in 0..k {
            for i in 0..k {
                tris.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                tris.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        // The strip in the plane y = 0.008 + middle (clear of the sheet's diagonals),
        // from 2 mm over `below` cells under the sheet up 6 cells, 1 cm wide in x.
        let first = x.len();
        let y = 0.008 + (k / 2) as f64 * h;
        let x0 = 0.005 + (k / 2) as f64 * h;
        for j in 0..=6 {
            for i in 0..=1 {
                x.push(Vec3::new(
                    x0 + i as f64 * h,
                    y,
                    (j as f64 - below as f64) * h + 0.002,
                ));
            }
        }
        let st = |i: usize, j: usize| first + j * 2 + i;
        for j in 0..6 {
            tris.push([st(0, j), st(1, j), st(1, j + 1)]);
            tris.push([st(0, j), st(1, j + 1), st(0, j + 1)]);
        }
        // Flat coordinates apart, so no pair is near in the flat cloth.
        let uv = x
            .iter()
            .enumerate()
            .map(|(i, p)| {
                if i < first {
                    Vector2::new(p.x, p.y)
                } else {
                    Vector2::new(p.x + 1.0, p.z + 1.0)
                }
            })
            .collect();
        (ClothMesh::new(x, uv, tris).unwrap(), first)
    }

    /// `mesh` as a garment welded at no seam.
    fn unwelded(mesh: ClothMesh) -> Welded {
        let particle_of = (0..mesh.vertex_count()).collect();
        Welded { mesh, particle_of }
    }

    #[test]
    fn the_part_a_crossing_cuts_off_is_the_smaller_and_is_moved_through_as_one() {
        // One row of the strip's cells under the sheet: its lowest two particles are cut
        // off from the rest of the strip by the edges through the sheet.
        let (mesh, first) = caught_corner(4, 1);
        let x0 = mesh.positions().to_vec();
        let pairs = self_intersecting_pairs(&mesh, &[], 0.0, &x0);
        assert!(!pairs.is_empty());
        let charts = Neighbours::of(&mesh);
        let mut welded = unwelded(mesh);
        let found = regions(&welded, &charts, &pairs);
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!(found[0].particles, vec![first, first + 1]);
        // Moved up through the sheet as one, to just above it, and nothing crosses.
        let crossings = SelfCrossings::new(&welded.mesh, &[], 0.0);
        let (moved, left) = clear(&mut welded, &charts, pairs, &crossings, 0.02);
        assert_eq!(moved, 1);
        assert!(left.is_empty());
        let x = welded.mesh.positions();
        assert!(self_intersecting_pairs(&welded.mesh, &[], 0.0, x).is_empty());
        for i in [first, first + 1] {
            let by = x[i] - x0[i];
            assert!(by.x.abs() < 1e-12 && by.y.abs() < 1e-12, "{by:?}");
            assert!((x[i].z - MARGIN).abs() < 1e-12, "{}", x[i].z);
        }
        for i in (0..x.len()).filter(|&i| i != first && i != first + 1) {
            assert_eq!(x[i], x0[i], "only the region moves");
        }
    }

    #[test]
    fn a_region_farther_through_than_the_cloth_may_move_is_left() {
        // Three rows under: the region's lowest particle is 2.8 cm under the sheet.
        let (mesh, _) = caught_corner(4, 3);
        let x0 = mesh.positions().to_vec();
        let pairs = self_intersecting_pairs(&mesh, &[], 0.0, &x0);
        let charts = Neighbours::of(&mesh);
        let mut welded = unwelded(mesh);
        let found = regions(&welded, &charts, &pairs);
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!(found[0].particles.len(), 6);
        let crossings = SelfCrossings::new(&welded.mesh, &[], 0.0);
        let (moved, left) = clear(&mut welded, &charts, pairs.clone(), &crossings, 0.02);
        assert_eq!(moved, 0);
        assert_eq!(left, pairs);
        assert_eq!(welded.mesh.positions(), &x0[..]);
    }
}
