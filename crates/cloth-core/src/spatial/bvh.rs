//! A bounding volume hierarchy of axis-aligned boxes, built once over primitives where
//! they start and refitted to their moving boxes every time it is asked. Cloth barely
//! stretches, and a rigid body's edges keep their arrangement, so primitives grouped near
//! each other at the start stay near each other however the cloth folds or the body moves:
//! refitting keeps the tree useful without rebuilding.

use crate::math::Vec3;

/// Primitives per leaf at most.
const LEAF_SIZE: usize = 4;
/// Deepest tree a query walks: median splits halve every level, so 2^64 primitives.
const MAX_DEPTH: usize = 64;

/// An axis-aligned box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    pub lo: Vec3,
    pub hi: Vec3,
}

impl Aabb {
    /// The empty box: the union with it changes nothing.
    pub fn empty() -> Self {
        Self {
            lo: Vec3::repeat(f64::INFINITY),
            hi: Vec3::repeat(f64::NEG_INFINITY),
        }
    }
    pub fn point(p: &Vec3) -> Self {
        Self { lo: *p, hi: *p }
    }
    /// The box of `points`.
    pub fn of(points: impl IntoIterator<Item = Vec3>) -> Self {
        let mut b = Self::empty();
        for p in points {
            b.grow(&p);
        }
        b
    }
    pub fn grow(&mut self, p: &Vec3) {
        self.lo = self.lo.inf(p);
        self.hi = self.hi.sup(p);
    }
    pub fn union(&self, other: &Self) -> Self {
        Self {
            lo: self.lo.inf(&other.lo),
            hi: self.hi.sup(&other.hi),
        }
    }
    /// The box grown by `r` on every side.
    pub fn inflated(&self, r: f64) -> Self {
        Self {
            lo: self.lo.add_scalar(-r),
            hi: self.hi.add_scalar(r),
        }
    }
    pub fn overlaps(&self, other: &Self) -> bool {
        (0..3).all(|k| self.lo[k] <= other.hi[k] && other.lo[k] <= self.hi[k])
    }
}

/// A node: a leaf holds `count > 0` primitives from `first` in the tree's order; an inner
/// node's children are the next node and `right`. Either way its subtree's primitives are
/// the `span` from `first`.
#[derive(Debug, Clone, Copy)]
struct Node {
    first: u32,
    count: u32,
    right: u32,
    span: u32,
}

/// Node pairs a traversal keeps on its stack at most.
const PAIR_STACK: usize = 4 * MAX_DEPTH;

/// The hierarchy of `len` primitives: its shape, fixed at build, and the boxes of its
/// nodes, set by [`Bvh::refit`].
#[derive(Debug, Clone)]
pub struct Bvh {
    nodes: Vec<Node>,
    boxes: Vec<Aabb>,
    /// The primitives in leaf order.
    order: Vec<u32>,
}

impl Bvh {
    /// The tree of primitives whose centres are `centres`, split at the median of the
    /// longest side of their bounds until leaves hold a few.
    pub fn new(centres: &[Vec3]) -> Self {
        let mut order: Vec<u32> = (0..centres.len() as u32).collect();
        let mut nodes = Vec::with_capacity(2 * centres.len() / LEAF_SIZE + 1);
        if !centres.is_empty() {
            split(centres, &mut order, 0, &mut nodes);
        }
        let boxes = vec![Aabb::empty(); nodes.len()];
        Self { nodes, boxes, order }
    }

    /// Sets every node's box from the primitives' boxes, `bound(i)` that of primitive `i`.
    pub fn refit(&mut self, bound: impl Fn(usize) -> Aabb) {
        let mut boxes = std::mem::take(&mut self.boxes);
        self.fold_up(
            &mut boxes,
            |items| {
                items
                    .iter()
                    .fold(Aabb::empty(), |b, &i| b.union(&bound(i as usize)))
            },
            Aabb::union,
        );
        self.boxes = boxes;
    }

    /// Number of primitives.
    pub fn len(&self) -> usize {
        self.order.len()
    }

