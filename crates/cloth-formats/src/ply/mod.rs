//! PLY: meshes with colours or strain read, strain meshes written.

mod read;
mod write;

pub use read::PlyMesh;
pub use write::{write_strain_ply, StrainPly};

#[cfg(test)]
mod tests {
    use super::*;
    use cloth_core::math::Vec3;

    #[test]
    fn a_written_strain_ply_reads_back() {
        let path = tempfile::Builder::new()
            .suffix(".ply")
            .tempfile()
            .unwrap()
            .into_temp_path();
        let positions = [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(0.1, 0.0, 0.0),
            Vec3::new(0.1, 0.2, 1.0 / 3.0),
            Vec3::new(0.0, 0.2, -0.25),
        ];
        let ply = StrainPly {
            comments: &["a test".into(), "z up, metres".into()],
            positions: &positions,
            triangles: &[[0, 1, 2], [0, 2, 3]],
            colours: &[[0, 0, 255], [0, 255, 0], [255, 255, 0], [255, 0, 0]],
            strain: &[0.0, 1.5, 3.25, 7.0],
            panels: None,
        };
        write_strain_ply(&path, &ply).unwrap();
        let read = PlyMesh::read(&path).unwrap();
        assert_eq!(read.positions, positions);
        assert_eq!(read.faces, vec![vec![0, 1, 2], vec![0, 2, 3]]);
        assert_eq!(read.colours.as_deref(), Some(ply.colours));
        assert_eq!(read.strain.as_deref(), Some(ply.strain));
        assert_eq!(read.panel, None);
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.starts_with("ply\nformat ascii 1.0\ncomment a test\ncomment z up, metres\n"));
        // A garment's panels: a label per vertex, the names in the header.
        let names = ["front".to_string(), "back".to_string()];
        let labelled = StrainPly {
            panels: Some((&[0, 0, 1, -1], &names)),
            ..ply
        };
        write_strain_ply(&path, &labelled).unwrap();
        let read = PlyMesh::read(&path).unwrap();
        assert_eq!(read.panel, Some(vec![0, 0, 1, -1]));
        assert_eq!(read.strain.as_deref(), Some(ply.strain));
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(
            text.contains("comment panel 0 front\ncomment panel 1 back\n"),
            "{text}"
        );
        let mislabelled = StrainPly {
            panels: Some((&[0], &names)),
            ..ply
        };
        assert!(write_strain_ply(&path, &mislabelled).is_err());
        let short = StrainPly {
            strain: &[0.0],
            ..ply
        };
        assert!(write_strain_ply(&path, &short).is_err());
    }
}
