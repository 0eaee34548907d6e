//! Welding: merging vertices that are closer than a tolerance.

use std::collections::HashMap;

use cloth_core::Vec3;

/// A welded, compacted mesh.
pub(super) struct Welded {
    pub vertices: Vec<Vec3>,
    pub triangles: Vec<[u32; 3]>,
    /// For each kept vertex, the input index it came from, so errors can name it.
    pub original: Vec<usize>,
}

/// Maps every vertex to the first earlier vertex within `distance` (or itself), then drops
/// vertices no triangle uses. Kept vertices stay in input order, so the result does not
/// depend on anything but the input.
pub(super) fn weld(vertices: &[Vec3], triangles: &[[u32; 3]], distance: f64) -> Welded {
    let representative = if distance > 0.0 {
        representatives_within(vertices, distance)
    } else {
        representatives_exact(vertices)
    };
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
        original,
    }
}

/// Spatial hash with cells of size `distance`: a vertex within `distance` of another lies in
/// the same or a neighbouring cell.
fn representatives_within(vertices: &[Vec3], distance: f64) -> Vec<u32> {
    let mut cells: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
    let cell_of = |p: &Vec3| p.map(|c| (c / distance).floor() as i64);
    let mut representative = Vec::with_capacity(vertices.len());
    for (i, p) in vertices.iter().enumerate() {
        let cell = cell_of(p);
        let mut best: Option<u32> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    // Wrapping: a coordinate over i64::MAX cells saturates, and its neighbour
                    // key only has to be some key, not a panic.
                    let key = [
                        cell.x.wrapping_add(dx),
                        cell.y.wrapping_add(dy),
                        cell.z.wrapping_add(dz),
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
        representative.push(best.unwrap_or_else(|| {
            cells.entry([cell.x, cell.y, cell.z]).or_default().push(i as u32);
            i as u32
        }));
    }
    representative
}

fn representatives_exact(vertices: &[Vec3]) -> Vec<u32> {
    let mut first: HashMap<[u64; 3], u32> = HashMap::new();
    // `+ 0.0` turns -0.0 into 0.0 so the two zeros weld.
    vertices
        .iter()
        .enumerate()
        .map(|(i, p)| {
            *first
                .entry([p.x, p.y, p.z].map(|c| (c + 0.0).to_bits()))
                .or_insert(i as u32)
        })
        .collect()
}
