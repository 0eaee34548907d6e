//! Writing PLY: a triangle mesh with a colour and a `strain` value (%) per vertex, and a
//! garment's `panel` per vertex, as ASCII, written atomically.

use crate::atomic::write_atomically;
use cloth_core::math::Vec3;
use std::io::{Error, ErrorKind};
use std::path::Path;

/// A mesh with per-vertex colours and strain; every slice but `triangles` has one entry
/// per vertex.
#[derive(Debug, Clone, Copy)]
pub struct StrainPly<'a> {
    /// The header's comment lines (what the file holds, its frame and units).
    pub comments: &'a [String],
    pub positions: &'a [Vec3],
    pub triangles: &'a [[usize; 3]],
    pub colours: &'a [[u8; 3]],
    pub strain: &'a [f64],
    /// A garment's panels: each vertex's panel (-1 for none) as an `int panel` property,
    /// and the panels' names, in `comment panel K NAME` lines.
    pub panels: Option<(&'a [i32], &'a [String])>,
}

/// Writes `ply` (positions as the shortest decimals that read back to the same f64). Slices
/// of different lengths are an `InvalidInput` error and nothing is written.
pub fn write_strain_ply(path: &Path, ply: &StrainPly<'_>) -> std::io::Result<()> {
    let n = ply.positions.len();
    let labels = ply.panels.map_or(n, |(labels, _)| labels.len());
    if ply.colours.len() != n || ply.strain.len() != n || labels != n {
        return Err(Error::new(
            ErrorKind::InvalidInput,
            format!(
                "{n} vertices but {} colours, {} strain values and {labels} panel labels",
                ply.colours.len(),
                ply.strain.len()
            ),
        ));
    }
    write_atomically(path, |out| {
        writeln!(out, "ply\nformat ascii 1.0")?;
        for c in ply.comments {
            writeln!(out, "comment {}", c.replace(char::is_control, " "))?;
        }
        if let Some((_, names)) = ply.panels {
            for (k, name) in names.iter().enumerate() {
                // A line break in a name would end the comment inside the header.
                let name = name.replace(char::is_control, " ");
                writeln!(out, "comment panel {k} {name}")?;
            }
        }
        writeln!(out, "element vertex {n}")?;
        writeln!(out, "property double x\nproperty double y\nproperty double z")?;
        writeln!(
            out,
            "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty float strain"
        )?;
        if ply.panels.is_some() {
            writeln!(out, "property int panel")?;
        }
        writeln!(out, "element face {}", ply.triangles.len())?;
        writeln!(out, "property list uchar int vertex_indices\nend_header")?;
        for (i, ((p, [r, g, b]), s)) in ply.positions.iter().zip(ply.colours).zip(ply.strain).enumerate() {
            write!(out, "{} {} {} {r} {g} {b} {s}", p.x, p.y, p.z)?;
            match ply.panels {
                Some((labels, _)) => writeln!(out, " {}", labels[i])?,
                None => writeln!(out)?,
            }
        }
        for t in ply.triangles {
            writeln!(out, "3 {} {} {}", t[0], t[1], t[2])?;
        }
        Ok(())
    })
}
