//! Reading a surface from a file chosen by its extension.

use std::path::Path;

use super::{SurfaceError, SurfaceOptions, TriSurface};

impl TriSurface {
    /// Reads an OBJ, STL, PLY, glTF or GLB file, chosen by its extension
    /// (case-insensitive), in the file's own frame. Every error names the file.
    pub fn read(path: &Path, options: &SurfaceOptions) -> Result<Self, SurfaceError> {
        let extension = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match extension.as_deref() {
            Some("obj") => Self::from_obj(path, options),
            Some("stl") => Self::from_stl(path, options),
            Some("ply") => Self::from_ply(path, options),
            Some("gltf" | "glb") => Self::from_gltf(path, options),
            _ => Err(SurfaceError::UnknownFormat {
                path: path.to_path_buf(),
            }),
        }
    }
}

pub(super) fn read_bytes(path: &Path) -> Result<Vec<u8>, SurfaceError> {
    std::fs::read(path).map_err(|source| SurfaceError::Io {
        path: path.to_path_buf(),
        source,
    })
}
