//! Why a cloth mesh cannot be simulated: each error names the triangle, vertex or edge.

use thiserror::Error;

/// A cloth mesh that cannot be simulated.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum MeshError {
    #[error("mesh has no triangles")]
    Empty,
    #[error("mesh has {positions} positions but {uvs} material (u, v) coordinates")]
    LengthMismatch { positions: usize, uvs: usize },
    #[error("triangle {triangle} refers to vertex {index}, but the mesh has {vertex_count} vertices")]
    IndexOutOfRange {
        triangle: usize,
        index: usize,
        vertex_count: usize,
    },
    #[error("triangle {triangle} repeats vertex {index}")]
    RepeatedVertex { triangle: usize, index: usize },
    #[error("triangle {triangle} is degenerate in {space} (area {area:e})")]
    DegenerateTriangle {
        triangle: usize,
        space: &'static str,
        area: f64,
    },
    #[error("edge ({a}, {b}) is shared by {count} triangles (at most 2 allowed): non-manifold")]
    NonManifoldEdge { a: usize, b: usize, count: usize },
    #[error("vertex {vertex} belongs to no triangle (it would have no mass)")]
    UnusedVertex { vertex: usize },
    #[error("vertex {vertex} has a non-finite {field} coordinate")]
    NonFinite { vertex: usize, field: &'static str },
    #[error("grid needs at least 2 x 2 particles and positive spacing, got {nx} x {ny} at ({du}, {dv}) m")]
    BadGrid { nx: usize, ny: usize, du: f64, dv: f64 },
}
