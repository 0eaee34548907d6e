//! A triangle mesh as a file gives it.

use cloth_core::math::Vec3;

/// The file's vertices in the file's order and its faces as triangles (a polygon as a fan
/// from its first corner), every index a vertex of the file.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FileMesh {
    pub positions: Vec<Vec3>,
    pub triangles: Vec<[u32; 3]>,
}

/// The triangles of a polygon's fan from its first corner, in order.
pub fn fan<T: Copy>(corners: &[T]) -> impl Iterator<Item = [T; 3]> + '_ {
    (1..corners.len().saturating_sub(1)).map(move |k| [corners[0], corners[k], corners[k + 1]])
}
