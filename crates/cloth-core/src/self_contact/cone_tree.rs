//! The cloth's triangles in a bounding volume hierarchy, searched for pairs near each other
//! by walking it against itself (node pairs whose boxes overlap, down to leaf pairs). Each
//! node carries the cone of its triangles' normals and whether they are one connected
//! piece: a connected patch whose normals spread less than a right angle is a gently
//! curved sheet that cannot fold onto itself, and is not searched against itself (see
//! [`super::cone`]). Most of a draped garment is such patches, so its search visits little
//! more than the folds. A patch that winds round like a spiral ramp would escape this test;
//! the hierarchy's patches, compact pieces of cloth, do not.

use super::cone::Cone;
use super::contour::{outer, star_shaped, Contours, Motion};
use super::topology::Topology;
use crate::math::union_find::union;
use crate::math::Vec3;
use crate::spatial::{Aabb, Bvh};

/// Node pairs a search is split into, for the threads.
const TASKS: usize = 256;

#[derive(Debug, Clone)]
pub(crate) struct ConeTree {
    pub bvh: Bvh,
    cones: Vec<Cone>,
    /// Each triangle's box at the last refit. Two triangles whose boxes are apart hold no
    /// pair a search tests (each test asks at least as much of its primitives' boxes),
    /// though their leaves' boxes overlap: of the triangle pairs in the leaf pairs a
    /// draped dress's search met, most were so.
    boxes: Vec<Aabb>,
    /// Whether each node's triangles are one connected piece (fixed with the mesh).
    connected: Vec<bool>,
    /// Whether each node has a triangle with a particle to search again.
    dirty: Vec<bool>,
    contours: Contours,
    pub tasks: Vec<(u32, u32)>,
    scratch: Vec<(u32, u32)>,
}

impl ConeTree {
    /// The tree of `topology`'s triangles where they are at `x`.
    pub fn new(topology: &Topology, x: &[Vec3]) -> Self {
        let centres: Vec<Vec3> = topology
            .triangles
            .iter()
            .map(|t| t.iter().map(|&i| x[i as usize]).sum::<Vec3>() / 3.0)
            .collect();
        let bvh = Bvh::new(&centres);
        let connected = connected_nodes(&bvh, topology);
        Self {
            contours: Contours::new(&bvh, topology, x),
            cones: vec![Cone::FULL; bvh.node_count()],
            boxes: vec![Aabb::empty(); topology.triangles.len()],
            dirty: vec![true; bvh.node_count()],
            bvh,
            connected,
            tasks: Vec::new(),
            scratch: Vec::new(),
        }
    }

    /// Each node's box and normal cone from its triangles', `bound(t)` and `normals(t)`.
    pub fn refit(&mut self, bound: impl Fn(usize) -> Aabb, normals: impl Fn(usize) -> Cone) {
        for (t, b) in self.boxes.iter_mut().enumerate() {
            *b = bound(t);
        }
        let boxes = &self.boxes;
        self.bvh.refit(|t| boxes[t]);
        self.bvh.fold_up(
            &mut self.cones,
            |items| {
                items
                    .iter()
                    .skip(1)
                    .fold(normals(items[0] as usize), |c, &t| c.merge(&normals(t as usize)))
            },
            |a, b| a.merge(b),
        );
    }

    /// Marks the nodes with a triangle that `dirty(t)` picks.
    pub fn mark(&mut self, dirty: impl Fn(usize) -> bool) {
        let mut flags = std::mem::take(&mut self.dirty);
        self.bvh.fold_up(
            &mut flags,
            |items| items.iter().any(|&t| dirty(t as usize)),
            |a, b| *a || *b,
        );
        self.dirty = flags;
    }

