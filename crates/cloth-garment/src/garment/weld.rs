//! Welding sewn seams: each group of paired vertices becomes one particle.

use super::{Garment, GarmentError};
use cloth_core::math::union_find::{find, union};
use cloth_core::{math::Vec3, ClothMesh};

/// The garment's mesh after welding, and where each unsewn vertex went.
#[derive(Debug, Clone)]
pub struct Welded {
    pub mesh: ClothMesh,
    /// The welded particle of each vertex of the unsewn mesh.
    pub particle_of: Vec<usize>,
}

impl Garment {
    /// The particle each vertex of the unsewn mesh becomes when the seams are welded,
    /// numbered from 0 in the order of their first vertices: vertices a seam joins,
    /// directly or through others, share one.
    pub(crate) fn seam_groups(&self) -> Vec<usize> {
        let n = self.mesh.vertex_count();
        let mut parent: Vec<usize> = (0..n).collect();
        for [a, b] in self.seam_pairs() {
            union(&mut parent, a, b);
        }
        let mut particle_of = vec![usize::MAX; n];
        let mut count = 0;
        for i in 0..n {
            let r = find(&mut parent, i);
            if particle_of[r] == usize::MAX {
                particle_of[r] = count;
                count += 1;
            }
            particle_of[i] = particle_of[r];
        }
        particle_of
    }

    /// Welds every seam pair at `positions` (each particle at the mean of the vertices it
    /// joins). Triangles keep their panels' material coordinates per corner, so the rest
    /// state is unchanged; edges and hinges are rebuilt across the seams.
    pub fn weld(&self, positions: &[Vec3]) -> Result<Welded, GarmentError> {
        let particle_of = self.seam_groups();
        let mut sum = vec![(Vec3::zeros(), 0.0); particle_of.iter().max().map_or(0, |&k| k + 1)];
        for (i, &k) in particle_of.iter().enumerate() {
            sum[k].0 += positions[i];
            sum[k].1 += 1.0;
        }
        let welded_positions = sum.iter().map(|(p, count)| p / *count).collect();
        let triangles: Vec<[usize; 3]> = self
            .mesh
            .triangles()
            .iter()
            .map(|t| t.map(|i| particle_of[i]))
            .collect();
        if let Some(t) = triangles
            .iter()
            .position(|t| t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
        {
            return Err(GarmentError::Collapse {
                triangle: t,
                panel: self.panel_names[self.triangle_panel[t]].clone(),
            });
        }
        let corner_uv = (0..triangles.len()).map(|t| self.mesh.corner_uv(t)).collect();
        let mesh = ClothMesh::with_corner_uv(welded_positions, triangles, corner_uv).map_err(|source| {
            GarmentError::Mesh {
                what: "the welded panels",
                source,
            }
        })?;
        Ok(Welded { mesh, particle_of })
    }
}
