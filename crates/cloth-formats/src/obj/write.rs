//! Writing OBJ: a cloth (with its material coordinates when asked) written atomically, and
//! named triangle surfaces, one object each, to any writer.

use crate::atomic::write_atomically;
use crate::panels::PanelLabels;
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

/// A cloth to write as OBJ with its material coordinates.
#[derive(Debug, Clone, Copy)]
pub struct ClothObj<'a> {
    /// Header lines, each written as a `#` comment (the frame, the units).
    pub comments: &'a [String],
    pub mesh: &'a ClothMesh,
    pub positions: &'a [Vec3],
    /// A garment's panels, written as OBJ groups (`g name` before each run of a panel's
    /// triangles), which importers can split the mesh by (Blender's "Split by Group").
    pub panels: Option<&'a PanelLabels>,
}

/// Writes the cloth with its material coordinates as texture coordinates (`vt`, in
/// metres), one per triangle corner, so the panels of a sewn garment keep their own. The
/// faces are in the mesh's order, so face `k` is triangle `k`.
pub fn write_cloth_obj_with_uv(path: &Path, obj: &ClothObj<'_>) -> std::io::Result<()> {
    let mesh = obj.mesh;
    write_atomically(path, |out| {
        for c in obj.comments {
            writeln!(out, "# {}", c.replace(char::is_control, " "))?;
        }
        write_vertices(out, obj.positions)?;
        for t in 0..mesh.triangles().len() {
            for uv in mesh.corner_uv(t) {
                writeln!(out, "vt {} {}", uv.x, uv.y)?;
            }
        }
        let mut group = None;
        for (t, tri) in mesh.triangles().iter().enumerate() {
            if let Some(panels) = obj.panels {
                let p = panels.of_triangle().get(t).copied();
                if p != group {
                    group = p;
                    let name = p.map_or("unlabelled", |p| panels.names()[p].as_str());
                    writeln!(out, "g {}", group_name(name))?;
                }
            }
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

/// An OBJ group's name: one word (`g a b` would be two groups), so whitespace becomes `_`.
fn group_name(name: &str) -> String {
    let word: String = name
        .chars()
        .map(|c| if c.is_whitespace() { '_' } else { c })
        .collect();
    if word.is_empty() {
        "unnamed".into()
    } else {
        word
    }
}

fn write_vertices(out: &mut dyn Write, positions: &[Vec3]) -> std::io::Result<()> {
    for p in positions {
        writeln!(out, "v {} {} {}", p.x, p.y, p.z)?;
    }
    Ok(())
}

/// One object of an OBJ file: a triangle surface, named or not.
#[derive(Debug, Clone, Copy)]
pub struct ObjObject<'a> {
    pub name: Option<&'a str>,
    pub positions: &'a [Vec3],
    pub triangles: &'a [[u32; 3]],
}

/// Writes `comments` (one `#` line each), then each object (`o name` when named, a comment
/// with its counts, its `v` and `f` lines; OBJ numbers vertices across objects, from 1).
/// Positions are the shortest decimals that read back to the same f64, so a file read back
/// is the surface exactly.
pub fn write_objects(
    out: &mut dyn Write,
    comments: &[String],
    objects: &[ObjObject<'_>],
) -> std::io::Result<()> {
    for c in comments {
        writeln!(out, "# {c}")?;
    }
    let mut offset = 1;
    for object in objects {
        if let Some(name) = object.name {
            writeln!(out, "o {name}")?;
        }
        writeln!(
            out,
            "# {} vertices, {} triangles",
            object.positions.len(),
            object.triangles.len()
        )?;
        write_vertices(out, object.positions)?;
        for [a, b, c] in object.triangles {
            writeln!(out, "f {} {} {}", a + offset, b + offset, c + offset)?;
        }
        offset += object.positions.len() as u32;
    }
    Ok(())
}
