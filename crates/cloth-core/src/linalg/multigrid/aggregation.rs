//! Greedy aggregation of a matrix graph (Vaněk, Mandel & Brezina 1996): the nodes are
//! grouped into small aggregates connected by strong couplings, each one unknown block of
//! the coarser level.

use crate::linalg::BlockSparse;

/// The aggregate of each node and the number of aggregates.
#[derive(Debug, Clone)]
pub(super) struct Aggregates {
    pub of_node: Vec<u32>,
    pub count: usize,
}

const NONE: u32 = u32::MAX;
/// Uncoupled nodes per aggregate.
const UNCOUPLED_BATCH: usize = 8;

/// A coupling `A_ij` is strong when `|A_ij| >= strength * sqrt(|A_ii| |A_jj|)` (Frobenius
/// norms; with `strength` 0, every stored coupling). In node order: a node whose strong
/// neighbours are all unassigned founds an aggregate of itself and them; a node left over
/// joins the neighbouring aggregate it has most strong couplings with (it has one, or it
/// would have founded its own); nodes with no strong coupling are grouped by eights.
/// Every aggregate but the last has at least two nodes, so a level at least halves.
pub(super) fn aggregate(a: &BlockSparse, strength: f64) -> Aggregates {
    let n = a.n();
    let mut of_node = vec![NONE; n];
    let mut count = 0u32;
    let norm = |s: usize| a.blocks()[s].norm();
    let neighbours = |i: usize| {
        let di = norm(a.diag_slot(i));
        a.row(i)
            .filter(move |&s| norm(s) >= strength * (di * norm(a.diag_slot(a.col_of(s)))).sqrt())
            .map(|s| a.col_of(s))
            .filter(move |&j| j != i)
    };

    for i in 0..n {
        if of_node[i] == NONE && neighbours(i).all(|j| of_node[j] == NONE) {
            of_node[i] = count;
            for j in neighbours(i) {
                of_node[j] = count;
            }
            count += 1;
        }
    }

    // Join the aggregates of the first pass only, so nothing joins through a joined node.
    let first_pass = of_node.clone();
    let mut tally: Vec<(u32, u32)> = Vec::new();
    for i in 0..n {
        if of_node[i] != NONE {
            continue;
        }
        tally.clear();
        for j in neighbours(i) {
            let g = first_pass[j];
            if g == NONE {
                continue;
            }
            match tally.iter_mut().find(|(h, _)| *h == g) {
                Some((_, c)) => *c += 1,
                None => tally.push((g, 1)),
            }
        }
        // Most couplings, then the lowest aggregate: the choice does not depend on the
        // order of the row.
        if let Some(&(g, _)) = tally.iter().max_by(|x, y| x.1.cmp(&y.1).then(y.0.cmp(&x.0))) {
            of_node[i] = g;
        }
    }

    // Left now are only nodes with no strong coupling at all (a stray vertex, or a
    // coupling too weak to matter): grouped a few at a time in node order, so the level
    // still shrinks; with nothing between them, any grouping is as good.
    let mut batch = 0;
    for node in of_node.iter_mut().filter(|g| **g == NONE) {
        *node = count;
        batch += 1;
        if batch == UNCOUPLED_BATCH {
            count += 1;
            batch = 0;
        }
    }
    if batch > 0 {
        count += 1;
    }
    Aggregates {
        of_node,
        count: count as usize,
    }
}