    /// Number of nodes; the root is node 0.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    pub fn node_box(&self, k: usize) -> &Aabb {
        &self.boxes[k]
    }

    /// The primitives under node `k`.
    pub fn subtree(&self, k: usize) -> &[u32] {
        let n = self.nodes[k];
        &self.order[n.first as usize..(n.first + n.span) as usize]
    }

    /// Where node `k`'s primitives lie in the tree's order (that of [`Bvh::subtree`] of the
    /// root).
    pub fn span(&self, k: usize) -> std::ops::Range<usize> {
        let n = self.nodes[k];
        n.first as usize..(n.first + n.span) as usize
    }

    pub fn is_leaf(&self, k: usize) -> bool {
        self.nodes[k].count > 0
    }

    /// The children of an inner node.
    fn children(&self, k: usize) -> Option<(usize, usize)> {
        let n = self.nodes[k];
        (n.count == 0).then_some((k + 1, n.right as usize))
    }

    /// Sets a value for every node from its primitives', `leaf(items)` for a leaf and
    /// `merge(left, right)` for an inner node, into `out` (one per node). Children follow
    /// their parents in the node list, so one backward pass does it.
    pub fn fold_up<T: Copy>(&self, out: &mut [T], leaf: impl Fn(&[u32]) -> T, merge: impl Fn(&T, &T) -> T) {
        assert_eq!(out.len(), self.nodes.len(), "one value per node");
        for k in (0..self.nodes.len()).rev() {
            out[k] = match self.children(k) {
                None => leaf(self.subtree(k)),
                Some((l, r)) => merge(&out[l], &out[r]),
            };
        }
    }

    /// The pairs of nodes `(a, b)` (`a == b` for a node against itself) that `keep` accepts,
    /// from the root against itself down, a level at a time, until there are `want` of them
    /// or none left to split: the tasks of a parallel traversal (see [`Bvh::leaf_pairs`]).
    /// `scratch` holds a level while the next is made.
    pub fn pair_tasks(
        &self,
        keep: impl Fn(usize, usize) -> bool,
        want: usize,
        tasks: &mut Vec<(u32, u32)>,
        scratch: &mut Vec<(u32, u32)>,
    ) {
        tasks.clear();
        if self.nodes.is_empty() || !keep(0, 0) {
            return;
        }
        tasks.push((0, 0));
        while tasks.len() < want {
            std::mem::swap(tasks, scratch);
            tasks.clear();
            let mut split = false;
            for &(a, b) in scratch.iter() {
                let (a, b) = (a as usize, b as usize);
                if self.split_pair(a, b, &keep, |x, y| tasks.push((x as u32, y as u32))) {
                    split = true;
                } else {
                    tasks.push((a as u32, b as u32));
                }
            }
            if !split {
                break;
            }
        }
    }

    /// The child pairs of `(a, b)` that `keep` accepts, to `push`; false for two leaves
    /// (nothing to split).
    fn split_pair(
        &self,
        a: usize,
        b: usize,
        keep: &impl Fn(usize, usize) -> bool,
        mut push: impl FnMut(usize, usize),
    ) -> bool {
        let mut offer = |x: usize, y: usize| {
            if keep(x, y) {
                push(x, y);
            }
        };
        if a == b {
            let Some((l, r)) = self.children(a) else {
                return false;
            };
            offer(l, l);
            offer(r, r);
            offer(l, r);
            return true;
        }
        let split_a = match (self.children(a), self.children(b)) {
            (None, None) => return false,
            (Some(_), None) => true,
            (None, Some(_)) => false,
            (Some(_), Some(_)) => self.nodes[a].span >= self.nodes[b].span,
        };
        if split_a {
            let (l, r) = self.children(a).expect("inner");
            offer(l, b);
            offer(r, b);
        } else {
            let (l, r) = self.children(b).expect("inner");
            offer(a, l);
            offer(a, r);
        }
        true
    }

    /// Every pair of leaves under the node pair `task` that `keep` accepts (and every pair
    /// above them), depth first: `visit(primitives of a, primitives of b, a == b)`.
    pub fn leaf_pairs(
        &self,
        task: (u32, u32),
        keep: impl Fn(usize, usize) -> bool,
        mut visit: impl FnMut(&[u32], &[u32], bool),
    ) {
        let mut stack = [(0u32, 0u32); PAIR_STACK];
        stack[0] = task;
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let (a, b) = (stack[top].0 as usize, stack[top].1 as usize);
            let mut children = [(0u32, 0u32); 3];
            let mut count = 0;
            let inner = self.split_pair(a, b, &keep, |x, y| {
                children[count] = (x as u32, y as u32);
                count += 1;
            });
            if !inner {
                visit(self.subtree(a), self.subtree(b), a == b);
                continue;
            }
            // A stack this deep would need a tree far deeper than median splits build.
            assert!(top + count <= PAIR_STACK, "bounding volume hierarchy too deep");
            stack[top..top + count].copy_from_slice(&children[..count]);
            top += count;
        }
    }

    /// Calls `visit` with every primitive whose leaf's box overlaps `query` (a superset
    /// of the primitives whose own boxes do).
    pub fn query(&self, query: &Aabb, mut visit: impl FnMut(usize)) {
        if self.nodes.is_empty() {
            return;
        }
        let mut stack = [0u32; MAX_DEPTH];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let k = stack[top] as usize;
            if !self.boxes[k].overlaps(query) {
                continue;
            }
            let node = self.nodes[k];
            if node.count > 0 {
                for &i in &self.order[node.first as usize..(node.first + node.count) as usize] {
                    visit(i as usize);
                }
            } else {
                stack[top] = node.right;
                stack[top + 1] = k as u32 + 1;
                top += 2;
            }
        }
    }
}

