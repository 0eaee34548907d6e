//! Measures of the cloth against itself at one instant: the intersection count (edge-
//! triangle pairs passing through each other) and the closest approach of a particle to a
//! triangle, pairs sharing a particle (or seam partners) exempt. The count is zero for
//! cloth that has never passed through itself.

use super::topology::Topology;
use crate::math::predicates::{closest_on_triangle, segment_crosses_triangle};
use crate::math::Vec3;
use crate::mesh::ClothMesh;
use crate::spatial::{Aabb, Bvh};
use rayon::prelude::*;

/// How many edge-triangle pairs intersect, and the first (edge, triangle) of them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Intersections {
    pub count: usize,
    pub first: Option<(usize, usize)>,
}

/// The triangles' hierarchy at `x`.
fn triangle_tree(topology: &Topology, x: &[Vec3]) -> Bvh {
    let tris = &topology.triangles;
    let centres: Vec<Vec3> = tris
        .iter()
        .map(|t| t.iter().map(|&i| x[i as usize]).sum::<Vec3>() / 3.0)
        .collect();
    let mut tree = Bvh::new(&centres);
    tree.refit(|t| Aabb::of(tris[t].map(|i| x[i as usize])));
    tree
}

pub(crate) fn count(topology: &Topology, x: &[Vec3]) -> Intersections {
    let pairs = crossing_pairs(topology, x);
    Intersections {
        count: pairs.len(),
        first: pairs.first().copied(),
    }
}

/// The (edge, triangle) pairs passing through each other at `x`, not exempt, sorted.
pub(super) fn crossing_pairs(topology: &Topology, x: &[Vec3]) -> Vec<(usize, usize)> {
    let tris = &topology.triangles;
    let tree = triangle_tree(topology, x);
    let mut pairs: Vec<(usize, usize)> = (0..topology.edges.len())
        .into_par_iter()
        .flat_map_iter(|e| {
            let [a, b] = topology.edges[e];
            let (p, q) = (x[a as usize], x[b as usize]);
            let mut found = Vec::new();
            tree.query(&Aabb::of([p, q]), |t| {
                if !topology.edge_triangle_exempt(e, t)
                    && segment_crosses_triangle(&p, &q, &tris[t].map(|i| x[i as usize]))
                {
                    found.push((e, t));
                }
            });
            found
        })
        .collect();
    pairs.sort_unstable();
    pairs
}

/// The edge-triangle pairs of different charts passing through each other at `x`, counted
/// by chart pair (lower chart first, sorted), for the edges whose charts `edges_of` takes
/// (pairs exempt for good are not counted; pairs exempt while tangled are).
pub(crate) fn crossings_by_chart(
    topology: &Topology,
    x: &[Vec3],
    edges_of: impl Fn(u32) -> bool + Sync,
) -> Vec<((u32, u32), usize)> {
    let tris = &topology.triangles;
    let tree = triangle_tree(topology, x);
    let mut pairs: Vec<(u32, u32)> = (0..topology.edges.len())
        .into_par_iter()
        .flat_map_iter(|e| {
            let [a, b] = topology.edges[e];
            let (p, q) = (x[a as usize], x[b as usize]);
            let own = topology.edge_chart(e);
            let mut found = Vec::new();
            if !edges_of(own) {
                return found;
            }
            tree.query(&Aabb::of([p, q]), |t| {
                let other = topology.chart(t);
                if other == own || topology.edge_triangle_exempt(e, t) {
                    return;
                }
                if segment_crosses_triangle(&p, &q, &tris[t].map(|i| x[i as usize])) {
                    found.push((own.min(other), own.max(other)));
                }
            });
            found
        })
        .collect();
    pairs.sort_unstable();
    let mut counted: Vec<((u32, u32), usize)> = Vec::new();
    for pair in pairs {
        match counted.last_mut() {
            Some((last, n)) if *last == pair => *n += 1,
            _ => counted.push((pair, 1)),
        }
    }
    counted
}

/// Rings of particles round each particle of a pair, through the mesh and the seams,
/// whose triangles are not counted across the pair: where seams meet at a corner (a
/// crotch, an underarm) the panels' corners lie between each other's pairs as the seams
/// close, and they are the seams closing, not a layer caught in them.
const JOINED_RINGS: usize = 3;

/// The triangles that the segment between each pair of `pairs` passes through at `x`, as
/// (pair, triangle), sorted: the cloth lying between two particles that a seam pulls
/// together. Triangles near either particle for good (see
/// [`Topology::segment_triangle_exempt`]) or within [`JOINED_RINGS`] of it are not counted.
pub(crate) fn across_pairs(topology: &Topology, x: &[Vec3], pairs: &[[usize; 2]]) -> Vec<(usize, usize)> {
    let tris = &topology.triangles;
    let tree = triangle_tree(topology, x);
    pairs
        .par_iter()
        .enumerate()
        .flat_map_iter(|(k, &[a, b])| {
            let (p, q) = (x[a], x[b]);
            let mut found = Vec::new();
            if a == b || p == q {
                return found;
            }
            tree.query(&Aabb::of([p, q]), |t| {
                if segment_crosses_triangle(&p, &q, &tris[t].map(|i| x[i as usize]))
                    && !topology.segment_triangle_exempt(a, b, t)
                {
                    found.push((k, t));
                }
            });
            if !found.is_empty() {
                let mut joined = topology.joined_within(a, JOINED_RINGS);
                joined.extend(topology.joined_within(b, JOINED_RINGS));
                joined.sort_unstable();
                found.retain(|&(_, t)| !topology.triangle_among(t, &joined));
            }
            found.sort_unstable();
            found
        })
        .collect()
}

