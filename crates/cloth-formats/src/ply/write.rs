//! Writing PLY: a triangle mesh with a colour and a `strain` value (%) per vertex, as
//! ASCII, written atomically.

use crate::atomic::write_atomically;
use cloth_core::math::Vec3;
use std::io::{Error, ErrorKind};
use std::path::Path;

/// A mesh with per-vertex colours and strain; every slice but `triangles` has one entry
/// per vertex.
#[derive(Debug, Clone, Copy)]
pub struct StrainPly<'a> {
    /// The header's comment line.
    pub comment: &'a str,
    pub positions: &'a [Vec3],
    pub triangles: &'a [[usize; 3]],
    pub colours: &'a [[u8; 3]],
    pub strain: &'a [f64],
}

/// Writes `ply` (positions as the shortest decimals that read back to the same f64). Slices
/// of different lengths are an `InvalidInput` error and nothing is written.
pub fn write_strain_ply(path: &Path, ply: &StrainPly<'_>) -> std::io::Result<()> {
    let n = ply.positions.len();
    if ply.colours.len() != n || ply.strain.len() != n {
        return Err(Error::new(
            ErrorKind::InvalidInput,
            format!(
                "{n} vertices but {} colours and {} strain values",
                ply.colours.len(),
                ply.strain.len()
            ),
        ));
    }
    write_atomically(path, |out| {
        writeln!(out, "ply\nformat ascii 1.0\ncomment {}", ply.comment)?;
        writeln!(out, "element vertex {n}")?;
        writeln!(out, "property double x\nproperty double y\nproperty double z")?;
        writeln!(
            out,
            "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty float strain"
        )?;
        writeln!(out, "element face {}", ply.triangles.len())?;
        writeln!(out, "property list uchar int vertex_indices\nend_header")?;
        for ((p, [r, g, b]), s) in ply.positions.iter().zip(ply.colours).zip(ply.strain) {
            writeln!(out, "{} {} {} {r} {g} {b} {s}", p.x, p.y, p.z)?;
        }
        for t in ply.triangles {
            writeln!(out, "3 {} {} {}", t[0], t[1], t[2])?;
        }
        Ok(())
    })
}
