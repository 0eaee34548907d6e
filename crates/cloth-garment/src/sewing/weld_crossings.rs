//! Crossings the weld makes. A seam is closed when its sides are within a millimetre, and
//! another panel's cloth can lie between them then: GarmentCode hangs its collars round
//! the neck, and the corner of a collar sat between the front and back shoulders where
//! they meet the neckline, a third of a millimetre from each. Welded at the middle, the
//! shoulder went through the collar (rand_1_034: no crossing before the weld, 17 after),
//! and no drape takes cloth that starts through itself back out. So the weld's crossings
//! are cleared before the drape: the cloth that lies between is moved out, away from the
//! bodies, until nothing crosses or it has moved a cell. (Moved the least way across, to
//! the nearer side, it made more crossings than it cleared: 17 to 60 on rand_1_034.)

use super::cut_off;
use crate::garment::Welded;
use cloth_core::{math::Vec3, Collider, Neighbours, ParticlePath, Proximity, SelfCrossings};

/// What clearing the weld's crossings found and left (intersecting edge-triangle pairs),
/// and how many parts of the cloth cut off by them were moved through as one (see
/// `cut_off`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub struct WeldCrossings {
    pub found: usize,
    pub left: usize,
    pub regions_moved: usize,
}

/// Each round moves the cloth between this far, m.
const STEP: f64 = 5e-4;

/// Particles this far from the bodies are moved out away from the nearest, m; farther,
/// along the normal of the triangle crossed.
const REACH: f64 = 0.2;

/// Clears the crossings of `welded` (its panels the charts of `charts`, the unwelded
/// mesh's neighbours) at time `t` of `bodies`, moving no particle by more
/// than `most` (m); pairs within `rest_radius` in the flat cloth are exempt, as the
/// self-collision exempts them. The parts of the cloth the crossings cut off are moved
/// through first (see `cut_off`); then, of an edge and a triangle through each other, the one
/// with more particles that no seam joins is moved out (the cloth caught between a seam's
/// sides, not the seam); of two alike, the one farther out. Each round moves it a
/// [`STEP`] out, away from the bodies; the round with the fewest crossings is kept.
pub(super) fn clear(
    welded: &mut Welded,
    charts: &Neighbours,
    bodies: &dyn Collider,
    t: f64,
    rest_radius: f64,
    most: f64,
) -> WeldCrossings {
    let n = welded.mesh.vertex_count();
    let mut members = vec![0u32; n];
    for &p in &welded.particle_of {
        members[p] += 1;
    }
    let free = |i: usize| members[i] <= 1;
    let rounds = (most / STEP).ceil() as usize;
    let crossings = SelfCrossings::new(&welded.mesh, &[], rest_radius);
    let found = crossings.pairs(welded.mesh.positions());
    let mut report = WeldCrossings {
        found: found.len(),
        ..WeldCrossings::default()
    };
    let (regions_moved, mut pairs) = cut_off::clear(welded, charts, found, &crossings, most);
    report.regions_moved = regions_moved;
    let mut moved = vec![false; n];
    // The fewest crossings yet, and where: moving cloth out may cross other cloth.
    let mut best: Option<(usize, Vec<Vec3>)> = None;
    for round in 0..=rounds {
        let x = welded.mesh.positions().to_vec();
        if round > 0 {
            pairs = crossings.pairs(&x);
        }
        if best.as_ref().is_none_or(|(count, _)| pairs.len() < *count) {
            best = Some((pairs.len(), x.clone()));
        }
        if pairs.is_empty() || round == rounds {
            break;
        }
        let outward = |i: usize, fallback: Vec3| match bodies.sweep(&ParticlePath::still(t, x[i]), 0.0, REACH)
        {
            Proximity::Near(p) => (p.normal, p.distance),
            Proximity::Far { .. } => (fallback, f64::INFINITY),
        };
        moved.iter_mut().for_each(|m| *m = false);
        for &(e, tri) in &pairs {
            let edge = welded.mesh.edges()[e];
            let triangle = welded.mesh.triangles()[tri];
            let [a, b, c] = triangle.map(|i| x[i]);
            let normal = (b - a).cross(&(c - a)).try_normalize(1e-12).unwrap_or(Vec3::z());
            let free_of = |vs: &[usize]| vs.iter().filter(|&&i| free(i)).count();
            let out_of =
                |vs: &[usize]| vs.iter().map(|&i| outward(i, normal).1).sum::<f64>() / vs.len() as f64;
            let move_triangle = match free_of(&triangle).cmp(&free_of(&edge)) {
                std::cmp::Ordering::Greater => true,
                std::cmp::Ordering::Less => false,
                std::cmp::Ordering::Equal => out_of(&triangle) >= out_of(&edge),
            };
            let movers: Vec<usize> = if move_triangle {
                triangle.to_vec()
            } else {
                edge.to_vec()
            };
            let any_free = movers.iter().any(|&i| free(i));
            for i in movers {
                if (any_free && !free(i)) || std::mem::replace(&mut moved[i], true) {
                    continue;
                }
                welded.mesh.translate_vertices(&[i], STEP * outward(i, normal).0);
            }
        }
    }
    if let Some((count, x)) = best {
        report.left = count;
        let now = welded.mesh.positions().to_vec();
        for (i, (to, at)) in x.iter().zip(&now).enumerate() {
            if to != at {
                welded.mesh.translate_vertices(&[i], to - at);
            }
        }
    }
    report
}

#[cfg(test)]
mod tests {
    use super::*;
    use cloth_collide::{Bodies, Body, TriSurface};
    use cloth_core::ClothMesh;
    use nalgebra::Vector2;