    /// Whether the search goes on into the node pair `(a, b)`: their boxes overlap, they
    /// are not together a flat patch, and in a search of the dirty nodes only, one of them
    /// is dirty.
    pub fn keep(&self, a: usize, b: usize, search: &Search<'_>) -> bool {
        self.bvh.node_box(a).overlaps(self.bvh.node_box(b))
            && (!search.only_dirty || self.dirty[a] || self.dirty[b])
            && !self.flat_together(a, b, search)
    }

    /// Whether nodes `a` and `b` are together one connected patch with its normals within
    /// a flat cone and its contour star-shaped over the search's motion: a node alone, or
    /// two neighbouring leaves (the commonest pair a walk meets, all along the patches'
    /// borders).
    fn flat_together(&self, a: usize, b: usize, search: &Search<'_>) -> bool {
        if a == b {
            let cone = &self.cones[a];
            return self.connected[a]
                && cone.is_flat()
                && star_shaped(
                    self.contours.of(a).iter().copied(),
                    search.topology.triangles[self.contours.centre(a) as usize],
                    cone.axis(),
                    &search.motion,
                );
        }
        // The cheap tests first: most pairs a walk meets are of inner nodes.
        if !(self.bvh.is_leaf(a) && self.bvh.is_leaf(b) && self.connected[a] && self.connected[b]) {
            return false;
        }
        let cone = self.cones[a].merge(&self.cones[b]);
        if !cone.is_flat() {
            return false;
        }
        let Some(centre) = self.contours.pair_centre(a, b) else {
            return false;
        };
        let (ca, cb) = (self.contours.of(a), self.contours.of(b));
        star_shaped(
            outer(ca, cb).chain(outer(cb, ca)),
            search.topology.triangles[centre as usize],
            cone.axis(),
            &search.motion,
        )
    }

    /// Splits the search into node-pair tasks.
    pub fn plan(&mut self, search: &Search<'_>) {
        let (mut tasks, mut scratch) = (std::mem::take(&mut self.tasks), std::mem::take(&mut self.scratch));
        self.bvh
            .pair_tasks(|a, b| self.keep(a, b, search), TASKS, &mut tasks, &mut scratch);
        (self.tasks, self.scratch) = (tasks, scratch);
    }

    /// Every pair of triangles (each unordered pair once, a triangle with itself too) in
    /// the leaf pairs under `task` whose boxes overlap.
    pub fn triangle_pairs(&self, task: (u32, u32), search: &Search<'_>, mut visit: impl FnMut(usize, usize)) {
        self.bvh.leaf_pairs(
            task,
            |a, b| self.keep(a, b, search),
            |first, second, same| {
                for (k, &s) in first.iter().enumerate() {
                    let others = if same { &second[k..] } else { second };
                    let near = &self.boxes[s as usize];
                    for &t in others {
                        if near.overlaps(&self.boxes[t as usize]) {
                            visit(s as usize, t as usize);
                        }
                    }
                }
            },
        );
    }
}

/// What a walk of the tree searches: the cloth's topology, its motion over the step (the
/// contour test holds over all of it), and whether only dirty nodes.
pub(crate) struct Search<'a> {
    pub topology: &'a Topology,
    pub motion: Motion<'a>,
    pub only_dirty: bool,
}

/// Whether each node's triangles are one piece through shared edges.
fn connected_nodes(bvh: &Bvh, topology: &Topology) -> Vec<bool> {
    let n = topology.triangles.len();
    let mut member = vec![u32::MAX; n];
    let mut parent: Vec<u32> = (0..n as u32).collect();
    (0..bvh.node_count())
        .map(|k| {
            let items = bvh.subtree(k);
            for &t in items {
                member[t as usize] = k as u32;
                parent[t as usize] = t;
            }
            let mut pieces = items.len();
            for &t in items {
                for c in 0..3 {
                    let Some(s) = topology.across(t as usize, c) else {
                        continue;
                    };
                    if member[s] != k as u32 {
                        continue;
                    }
                    if union(&mut parent, t, s as u32) {
                        pieces -= 1;
                    }
                }
            }
            pieces == 1
        })
        .collect()
}
