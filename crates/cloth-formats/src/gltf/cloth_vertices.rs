//! The cloth's glTF vertices: one per distinct (vertex, material coordinate) of its
//! triangle corners, so a seam vertex of a sewn garment is split into one per panel and
//! each keeps its panel's material coordinates and its panel label.

use crate::panels::PanelLabels;
use cloth_core::ClothMesh;
use std::collections::HashMap;
use std::io::{Error, ErrorKind};

#[derive(Debug, Clone)]
pub struct ClothVertices {
    /// The cloth vertex of each glTF vertex ...
    source: Vec<usize>,
    /// ... and the first triangle with a corner at it (all of them are one panel's).
    triangle: Vec<usize>,
    uv: Vec<[f32; 2]>,
    /// Three per triangle, in the mesh's order.
    indices: Vec<u32>,
}

impl ClothVertices {
    /// An `InvalidInput` error if the mesh needs more vertices than glTF's u32 indices.
    pub fn new(mesh: &ClothMesh) -> std::io::Result<Self> {
        // Keyed on the exact bits, as ClothMesh::cut_at_seams is: the corners of one panel
        // at a vertex carry the very same coordinates.
        let mut ids: HashMap<(usize, [u64; 2]), u32> = HashMap::new();
        let mut split = Self {
            source: Vec::new(),
            triangle: Vec::new(),
            uv: Vec::new(),
            indices: Vec::with_capacity(3 * mesh.triangles().len()),
        };
        for (t, tri) in mesh.triangles().iter().enumerate() {
            for (&v, c) in tri.iter().zip(mesh.corner_uv(t)) {
                let key = (v, [c.x.to_bits(), c.y.to_bits()]);
                let id = match ids.get(&key) {
                    Some(&id) => id,
                    None => {
                        let id = u32::try_from(split.source.len()).map_err(|_| {
                            Error::new(ErrorKind::InvalidInput, "too many cloth vertices for glTF")
                        })?;
                        split.source.push(v);
                        split.triangle.push(t);
                        split.uv.push([c.x as f32, c.y as f32]);
                        ids.insert(key, id);
                        id
                    }
                };
                split.indices.push(id);
            }
        }
        Ok(split)
    }

    /// How many glTF vertices there are.
    pub fn len(&self) -> usize {
        self.source.len()
    }

    pub fn is_empty(&self) -> bool {
        self.source.is_empty()
    }

    /// The material coordinates (u along the warp, v along the weft), m.
    pub fn uv(&self) -> &[[f32; 2]] {
        &self.uv
    }

    /// Three per triangle, in the mesh's order.
    pub fn indices(&self) -> &[u32] {
        &self.indices
    }

    /// A per-cloth-vertex attribute spread onto the glTF vertices.
    pub fn gather<T: Copy>(&self, values: &[T]) -> Vec<T> {
        self.source.iter().map(|&v| values[v]).collect()
    }

    /// Each glTF vertex's panel, as a float (glTF has no unsigned vertex attributes);
    /// -1 where the labels do not reach.
    pub fn panel_attribute(&self, panels: &PanelLabels) -> Vec<f32> {
        self.triangle
            .iter()
            .map(|&t| panels.of_triangle().get(t).map_or(-1.0, |&p| p as f32))
            .collect()
    }
}
