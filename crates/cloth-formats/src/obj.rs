//! OBJ output of a cloth, to look at in any viewer, written atomically.

use crate::atomic::write_atomically;
use cloth_core::{math::Vec3, ClothMesh};
use std::io::Write;
use std::path::Path;

/// Writes `v` and `f` lines; `{}` prints the shortest decimal that reads back to the same
/// f64.
pub fn write_cloth_obj(path: &Path, positions: &[Vec3], triangles: &[[usize; 3]]) -> std::io::Result<()> {
    write_atomically(path, |out| {
        write_vertices(out, positions)?;
        for t in triangles {
            writeln!(out, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1)?;
        }
        Ok(())
    })
}

/// Writes the cloth with its material coordinates as texture coordinates (`vt`, in
/// metres), one per triangle corner, so the panels of a sewn garment keep their own.
pub fn write_cloth_obj_with_uv(path: &Path, mesh: &ClothMesh, positions: &[Vec3]) -> std::io::Result<()> {
    write_atomically(path, |out| {
        write_vertices(out, positions)?;
        for t in 0..mesh.triangles().len() {
            for uv in mesh.corner_uv(t) {
                writeln!(out, "vt {} {}", uv.x, uv.y)?;
            }
        }
        for (t, tri) in mesh.triangles().iter().enumerate() {
            let vt = 3 * t + 1;
            writeln!(
                out,
                "f {}/{} {}/{} {}/{}",
                tri[0] + 1,
                vt,
                tri[1] + 1,
                vt + 1,
                tri[2] + 1,
                vt + 2
            )?;
        }
        Ok(())
    })
}

fn write_vertices(out: &mut dyn Write, positions: &[Vec3]) -> std::io::Result<()> {
    for p in positions {
        writeln!(out, "v {} {} {}", p.x, p.y, p.z)?;
    }
    Ok(())
}
