//! Welding: joining vertices on open edges that lie within a tolerance, which is what
//! closes an STL file (every corner repeated) or an OBJ split along texture seams.
//! Vertices that the faces keep apart on a closed surface are never joined, however
//! close they lie (a mouth's corners, an eyelid's two rims).

use std::collections::HashMap;

use cloth_core::math::Vec3;

use super::edges::{edge_groups, sorted_sides};

/// A welded, compacted mesh.
pub(super) struct Welded {
    pub vertices: Vec<Vec3>,
    pub triangles: Vec<[u32; 3]>,
    /// How many vertices were joined to another.
    pub joined: usize,
}

/// Maps every vertex on an open edge to the first earlier such vertex within `distance`
/// (or itself), then drops vertices no triangle uses. Kept vertices stay in input order,
/// so the result depends on nothing but the input.
pub(super) fn weld(vertices: &[Vec3], triangles: &[[u32; 3]], distance: f64) -> Welded {
    let sides = sorted_sides(triangles);
    let mut open = vec![false; vertices.len()];
    for group in edge_groups(&sides).filter(|g| g.len() == 1) {
        open[group[0].lo as usize] = true;
        open[group[0].hi as usize] = true;
    }
    let representative = representatives(vertices, &open, distance);
    let joined = representative
        .iter()
        .enumerate()
        .filter(|&(i, &r)| r as usize != i)
        .count();
    let triangles: Vec<[u32; 3]> = triangles
        .iter()
        .map(|tri| tri.map(|i| representative[i as usize]))
        .collect();
    let mut used = vec![false; vertices.len()];
    for &i in triangles.iter().flatten() {
        used[i as usize] = true;
    }
    let original: Vec<usize> = (0..vertices.len()).filter(|&i| used[i]).collect();
    let mut new_index = vec![u32::MAX; vertices.len()];
    for (new, &old) in original.iter().enumerate() {
        new_index[old] = new as u32;
    }
    Welded {
        vertices: original.iter().map(|&i| vertices[i]).collect(),
        triangles: triangles
            .iter()
            .map(|tri| tri.map(|i| new_index[i as usize]))
            .collect(),
        joined,
    }
}

/// For each vertex, the first earlier open vertex within `distance` if it is open itself,
/// else itself. A spatial hash with cells of size `distance` finds them (exact equality of
/// coordinates when `distance` is 0).
fn representatives(vertices: &[Vec3], open: &[bool], distance: f64) -> Vec<u32> {
    let mut cells: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
    let cell_of = |p: &Vec3| -> [i64; 3] {
        if distance > 0.0 {
            [p.x, p.y, p.z].map(|c| (c / distance).floor() as i64)
        } else {
            // `+ 0.0` turns -0.0 into 0.0 so the two zeros weld.
            [p.x, p.y, p.z].map(|c| (c + 0.0).to_bits() as i64)
        }
    };
    let reach: i64 = if distance > 0.0 { 1 } else { 0 };
    let mut representative: Vec<u32> = (0..vertices.len() as u32).collect();
    for (i, p) in vertices.iter().enumerate() {
        if !open[i] {
            continue;
        }
        let cell = cell_of(p);
        let mut best: Option<u32> = None;
        for dx in -reach..=reach {
            for dy in -reach..=reach {
                for dz in -reach..=reach {
                    // Wrapping: a coordinate over i64::MAX cells saturates, and its neighbour
                    // key only has to be some key, not a panic.
                    let key = [
                        cell[0].wrapping_add(dx),
                        cell[1].wrapping_add(dy),
                        cell[2].wrapping_add(dz),
                    ];
                    let Some(kept) = cells.get(&key) else { continue };
                    for &j in kept {
                        if (vertices[j as usize] - p).norm() <= distance && best.is_none_or(|b| j < b) {
                            best = Some(j);
                        }
                    }
                }
            }
        }
        match best {
            Some(j) => representative[i] = j,
            None => cells.entry(cell).or_default().push(i as u32),
        }
    }
    representative
}
