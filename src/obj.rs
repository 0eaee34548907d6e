//! Plain OBJ output of a cloth: its positions and triangles, to look at in any viewer.

use cloth_core::Vec3;
use std::io::Write;
use std::path::Path;

/// Writes `v` and `f` lines; `{}` prints the shortest decimal that reads back to the same
/// f64.
pub fn write_cloth_obj(path: &Path, positions: &[Vec3], triangles: &[[usize; 3]]) -> std::io::Result<()> {
    let mut out = std::io::BufWriter::new(std::fs::File::create(path)?);
    for p in positions {
        writeln!(out, "v {} {} {}", p.x, p.y, p.z)?;
    }
    for t in triangles {
        writeln!(out, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1)?;
    }
    out.flush()
}
