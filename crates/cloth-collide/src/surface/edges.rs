//! Triangle sides grouped by undirected edge: the adjacency that validation and feature
//! detection share.

/// One side of a triangle, keyed by its undirected edge first so that sorting brings the
/// sides of the same edge together.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(super) struct Side {
    pub lo: u32,
    pub hi: u32,
    pub triangle: u32,
    /// The triangle runs along the edge from `lo` to `hi`.
    pub forward: bool,
}

/// All triangle sides, sorted by edge. Sorting rather than hashing keeps every report
/// (which edge is named first) independent of hash seeds.
pub(super) fn sorted_sides(triangles: &[[u32; 3]]) -> Vec<Side> {
    let mut sides = Vec::with_capacity(3 * triangles.len());
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (from, to) = (tri[k], tri[(k + 1) % 3]);
            sides.push(Side {
                lo: from.min(to),
                hi: from.max(to),
                triangle: t as u32,
                forward: from < to,
            });
        }
    }
    sides.sort_unstable();
    sides
}

/// The sides of each undirected edge, in edge order.
pub(super) fn edge_groups(sides: &[Side]) -> impl Iterator<Item = &[Side]> {
    sides.chunk_by(|x, y| (x.lo, x.hi) == (y.lo, y.hi))
}
