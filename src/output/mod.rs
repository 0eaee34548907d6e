//! What a scene run writes into its output folder: the cloth as OBJ (with material
//! coordinates) and PLY (with strain colours), the bodies as OBJ, and the report as JSON
//! and markdown. Every file is written atomically.

mod ply;
mod report;

pub use ply::write_strain_ply;
pub use report::write_report;

use crate::collide::{Bodies, TriSurface};
use crate::obj::write_cloth_obj_with_uv;
use crate::scene_file::{OutputSpec, RunResult};
use std::path::{Path, PathBuf};

/// Writes the outputs `spec` asks for into `dir` (which must exist); returns the files.
pub fn write_outputs(
    dir: &Path,
    result: &RunResult,
    bodies: &Bodies,
    spec: &OutputSpec,
) -> std::io::Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    if spec.obj {
        let path = dir.join("cloth.obj");
        write_cloth_obj_with_uv(&path, &result.mesh, &result.positions)?;
        written.push(path);
    }
    if spec.ply {
        let path = dir.join("cloth.ply");
        write_strain_ply(&path, &result.mesh, &result.positions)?;
        written.push(path);
    }
    if spec.bodies && !bodies.bodies().is_empty() {
        let path = dir.join("bodies.obj");
        let surfaces: Vec<TriSurface> = bodies.bodies().iter().map(|b| b.surface_at(0.0)).collect();
        let merged = TriSurface::merged(&surfaces);
        crate::obj::write_atomically(&path, |out| merged.write_obj_to(out))?;
        written.push(path);
    }
    written.extend(write_report(dir, &result.report)?);
    Ok(written)
}
