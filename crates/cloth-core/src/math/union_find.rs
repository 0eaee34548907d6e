//! Disjoint sets as a forest of parent links (each root its own parent), for the meshes'
//! pieces, seams and zones: one root found by halving the path, and sets joined under the
//! smaller root, so the roots do not depend on the order the joins came in.

/// An index into a forest: `u32` where the meshes keep `u32` indices, else `usize`.
pub trait Node: Copy + Ord {
    fn index(self) -> usize;
}

impl Node for u32 {
    fn index(self) -> usize {
        self as usize
    }
}

impl Node for usize {
    fn index(self) -> usize {
        self
    }
}

/// The root of `i`, halving the path to it on the way.
pub fn find<N: Node>(parent: &mut [N], mut i: N) -> N {
    while parent[i.index()] != i {
        let up = parent[parent[i.index()].index()];
        parent[i.index()] = up;
        i = up;
    }
    i
}

/// Joins the sets of `a` and `b` under the smaller of their roots; whether they were apart.
pub fn union<N: Node>(parent: &mut [N], a: N, b: N) -> bool {
    let (ra, rb) = (find(parent, a), find(parent, b));
    if ra == rb {
        return false;
    }
    parent[ra.max(rb).index()] = ra.min(rb);
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn joined_sets_share_the_smallest_root_whatever_the_order() {
        for joins in [[(4usize, 2usize), (2, 3), (0, 1)], [(0, 1), (3, 2), (2, 4)]] {
            let mut parent: Vec<usize> = (0..6).collect();
            for (a, b) in joins {
                assert!(union(&mut parent, a, b));
            }
            assert!(!union(&mut parent, 4, 3), "already one set");
            let roots: Vec<usize> = (0..6).map(|i| find(&mut parent, i)).collect();
            assert_eq!(roots, [0, 0, 2, 2, 2, 5]);
        }
        let mut parent: Vec<u32> = vec![0, 0, 1, 2];
        assert_eq!(find(&mut parent, 3), 0);
        assert!(parent[3] != 2, "the path was halved");
    }
}