/// The two sides of a layer pass as the cloth's primitives: the triangles having a
/// particle of each side, and their edges; found once, when the pass begins.
#[derive(Debug, Clone)]
pub(crate) struct PassRegion {
    triangles: [Vec<usize>; 2],
    edges: [Vec<usize>; 2],
}

impl PassRegion {
    pub(crate) fn new(topology: &Topology, sides: [&[usize]; 2]) -> Self {
        let triangles = sides.map(|particles| {
            let mut t: Vec<usize> = particles
                .iter()
                .flat_map(|&p| topology.triangles_of(p).iter().map(|&t| t as usize))
                .collect();
            t.sort_unstable();
            t.dedup();
            t
        });
        let edges = [0, 1].map(|k| {
            let mut e: Vec<usize> = triangles[k]
                .iter()
                .flat_map(|&t| topology.triangle_edges[t].map(|e| e as usize))
                .collect();
            e.sort_unstable();
            e.dedup();
            e
        });
        Self { triangles, edges }
    }
}

/// How many edge-triangle pairs of the two sides of `region` pass through each other at
/// `x`: an edge of one side against a triangle of the other, either way round (pairs
/// exempt for good not counted).
pub(crate) fn crossings_between(topology: &Topology, x: &[Vec3], region: &PassRegion) -> usize {
    let crossing = |edges: &[usize], tris: &[usize]| {
        let reach = tris.iter().fold(Aabb::empty(), |b, &t| {
            b.union(&Aabb::of(topology.triangles[t].map(|i| x[i as usize])))
        });
        edges
            .iter()
            .map(|&e| {
                let [a, b] = topology.edges[e].map(|i| x[i as usize]);
                if !Aabb::of([a, b]).overlaps(&reach) {
                    return 0;
                }
                tris.iter()
                    .filter(|&&t| {
                        let tri = topology.triangles[t].map(|i| x[i as usize]);
                        segment_crosses_triangle(&a, &b, &tri) && !topology.edge_triangle_exempt(e, t)
                    })
                    .count()
            })
            .sum::<usize>()
    };
    let [one, other] = &region.triangles;
    crossing(&region.edges[0], other) + crossing(&region.edges[1], one)
}

/// The intersecting edge-triangle pairs of `mesh` at positions `x`: pairs sharing a
/// particle, or particles that `seams` join, or within `rest_radius` of each other in the
/// flat cloth are exempt (as self-collision exempts them; see
/// [`crate::Simulation::self_intersections`]).
pub fn count_self_intersections(
    mesh: &ClothMesh,
    seams: &[[usize; 2]],
    rest_radius: f64,
    x: &[Vec3],
) -> Intersections {
    count(&Topology::new(mesh, seams, rest_radius), x)
}

/// The intersecting (edge, triangle) pairs of `mesh` at `x`, exempt as for
/// [`count_self_intersections`], sorted.
pub fn self_intersecting_pairs(
    mesh: &ClothMesh,
    seams: &[[usize; 2]],
    rest_radius: f64,
    x: &[Vec3],
) -> Vec<(usize, usize)> {
    SelfCrossings::new(mesh, seams, rest_radius).pairs(x)
}

/// Which pairs of a mesh are exempt, made once, to find its crossings at one position
/// after another (a repair that moves the cloth round after round) without making them
/// again each time.
#[derive(Debug, Clone)]
pub struct SelfCrossings(Topology);

impl SelfCrossings {
    /// The exemptions of [`self_intersecting_pairs`] for `mesh`.
    pub fn new(mesh: &ClothMesh, seams: &[[usize; 2]], rest_radius: f64) -> Self {
        Self(Topology::new(mesh, seams, rest_radius))
    }

    /// The intersecting (edge, triangle) pairs at `x`, sorted.
    pub fn pairs(&self, x: &[Vec3]) -> Vec<(usize, usize)> {
        crossing_pairs(&self.0, x)
    }
}

/// The smallest distance of a particle from a triangle of the cloth, pairs sharing a
/// particle (or seam partners) exempt, if one is under `within` (m).
pub(crate) fn closest_approach(topology: &Topology, x: &[Vec3], within: f64) -> Option<f64> {
    let tris = &topology.triangles;
    let tree = triangle_tree(topology, x);
    let closest = (0..topology.particles())
        .into_par_iter()
        .map(|p| {
            let mut best = f64::INFINITY;
            tree.query(&Aabb::point(&x[p]).inflated(within), |t| {
                if topology.vertex_triangle_exempt(p, t) {
                    return;
                }
                let [a, b, c] = tris[t].map(|i| x[i as usize]);
                let w = closest_on_triangle(&x[p], &a, &b, &c);
                best = best.min((x[p] - (w[0] * a + w[1] * b + w[2] * c)).norm());
            });
            best
        })
        .reduce(|| f64::INFINITY, f64::min);
    (closest < within).then_some(closest)
}

/// The smallest distance of a particle of `mesh` at `x` from one of its triangles, if one
/// is under `within` (m): how close layers of the cloth come. Pairs are exempt as for
/// [`count_self_intersections`].
pub fn closest_self_approach(
    mesh: &ClothMesh,
    seams: &[[usize; 2]],
    rest_radius: f64,
    x: &[Vec3],
    within: f64,
) -> Option<f64> {
    closest_approach(&Topology::new(mesh, seams, rest_radius), x, within)
}
