//! The layout of a regular warp/weft grid, which a mesh made by [`super::GridBuilder`]
//! remembers.

/// How each grid cell is split into two triangles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GridDiagonals {
    /// Every cell split along the same diagonal.
    Uniform,
    /// Diagonals alternate in a checkerboard, so the mesh has the square's mirror symmetries.
    #[default]
    Alternating,
}

/// Shape of a regular warp/weft grid: vertex `j * nx + i` sits at thread crossing (i, j),
/// `i` counting along the warp (u), `j` along the weft (v).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridShape {
    pub nx: usize,
    pub ny: usize,
    /// Spacing along the warp and the weft, m.
    pub du: f64,
    pub dv: f64,
    pub diagonals: GridDiagonals,
}

impl GridShape {
    pub fn index(&self, i: usize, j: usize) -> usize {
        j * self.nx + i
    }
}
