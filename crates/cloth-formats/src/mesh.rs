//! A triangle mesh as a file gives it.

use cloth_core::math::Vec3;

/// The file's vertices in the file's order and its faces as triangles (a polygon as a fan
/// from its first corner), every index a vertex of the file.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FileMesh {
    pub positions: Vec<Vec3>,
    pub triangles: Vec<[u32; 3]>,
}