    /// The neighbours of the unwelded mesh of `triangles`, its vertex `i` at
    /// `x[particle_of[i]]`.
    fn charts(x: &[Vec3], particle_of: &[usize], triangles: Vec<[usize; 3]>) -> Neighbours {
        let positions: Vec<Vec3> = particle_of.iter().map(|&k| x[k]).collect();
        let uv = positions.iter().map(|p| Vector2::new(p.x + p.z, p.y)).collect();
        Neighbours::of(&ClothMesh::new(positions, uv, triangles).unwrap())
    }

    #[test]
    fn cloth_the_weld_left_through_a_seam_is_moved_out_off_it() {
        // A welded strip lying on a box (its top at z = 0.1), every particle joining two
        // panels, and a free triangle standing across it, its foot under the strip's edge
        // along y = 0 (as a collar's corner caught between a shoulder's sides).
        let strip = [[0.0, 0.0], [0.02, 0.0], [0.0, 0.02], [0.02, 0.02]].map(|[x, y]| Vec3::new(x, y, 0.102));
        let foot = 0.1005;
        let collar = [
            Vec3::new(0.01, -0.01, foot),
            Vec3::new(0.01, 0.01, foot),
            Vec3::new(0.01, 0.0, 0.11),
        ];
        let positions: Vec<Vec3> = strip.iter().chain(&collar).copied().collect();
        let uv = positions.iter().map(|p| Vector2::new(p.x + p.z, p.y)).collect();
        let mesh = ClothMesh::new(positions.clone(), uv, vec![[0, 1, 2], [1, 3, 2], [4, 5, 6]]).unwrap();
        let mut welded = Welded {
            mesh,
            particle_of: vec![0, 0, 1, 1, 2, 2, 3, 3, 4, 5, 6],
        };
        let bodies = Bodies::new(vec![Body::new(
            "box",
            TriSurface::cuboid(Vec3::new(0.5, 0.5, 0.1)).unwrap(),
        )]);
        // Unwelded: the strip twice (two panels seamed all round), then the triangle.
        let charts = charts(
            &positions,
            &welded.particle_of,
            vec![[0, 2, 4], [2, 6, 4], [1, 3, 5], [3, 7, 5], [8, 9, 10]],
        );
        let report = clear(&mut welded, &charts, &bodies, 0.0, 0.0, 0.015);
        // The strip's edge through the triangle, and the triangle's edge through the strip.
        assert_eq!((report.found, report.left), (2, 0));
        let x = welded.mesh.positions();
        for i in 0..4 {
            assert_eq!(x[i], positions[i], "the seam stays");
        }
        // Straight up, out of the box, as one, and no further than it took: the foot
        // above the strip by less than a step.
        let rise = x[4].z - foot;
        for i in 4..7 {
            let by = x[i] - positions[i];
            assert!(by.x.abs() < 1e-12 && by.y.abs() < 1e-12, "{by:?}");
            assert!((by.z - rise).abs() < 1e-12, "{by:?}");
        }
        assert!(x[4].z > 0.102 && x[4].z < 0.102 + STEP, "{}", x[4].z);
    }

    #[test]
    fn clearing_that_crosses_more_cloth_than_it_clears_is_undone() {
        // As above, with a sheet 0.9 mm over the strip that the triangle's top is under:
        // moved out by the millimetre it may move, the triangle would still cross the
        // strip, and the sheet too.
        let strip = [[0.0, 0.0], [0.02, 0.0], [0.0, 0.02], [0.02, 0.02]].map(|[x, y]| Vec3::new(x, y, 0.102));
        let collar = [
            Vec3::new(0.01, -0.01, 0.1005),
            Vec3::new(0.01, 0.01, 0.1005),
            Vec3::new(0.01, 0.0, 0.1025),
        ];
        let sheet = [[-0.05, -0.05], [0.05, -0.05], [-0.05, 0.05], [0.05, 0.05]]
            .map(|[x, y]| Vec3::new(x, y, 0.1029));
        let positions: Vec<Vec3> = strip.iter().chain(&collar).chain(&sheet).copied().collect();
        let uv = positions.iter().map(|p| Vector2::new(p.x + p.z, p.y)).collect();
        let triangles = vec![[0, 1, 2], [1, 3, 2], [4, 5, 6], [7, 8, 9], [8, 10, 9]];
        let mesh = ClothMesh::new(positions.clone(), uv, triangles).unwrap();
        let before = cloth_core::self_intersecting_pairs(&mesh, &[], 0.0, &positions).len();
        let mut welded = Welded {
            mesh,
            particle_of: vec![0, 0, 1, 1, 2, 2, 3, 3, 4, 5, 6, 7, 7, 8, 8, 9, 9, 10, 10],
        };
        let bodies = Bodies::new(vec![Body::new(
            "box",
            TriSurface::cuboid(Vec3::new(0.5, 0.5, 0.1)).unwrap(),
        )]);
        let charts = charts(
            &positions,
            &welded.particle_of,
            vec![
                [0, 2, 4],
                [2, 6, 4],
                [1, 3, 5],
                [3, 7, 5],
                [8, 9, 10],
                [11, 13, 15],
                [13, 17, 15],
                [12, 14, 16],
                [14, 18, 16],
            ],
        );
        let report = clear(&mut welded, &charts, &bodies, 0.0, 0.0, 0.001);
        assert_eq!((report.found, report.left), (before, before));
        assert!(before > 0);
        assert_eq!(welded.mesh.positions(), &positions[..], "nothing moved");
    }
}
