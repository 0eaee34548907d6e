//! Edges and hinges (interior edges with the two vertices opposite them).

use super::error::MeshError;
use std::collections::HashMap;

/// An interior edge `edge` shared by two triangles; `opposite[k]` is the vertex of
/// the k-th triangle (`triangles[k]`) that is not on the edge. The bending energies act
/// on hinges.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Hinge {
    pub edge: [usize; 2],
    pub opposite: [usize; 2],
    pub triangles: [usize; 2],
}

/// Unique edges (sorted vertex pairs) and hinges of a triangle list; fails on an
/// edge shared by more than two triangles.
pub(crate) fn edges_and_hinges(triangles: &[[usize; 3]]) -> Result<(Vec<[usize; 2]>, Vec<Hinge>), MeshError> {
    // edge -> (each triangle's opposite vertex and index, count)
    type Wings = ([usize; 2], [usize; 2], usize);
    let mut map: HashMap<[usize; 2], Wings> = HashMap::with_capacity(triangles.len() * 2);
    let mut order = Vec::with_capacity(triangles.len() * 2);
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b, c) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
            let key = if a < b { [a, b] } else { [b, a] };
            let entry = map.entry(key).or_insert_with(|| {
                order.push(key);
                ([c, usize::MAX], [t, usize::MAX], 0)
            });
            if entry.2 == 1 {
                entry.0[1] = c;
                entry.1[1] = t;
            }
            entry.2 += 1;
        }
    }
    let mut hinges = Vec::new();
    for key in &order {
        let (opposite, wings, count) = map[key];
        match count {
            1 => {}
            2 => hinges.push(Hinge {
                edge: *key,
                opposite,
                triangles: wings,
            }),
            _ => {
                return Err(MeshError::NonManifoldEdge {
                    a: key[0],
                    b: key[1],
                    count,
                })
            }
        }
    }
    Ok((order, hinges))
}
