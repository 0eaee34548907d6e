//! The form as one Wavefront OBJ file, one object per surface.

use std::io::{BufWriter, Write};
use std::path::Path;

use super::Mannequin;

pub(super) fn write(mannequin: &Mannequin, path: &Path) -> std::io::Result<()> {
    let mut out = BufWriter::new(std::fs::File::create(path)?);
    let m = mannequin.measurements();
    writeln!(
        out,
        "# Parametric dress form (cloth-garment mannequin), metres, z up, front -y"
    )?;
    writeln!(
        out,
        "# height {} bust {} waist {} hip {} shoulder_width {} neck_girth {}",
        m.height, m.bust, m.waist, m.hip, m.shoulder_width, m.neck_girth
    )?;
    if let Some(a) = &m.arms {
        writeln!(
            out,
            "# arms: length {} upper_arm_girth {} wrist_girth {} angle_degrees {}",
            a.length, a.upper_arm_girth, a.wrist_girth, a.angle_degrees
        )?;
    }
    // OBJ indices are global and 1-based across objects.
    let mut offset = 1;
    for (name, surface) in mannequin.surfaces() {
        writeln!(
            out,
            "o {name}\n# {} vertices, {} triangles",
            surface.vertices().len(),
            surface.triangles().len()
        )?;
        // The shortest decimals that read back to the same f64, so a file read back is the
        // generated surface exactly. Rounding to micrometres would not do: a flat cap's
        // vertices all round the same way in z, which moves its whole area and changes the
        // volume by some 1e-7 relative.
        for p in surface.vertices() {
            writeln!(out, "v {} {} {}", p.x, p.y, p.z)?;
        }
        for [a, b, c] in surface.triangles() {
            writeln!(out, "f {} {} {}", a + offset, b + offset, c + offset)?;
        }
        offset += surface.vertices().len() as u32;
    }
    out.flush()
}
