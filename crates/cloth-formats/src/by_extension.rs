//! Any mesh file, its format chosen by its extension.

use crate::error::FormatError;
use crate::gltf::read_gltf;
use crate::mesh::FileMesh;
use crate::obj::ObjFile;
use crate::ply::PlyMesh;
use crate::stl::read_stl;
use std::path::Path;

/// The mesh formats the engine reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshFormat {
    Obj,
    Stl,
    Ply,
    /// `.gltf` or `.glb`.
    Gltf,
}

impl MeshFormat {
    /// The format `path`'s extension names (case-insensitive).
    pub fn of(path: &Path) -> Result<Self, FormatError> {
        let extension = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match extension.as_deref() {
            Some("obj") => Ok(Self::Obj),
            Some("stl") => Ok(Self::Stl),
            Some("ply") => Ok(Self::Ply),
            Some("gltf" | "glb") => Ok(Self::Gltf),
            _ => Err(FormatError::UnknownFormat {
                path: path.to_path_buf(),
                expected: "a .obj, .stl, .ply, .gltf or .glb file",
            }),
        }
    }
}

/// Reads the triangles of an OBJ, STL, PLY, glTF or GLB file, in the file's own frame and
/// numbering. Every coordinate is finite.
pub fn read_mesh(path: &Path) -> Result<FileMesh, FormatError> {
    MeshFormat::of(path)?.read(path)
}

impl MeshFormat {
    /// Reads `path` as this format (see [`read_mesh`]).
    pub fn read(self, path: &Path) -> Result<FileMesh, FormatError> {
        let mesh = match self {
            MeshFormat::Obj => {
                let obj = ObjFile::read(path)?;
                let triangles = obj.triangles().map(|t| t.map(|i| i as u32)).collect();
                FileMesh {
                    positions: obj.positions,
                    triangles,
                }
            }
            MeshFormat::Ply => {
                let ply = PlyMesh::read(path)?;
                let triangles = ply.triangles().collect();
                FileMesh {
                    positions: ply.positions,
                    triangles,
                }
            }
            MeshFormat::Stl => read_stl(path)?,
            MeshFormat::Gltf => read_gltf(path)?,
        };
        // OBJ and PLY refuse these with their line or element; STL and glTF have neither.
        if let Some((index, p)) = mesh
            .positions
            .iter()
            .enumerate()
            .find(|(_, p)| !p.iter().all(|c| c.is_finite()))
        {
            return Err(FormatError::BadElement {
                path: path.to_path_buf(),
                element: "vertex",
                index,
                message: format!("non-finite coordinate in ({}, {}, {})", p.x, p.y, p.z),
            });
        }
        Ok(mesh)
    }
}
