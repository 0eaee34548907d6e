//! What a scene run writes into its output folder: the cloth as OBJ (with material
//! coordinates) and PLY (with strain colours), the bodies as OBJ, both in one glTF binary,
//! a picture, a garment's segmentation, the steps as CSV, the report's plots, and the
//! report as JSON and markdown. OBJ and PLY
//! are in the frame the scene asks (`[output] up_axis`) and say so in their headers; a
//! garment's panels are OBJ groups and a PLY property. Every file is written atomically.

mod glb;
mod ply;
mod history;
mod plots;
mod report;

pub use glb::{write_glb, GlbCloth};
pub use history::write_history_csv;
pub use plots::{convergence, strain_histogram};
pub use ply::write_strain_ply;
pub use report::write_report;

use crate::scene_file::{OutputSpec, RunResult};
use cloth_collide::{Bodies, TriSurface};
use cloth_formats::obj::{write_cloth_obj_with_uv, write_objects, ClothObj, ObjObject};
use std::path::{Path, PathBuf};

/// Writes the outputs `spec` asks for into `dir` (which must exist); returns the files.
pub fn write_outputs(
    dir: &Path,
    result: &RunResult,
    bodies: &Bodies,
    spec: &OutputSpec,
) -> std::io::Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    let up = spec.up_axis;
    let panels = result.panels.as_ref();
    // The strain is measured in any frame alike; only the files' coordinates turn.
    let positions = up.turned_from_z_up(&result.positions);
    if spec.obj {
        let path = dir.join("cloth.obj");
        let comments = up.file_header("the cloth");
        let obj = ClothObj {
            comments: &comments,
            mesh: &result.mesh,
            positions: &positions,
            panels,
        };
        write_cloth_obj_with_uv(&path, &obj)?;
        written.push(path);
    }
    if spec.ply {
        let path = dir.join("cloth.ply");
        write_strain_ply(&path, &result.mesh, &positions, up, panels)?;
        written.push(path);
    }
    if let Some(panels) = panels.filter(|_| spec.segmentation) {
        let path = dir.join("segmentation.txt");
        panels.write_segmentation(&path, result.mesh.triangles(), result.mesh.vertex_count())?;
        written.push(path);
    }
    // The bodies where the run left them.
    let time = result.report.simulated_time;
    let surfaces: Vec<TriSurface> = bodies.bodies().iter().map(|b| b.surface_at(time)).collect();
    if spec.bodies && !surfaces.is_empty() {
        let path = dir.join("bodies.obj");
        let merged = TriSurface::merged(&surfaces);
        let object = ObjObject {
            name: None,
            positions: &up.turned_from_z_up(merged.vertices()),
            triangles: merged.triangles(),
        };
        let comments = up.file_header("the bodies");
        cloth_formats::atomic::write_atomically(&path, |out| write_objects(out, &comments, &[object]))?;
        written.push(path);
    }
    if spec.glb {
        let path = dir.join("scene.glb");
        let named: Vec<(String, TriSurface)> = bodies
            .bodies()
            .iter()
            .zip(&surfaces)
            .map(|(b, s)| (b.name().to_string(), s.clone()))
            .collect();
        let cloth = GlbCloth {
            mesh: &result.mesh,
            positions: &result.positions,
            panels,
        };
        write_glb(&path, &cloth, &named)?;
        written.push(path);
    }
    if spec.png {
        let path = dir.join("render.png");
        let [width, height] = spec.image_size;
        cloth_render::render_run(&result.mesh, &result.positions, &surfaces, width, height)
            .write_png(&path)?;
        written.push(path);
    }
    if spec.history {
        let path = dir.join("history.csv");
        write_history_csv(&path, &result.history)?;
        written.push(path);
    }
    let mut plots = Vec::new();
    if spec.plots {
        let path = dir.join("strain.png");
        strain_histogram(&result.mesh, &result.positions, 1200, 700).write_png(&path)?;
        written.push(path);
        plots.push((
            "strain.png",
            "The final warp and weft strain: the share of the cloth's area at each strain.",
        ));
        let path = dir.join("convergence.png");
        convergence(&result.history, 1200, 900).write_png(&path)?;
        written.push(path);
        plots.push((
            "convergence.png",
            "Step by step through the stages: the kinetic energy, and the linear solve's relative residual.",
        ));
    }
    written.extend(write_report(dir, &result.report, &plots)?);
    Ok(written)
}
