//! The form as one Wavefront OBJ file, one object per surface.

use std::io::{BufWriter, Write};
use std::path::Path;

use cloth_formats::obj::{write_objects, ObjObject};

use super::Mannequin;

pub(super) fn write(mannequin: &Mannequin, path: &Path) -> std::io::Result<()> {
    let m = mannequin.measurements();
    let mut comments = vec![
        "Parametric dress form (cloth-garment mannequin), metres, z up, front -y".to_string(),
        format!(
            "height {} bust {} waist {} hip {} shoulder_width {} neck_girth {}",
            m.height, m.bust, m.waist, m.hip, m.shoulder_width, m.neck_girth
        ),
    ];
    if let Some(a) = &m.arms {
        comments.push(format!(
            "arms: length {} upper_arm_girth {} wrist_girth {} angle_degrees {}",
            a.length, a.upper_arm_girth, a.wrist_girth, a.angle_degrees
        ));
    }
    // Written exactly (see `write_objects`): rounding to micrometres would not do, as a
    // flat cap's vertices all round the same way in z, which moves its whole area and
    // changes the volume by some 1e-7 relative.
    let surfaces = mannequin.surfaces();
    let objects: Vec<ObjObject<'_>> = surfaces
        .iter()
        .map(|(name, surface)| ObjObject {
            name: Some(name),
            positions: surface.vertices(),
            triangles: surface.triangles(),
        })
        .collect();
    let mut out = BufWriter::new(std::fs::File::create(path)?);
    write_objects(&mut out, &comments, &objects)?;
    out.flush()
}
