//! Meshes from files, to draw: OBJ and PLY, with the colours they carry.

use super::error::RenderError;
use super::strain_colours::strain_colour;
use super::{MeshColours, RenderMesh, NEUTRAL_GREY};
use cloth_core::math::Vec3;
use cloth_formats::obj::ObjFile;
use cloth_formats::ply::PlyMesh;
use cloth_formats::MeshFormat;
use std::path::Path;

/// Where a read mesh's colours came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Colouring {
    /// The file has none: the mesh is [`super::NEUTRAL_GREY`]; give it a tint of your own.
    Plain,
    /// Vertex colours from the file.
    FromFile,
    /// A PLY `strain` property (%), coloured on the PLY output's scale: draw the legend.
    Strain,
}

/// A mesh read from a file.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadedMesh {
    pub mesh: RenderMesh,
    pub colouring: Colouring,
}

impl LoadedMesh {
    /// A mesh whose per-vertex `colours` are used unless its colouring is plain.
    fn new(
        positions: Vec<Vec3>,
        triangles: Vec<[usize; 3]>,
        colours: Vec<[u8; 3]>,
        colouring: Colouring,
    ) -> Self {
        let colours = match colouring {
            Colouring::Plain => MeshColours::Uniform(NEUTRAL_GREY),
            _ => MeshColours::PerVertex(colours),
        };
        Self {
            mesh: RenderMesh {
                positions,
                triangles,
                colours,
            },
            colouring,
        }
    }

    /// Its colours mean strain, so a picture of it needs the strain legend.
    pub fn wants_legend(&self) -> bool {
        self.colouring == Colouring::Strain
    }
}

/// Reads an OBJ (all objects merged, polygons as fans, vertex colours if any) or a PLY
/// (ASCII or binary; polygons as fans; a `strain` property preferred to red/green/blue),
/// chosen by the extension, with the file's numbering.
pub fn read_render_mesh(path: &Path) -> Result<LoadedMesh, RenderError> {
    let loaded = match MeshFormat::of(path) {
        Ok(MeshFormat::Obj) => from_obj(ObjFile::read(path)?),
        Ok(MeshFormat::Ply) => from_ply(PlyMesh::read(path)?),
        _ => {
            return Err(RenderError::UnknownFormat {
                path: path.to_path_buf(),
            })
        }
    };
    if loaded.mesh.triangles.is_empty() {
        return Err(RenderError::NoTriangles {
            path: path.to_path_buf(),
        });
    }
    Ok(loaded)
}

/// Vertex colours (0 to 1) where the file gives them, grey for the vertices it does not.
fn from_obj(obj: ObjFile) -> LoadedMesh {
    let triangles = obj.triangles().collect();
    let (colours, colouring) = if obj.colours.iter().any(Option::is_some) {
        let colours = obj
            .colours
            .iter()
            .map(|c| {
                c.map_or(NEUTRAL_GREY, |c| {
                    c.map(|k| (k.clamp(0.0, 1.0) * 255.0).round() as u8)
                })
            })
            .collect();
        (colours, Colouring::FromFile)
    } else {
        (Vec::new(), Colouring::Plain)
    };
    LoadedMesh::new(obj.positions, triangles, colours, colouring)
}

/// Strain on the output's scale if the file has it, else its colours if any.
fn from_ply(ply: PlyMesh) -> LoadedMesh {
    let triangles = ply.triangles().map(|t| t.map(|i| i as usize)).collect();
    let (colours, colouring) = match (ply.strain, ply.colours) {
        (Some(strain), _) => (strain.into_iter().map(strain_colour).collect(), Colouring::Strain),
        (None, Some(colours)) => (colours, Colouring::FromFile),
        (None, None) => (Vec::new(), Colouring::Plain),
    };
    LoadedMesh::new(ply.positions, triangles, colours, colouring)
}

#[cfg(test)]
mod tests {
    use super::super::MeshColours;
    use super::*;
    use std::io::Write;

    /// `contents` in a temporary file whose name ends in `name` (read by its extension).
    fn scratch(name: &str, contents: &[u8]) -> tempfile::TempPath {
        let mut file = tempfile::Builder::new().suffix(name).tempfile().unwrap();
        file.write_all(contents).unwrap();
        file.into_temp_path()
    }

    const HEADER: &str =
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n";

