//! Surfaces from mesh files, and back to OBJ.

use std::io::{BufWriter, Write};
use std::path::Path;

use cloth_formats::obj::{write_objects, ObjObject};
use cloth_formats::MeshFormat;

use super::{SurfaceDefect, SurfaceError, SurfaceOptions, TriSurface};

impl TriSurface {
    /// Reads an OBJ, STL, PLY, glTF or GLB file, chosen by its extension
    /// (case-insensitive), in the file's own frame (glTF's is y-up: the caller turns it, as
    /// a body's `up_axis` does) and numbering: OBJ polygons become fans, every object and
    /// group one surface, points and lines are skipped. Every error names the file.
    ///
    /// STL repeats every corner, so the welding of [`SurfaceOptions::weld_distance`] is
    /// what joins its facets, and is not reported as a defect.
    pub fn read(path: &Path, options: &SurfaceOptions) -> Result<Self, SurfaceError> {
        let format = MeshFormat::of(path)?;
        let mesh = format.read(path)?;
        let mut surface =
            TriSurface::new(mesh.positions, mesh.triangles, options).map_err(|e| e.in_file(path))?;
        if format == MeshFormat::Stl {
            surface
                .defects
                .retain(|d| !matches!(d, SurfaceDefect::Welded { .. }));
        }
        Ok(surface)
    }

    /// Writes the surface as plain OBJ ('v' and 'f' lines), e.g. to look at a body.
    pub fn write_obj(&self, path: &Path) -> std::io::Result<()> {
        let mut out = BufWriter::new(std::fs::File::create(path)?);
        self.write_obj_to(&mut out)?;
        out.flush()
    }

    /// The same, to any writer.
    pub fn write_obj_to(&self, out: &mut dyn Write) -> std::io::Result<()> {
        let object = ObjObject {
            name: None,
            positions: &self.vertices,
            triangles: &self.triangles,
        };
        write_objects(out, &[], &[object])
    }
}
