//! Edges and hinges (interior edges with the two vertices opposite them).

use crate::error::MeshError;
use std::collections::HashMap;

/// An interior edge `edge` shared by two triangles; `opposite[k]` is the vertex of
/// the k-th triangle that is not on the edge. The bending energies act on hinges.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Hinge {
    pub edge: [usize; 2],
    pub opposite: [usize; 2],
}

/// Unique edges (sorted vertex pairs) and hinges of a triangle list; fails on an
/// edge shared by more than two triangles.
pub(crate) fn edges_and_hinges(triangles: &[[usize; 3]]) -> Result<(Vec<[usize; 2]>, Vec<Hinge>), MeshError> {
    // edge -> (first triangle's opposite vertex, second's, count)
    let mut map: HashMap<[usize; 2], (usize, usize, usize)> = HashMap::with_capacity(triangles.len() * 2);
    let mut order = Vec::with_capacity(triangles.len() * 2);
    for tri in triangles {
        for k in 0..3 {
            let (a, b, c) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
            let key = if a < b { [a, b] } else { [b, a] };
            let entry = map.entry(key).or_insert_with(|| {
                order.push(key);
                (c, usize::MAX, 0)
            });
            if entry.2 == 1 {
                entry.1 = c;
            }
            entry.2 += 1;
        }
    }
    let mut hinges = Vec::new();
    for key in &order {
        let (o0, o1, count) = map[key];
        match count {
            1 => {}
            2 => hinges.push(Hinge {
                edge: *key,
                opposite: [o0, o1],
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