    #[test]
    fn ascii_ply_with_strain_is_coloured_on_the_strain_scale() {
        let text = format!(
            "{HEADER}property uchar red\nproperty uchar green\nproperty uchar blue\nproperty float strain\n\
             element face 1\nproperty list uchar int vertex_indices\nend_header\n\
             0 0 0 9 9 9 0\n1 0 0 9 9 9 2.5\n1 0 1 9 9 9 5\n0 0 1 9 9 9 7\n4 0 1 2 3\n"
        );
        let file = scratch("strain.ply", text.as_bytes());
        let loaded = read_render_mesh(&file).unwrap();
        assert_eq!(loaded.colouring, Colouring::Strain);
        assert!(loaded.wants_legend());
        // A quad is two triangles sharing its first corner.
        assert_eq!(loaded.mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(
            loaded.mesh.positions[2],
            cloth_core::math::Vec3::new(1.0, 0.0, 1.0)
        );
        let full = crate::strain_colours::FULL_SCALE_PERCENT;
        let expected: Vec<[u8; 3]> = [0.0, 2.5, 5.0, 7.0]
            .iter()
            .map(|s| crate::strain_colours::colour(s / full))
            .collect();
        assert_eq!(loaded.mesh.colours, MeshColours::PerVertex(expected));
    }

    #[test]
    fn ply_colours_are_used_when_there_is_no_strain() {
        let text = format!(
            "{HEADER}property uchar red\nproperty uchar green\nproperty uchar blue\n\
             element face 2\nproperty list uchar uint vertex_index\nend_header\n\
             0 0 0 255 0 0\n1 0 0 0 255 0\n1 0 1 0 0 255\n0 0 1 10 20 30\n3 0 1 2\n3 0 2 3\n"
        );
        let file = scratch("colours.ply", text.as_bytes());
        let loaded = read_render_mesh(&file).unwrap();
        assert_eq!(loaded.colouring, Colouring::FromFile);
        assert_eq!(
            loaded.mesh.colours,
            MeshColours::PerVertex(vec![[255, 0, 0], [0, 255, 0], [0, 0, 255], [10, 20, 30]])
        );
        assert_eq!(loaded.mesh.triangles.len(), 2);
    }

    #[test]
    fn binary_ply_reads_like_ascii() {
        let mut bytes = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n\
property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
            .to_vec();
        for v in [[0.0f32, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 0.0, 3.0]] {
            for c in v {
                bytes.extend(c.to_le_bytes());
            }
        }
        bytes.push(3);
        for i in [0i32, 1, 2] {
            bytes.extend(i.to_le_bytes());
        }
        let file = scratch("binary.ply", &bytes);
        let loaded = read_render_mesh(&file).unwrap();
        assert_eq!(loaded.colouring, Colouring::Plain);
        assert_eq!(
            loaded.mesh.positions[1],
            cloth_core::math::Vec3::new(2.0, 0.0, 0.0)
        );
        assert_eq!(
            loaded.mesh.positions[2],
            cloth_core::math::Vec3::new(0.0, 0.0, 3.0)
        );
        assert_eq!(loaded.mesh.triangles, vec![[0, 1, 2]]);
    }

    #[test]
    fn malformed_ply_errors_name_the_file_and_the_place() {
        let cases = [
            ("bad-number.ply", format!("{HEADER}element face 0\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 x\n"), "line"),
            ("bad-index.ply", format!("{HEADER}element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 0 1\n0 0 1\n3 0 1 9\n"), "face 0"),
            ("no-faces.ply", format!("{HEADER}end_header\n0 0 0\n1 0 0\n1 0 1\n0 0 1\n"), "no triangles"),
            ("truncated.ply", format!("{HEADER}element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n"), ""),
            ("no-z.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n".to_string(), "z"),
        ];
        for (name, text, place) in cases {
            let file = scratch(name, text.as_bytes());
            let message = match read_render_mesh(&file) {
                Ok(_) => panic!("{name} was accepted"),
                Err(e) => e.to_string(),
            };
            assert!(message.contains(&file.display().to_string()), "{message}");
            assert!(message.contains(place), "{name}: {message}");
        }
    }

    #[test]
    fn missing_and_unknown_files_are_named() {
        let missing = std::env::temp_dir().join("cloth-render-surely-not-here.ply");
        let e = read_render_mesh(&missing).unwrap_err();
        assert!(
            matches!(e, RenderError::Format(cloth_formats::FormatError::Io { .. }))
                && e.to_string().contains("surely-not-here"),
            "{e}"
        );
        let e = read_render_mesh(Path::new("mesh.stl")).unwrap_err();
        assert!(matches!(e, RenderError::UnknownFormat { .. }), "{e}");
    }

    #[test]
    fn obj_models_are_merged_and_polygons_triangulated() {
        let text = "o a\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nf 1 2 3 4\no b\nv 0 1 0\nv 1 1 0\nv 0 1 1\nf 5 6 7\nl 1 5\n";
        let file = scratch("two.obj", text.as_bytes());
        let loaded = read_render_mesh(&file).unwrap();
        assert_eq!(loaded.colouring, Colouring::Plain);
        assert_eq!(loaded.mesh.positions.len(), 7);
        assert_eq!(loaded.mesh.triangles.len(), 3);
        // The second object's triangle refers to its own corners, after the first's.
        let t = loaded.mesh.triangles[2];
        assert!(t.iter().all(|&i| loaded.mesh.positions[i].y == 1.0), "{t:?}");
        let bad = scratch("bad.obj", b"v 0 0 0\nv 1 0 0\nf 1 2 3\n");
        let e = read_render_mesh(&bad).unwrap_err().to_string();
        assert!(e.contains("bad.obj"), "{e}");
    }

    #[test]
    fn obj_vertex_colours_are_kept() {
        let text = "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 0 1 0 0 1\nf 1 2 3\n";
        let file = scratch("coloured.obj", text.as_bytes());
        let loaded = read_render_mesh(&file).unwrap();
        assert_eq!(loaded.colouring, Colouring::FromFile);
        let MeshColours::PerVertex(c) = &loaded.mesh.colours else {
            panic!("no vertex colours")
        };
        for (p, c) in loaded.mesh.positions.iter().zip(c) {
            let expected = if p.x == 1.0 {
                [0, 255, 0]
            } else if p.z == 1.0 {
                [0, 0, 255]
            } else {
                [255, 0, 0]
            };
            assert_eq!(*c, expected);
        }
    }
}