/// Builds the subtree of `order[..]` (which starts at `first` in the whole order) into
/// `nodes`, depth first.
fn split(centres: &[Vec3], order: &mut [u32], first: usize, nodes: &mut Vec<Node>) {
    let k = nodes.len();
    nodes.push(Node {
        first: first as u32,
        count: order.len() as u32,
        right: 0,
        span: order.len() as u32,
    });
    if order.len() <= LEAF_SIZE {
        return;
    }
    let bounds = Aabb::of(order.iter().map(|&i| centres[i as usize]));
    let extent = bounds.hi - bounds.lo;
    let axis = extent.imax();
    let mid = order.len() / 2;
    order.select_nth_unstable_by(mid, |&a, &b| {
        centres[a as usize][axis].total_cmp(&centres[b as usize][axis])
    });
    nodes[k].count = 0;
    let (left, right) = order.split_at_mut(mid);
    split(centres, left, first, nodes);
    nodes[k].right = nodes.len() as u32;
    split(centres, right, first + mid, nodes);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_query_finds_every_overlapping_box_after_a_refit() {
        // Points on a 30 x 30 grid, then moved (folded over) before the refit.
        let n = 30;
        let start: Vec<Vec3> = (0..n * n)
            .map(|k| Vec3::new((k % n) as f64, (k / n) as f64, 0.0))
            .collect();
        let mut bvh = Bvh::new(&start);
        let moved: Vec<Vec3> = start
            .iter()
            .map(|p| {
                let a = p.x / n as f64 * std::f64::consts::PI;
                Vec3::new(10.0 * a.cos(), p.y, 10.0 * a.sin())
            })
            .collect();
        bvh.refit(|i| Aabb::point(&moved[i]).inflated(0.3));
        for q in [
            Aabb::point(&Vec3::new(0.0, 5.0, 10.0)).inflated(2.0),
            Aabb::point(&Vec3::new(-10.0, 0.0, 0.0)).inflated(1.5),
            Aabb::point(&Vec3::new(100.0, 0.0, 0.0)).inflated(1.0),
        ] {
            let mut found = Vec::new();
            bvh.query(&q, |i| found.push(i));
            for (i, p) in moved.iter().enumerate() {
                if Aabb::point(p).inflated(0.3).overlaps(&q) {
                    assert!(found.contains(&i), "missed {i}");
                }
            }
            // Leaves hold a few primitives: the query stays local.
            assert!(found.len() < 200, "{} found", found.len());
        }
    }
}
