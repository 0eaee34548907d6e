//! OBJ output of a cloth, to look at in any viewer. Files are written atomically: to a
//! temporary file beside the target, then renamed over it, so a reader (or a run stopped
//! half-way) never sees half a file.

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

/// Writes through `fill` into `path.tmp`, then renames it to `path`.
pub fn write_atomically(
    path: &Path,
    fill: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(".tmp");
    let tmp = std::path::PathBuf::from(tmp);
    let result = (|| {
        let mut out = std::io::BufWriter::new(std::fs::File::create(&tmp)?);
        fill(&mut out)?;
        out.flush()?;
        out.into_inner().map_err(|e| e.into_error())?.sync_all()
    })();
    match result {
        Ok(()) => std::fs::rename(&tmp, path),
        Err(e) => {
            let _ = std::fs::remove_file(&tmp);
            Err(e)
        }
    }
}
