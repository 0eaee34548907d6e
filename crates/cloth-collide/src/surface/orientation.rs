//! Consistent orientation: across every edge of exactly two triangles, the two run along
//! it in opposite directions. Parts are the triangles connected through such edges.

use super::edges::{edge_groups, Side};

/// What orienting did.
pub(super) struct Orientation {
    /// Triangles turned round.
    pub flipped: usize,
    /// Edges whose two triangles still disagree (the part cannot be oriented).
    pub conflicts: usize,
}

/// The neighbours of each triangle across its two-sided edges, and whether the two run
/// along the edge the same way (disagree).
fn neighbours(triangle_count: usize, sides: &[Side]) -> Vec<Vec<(u32, bool)>> {
    let mut out = vec![Vec::new(); triangle_count];
    for group in edge_groups(sides) {
        if let [s, t] = group {
            let disagree = s.forward == t.forward;
            out[s.triangle as usize].push((t.triangle, disagree));
            out[t.triangle as usize].push((s.triangle, disagree));
        }
    }
    out
}

/// Turns triangles round so that each part agrees with itself, walking breadth-first
/// across two-sided edges and keeping the way most of the part's triangles face. Edges of
/// one or of three or more triangles do not connect, so a closed 2-manifold is never
/// changed unless it disagrees with itself.
pub(super) fn orient(triangles: &mut [[u32; 3]], sides: &[Side]) -> Orientation {
    let around = neighbours(triangles.len(), sides);
    // None: not reached yet; Some(flip).
    let mut state: Vec<Option<bool>> = vec![None; triangles.len()];
    let mut conflicts = 0;
    let mut part = Vec::new();
    for seed in 0..triangles.len() {
        if state[seed].is_some() {
            continue;
        }
        state[seed] = Some(false);
        part.clear();
        part.push(seed);
        let mut next = 0;
        while let Some(&t) = part.get(next) {
            next += 1;
            let flip = state[t] == Some(true);
            for &(n, disagree) in &around[t] {
                let wanted = flip ^ disagree;
                match state[n as usize] {
                    None => {
                        state[n as usize] = Some(wanted);
                        part.push(n as usize);
                    }
                    // Each edge is seen from both sides: count it once.
                    Some(s) if s != wanted && t < n as usize => conflicts += 1,
                    Some(_) => {}
                }
            }
        }
        let flips = part.iter().filter(|&&t| state[t] == Some(true)).count();
        if 2 * flips > part.len() {
            for &t in &part {
                state[t] = state[t].map(|f| !f);
            }
        }
    }
    let mut flipped = 0;
    for (tri, s) in triangles.iter_mut().zip(&state) {
        if *s == Some(true) {
            tri.swap(1, 2);
            flipped += 1;
        }
    }
    Orientation { flipped, conflicts }
}

/// Labels triangles by part (connected through two-sided edges), labels numbered in order
/// of first triangle.
pub(super) fn components(triangle_count: usize, sides: &[Side]) -> Vec<usize> {
    let around = neighbours(triangle_count, sides);
    cloth_core::components(triangle_count, |t| around[t].iter().map(|&(n, _)| n as usize))
}
