//! A cloth read from an OBJ file: its texture coordinates are the material coordinates;
//! a file without them must be flat and is its own rest shape.

use cloth_core::{math::Vec3, ClothMesh};
use cloth_formats::mesh::fan;
use cloth_formats::obj::ObjFile;
use cloth_formats::FormatError;
use nalgebra::{Isometry3, Point3, Vector2};
use std::path::Path;

/// How far from its best plane a mesh without texture coordinates may be, relative to its
/// size.
const FLAT_TOLERANCE: f64 = 1e-6;

/// Reads `path` (positions times `scale` then placed by `placement`, texture coordinates
/// times `uv_scale`, both to metres). Particles are the file's vertices in the file's order, so
/// pins and arrays can name them by their numbers. Polygons are fanned into triangles.
/// Errors say what is wrong and on which line; the caller adds the file.
pub fn read_cloth_obj(
    path: &Path,
    scale: f64,
    uv_scale: f64,
    placement: &Isometry3<f64>,
) -> Result<ClothMesh, String> {
    let obj = ObjFile::read(path).map_err(|e| match e {
        FormatError::Io { source, .. } => source.to_string(),
        FormatError::Parse {
            line: Some(line),
            message,
            ..
        } => format!("line {line}: {message}"),
        other => other.to_string(),
    })?;
    // The rest shape of a flat file is its own, wherever it is placed.
    let unplaced: Vec<Vec3> = obj.positions.iter().map(|p| scale * p).collect();
    let positions: Vec<Vec3> = unplaced
        .iter()
        .map(|p| (placement * Point3::from(*p)).coords)
        .collect();
    if obj.faces.is_empty() {
        return Err("no faces".into());
    }
    // Every particle must be part of the cloth.
    let mut used = vec![false; obj.positions.len()];
    obj.faces
        .iter()
        .flat_map(|f| &f.vertices)
        .for_each(|&i| used[i] = true);
    if let Some(k) = used.iter().position(|u| !u) {
        return Err(format!(
            "line {}: vertex {} is used by no face (a cloth is made of its faces' vertices)",
            obj.position_lines[k],
            k + 1
        ));
    }
    let with_uv = obj.faces[0].texcoords.is_some();
    let (mut triangles, mut corner_uv) = (Vec::new(), Vec::new());
    for face in &obj.faces {
        if face.texcoords.is_some() != with_uv {
            return Err(format!(
                "line {}: some faces have texture coordinates (vt) and some do not",
                face.line
            ));
        }
        triangles.extend(fan(&face.vertices));
        if let Some(t) = &face.texcoords {
            corner_uv.extend(fan(t).map(|c| c.map(|i| uv_scale * Vector2::from(obj.texcoords[i]))));
        }
    }
    if with_uv {
        return ClothMesh::with_corner_uv(positions, triangles, corner_uv).map_err(|e| e.to_string());
    }
    if let Some(line) = obj.first_texcoord_line {
        return Err(format!(
            "line {line}: the file has texture coordinates (vt) but its faces do not use them: \
             write faces as f v/vt"
        ));
    }
    let uv = flat_coordinates(&unplaced)?;
    ClothMesh::new(positions, uv, triangles).map_err(|e| e.to_string())
}

/// Coordinates in the plane of a flat point set, u along the plane's x direction (or y's
/// when the plane is across x).
fn flat_coordinates(positions: &[Vec3]) -> Result<Vec<Vector2<f64>>, String> {
    let n = positions.len() as f64;
    let centre = positions.iter().sum::<Vec3>() / n;
    let mut covariance = nalgebra::Matrix3::zeros();
    for p in positions {
        let d = p - centre;
        covariance += d * d.transpose();
    }
    let eigen = covariance.symmetric_eigen();
    let k = eigen.eigenvalues.imin();
    let normal: Vec3 = eigen.eigenvectors.column(k).into();
    let size = positions.iter().map(|p| (p - centre).norm()).fold(0.0, f64::max);
    let off = positions
        .iter()
        .map(|p| (p - centre).dot(&normal).abs())
        .fold(0.0, f64::max);
    if off > FLAT_TOLERANCE * size.max(f64::MIN_POSITIVE) {
        return Err(format!(
            "the mesh has no texture coordinates (vt) and is not flat (a vertex is {off:.3e} m off its plane): \
             give its material coordinates as vt"
        ));
    }
    let along = if normal.x.abs() < 0.9 {
        Vec3::x()
    } else {
        Vec3::y()
    };
    let u = (along - normal * along.dot(&normal)).normalize();
    let v = normal.cross(&u);
    Ok(positions
        .iter()
        .map(|p| Vector2::new((p - centre).dot(&u), (p - centre).dot(&v)))
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    /// `text` in a temporary file whose name ends in `name`, removed when dropped.
    fn write(name: &str, text: &str) -> tempfile::TempPath {
        let mut file = tempfile::Builder::new().suffix(name).tempfile().unwrap();
        file.write_all(text.as_bytes()).unwrap();
        file.into_temp_path()
    }

    #[test]
    fn texture_coordinates_are_the_rest_shape() {
        // A unit square in space, its material square 0.5 m.
        let path = write(
            "uv.obj",
            "v 0 0 1\nv 1 0 1\nv 1 1 1.2\nv 0 1 1.2\nvt 0 0\nvt 0.5 0\nvt 0.5 0.5\nvt 0 0.5\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n",
        );
        let mesh = read_cloth_obj(&path, 1.0, 1.0, &Isometry3::identity()).unwrap();
        assert_eq!(mesh.vertex_count(), 4);
        assert!((mesh.total_rest_area() - 0.25).abs() < 1e-12);
        let scaled = read_cloth_obj(&path, 1.0, 2.0, &Isometry3::identity()).unwrap();
        assert!((scaled.total_rest_area() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_flat_mesh_without_uv_is_its_own_rest_shape_and_a_bent_one_is_refused() {
        let flat = write(
            "flat.obj",
            "v 0 0 2\nv 0.3 0 2\nv 0.3 0.2 2\nv 0 0.2 2\nf 1 2 3\nf 1 3 4\n",
        );
        let mesh = read_cloth_obj(&flat, 1.0, 1.0, &Isometry3::identity()).unwrap();
        assert!((mesh.total_rest_area() - 0.06).abs() < 1e-12);
        // The warp (u) runs along x.
        let uv = mesh.uv();
        assert!(((uv[1] - uv[0]).x.abs() - 0.3).abs() < 1e-12 && (uv[1] - uv[0]).y.abs() < 1e-12);
        let bent = write(
            "bent.obj",
            "v 0 0 0\nv 1 0 0\nv 1 1 0.3\nv 0 1 0\nf 1 2 3\nf 1 3 4\n",
        );
        let e = read_cloth_obj(&bent, 1.0, 1.0, &Isometry3::identity()).unwrap_err();
        assert!(e.contains("not flat") && e.contains("vt"), "{e}");
        let bad = write("bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n");
        let e = read_cloth_obj(&bad, 1.0, 1.0, &Isometry3::identity()).unwrap_err();
        assert!(e.contains("line 3") && e.contains("vertex 7"), "{e}");
    }

    #[test]
    fn particles_keep_the_files_vertex_numbers() {
        // Faces use the vertices out of order, one as a quad and with negative indices;
        // vertex 5 (0.05, -0.1, 1) is used last.
        let path = write(
            "order.obj",
            "o sheet\nv 0 0.1 1\nv 0.1 0.1 1\nv 0.1 0 1\nv 0 0 1\nv 0.05 -0.1 1\nvn 0 0 1\n\
             g a\nf 4//1 3//1 2//1 1//1\nf -3 -2 -1\n",
        );
        let mesh = read_cloth_obj(&path, 1.0, 1.0, &Isometry3::identity()).unwrap();
        assert_eq!(mesh.vertex_count(), 5);
        assert_eq!(mesh.positions()[4], Vec3::new(0.05, -0.1, 1.0));
        assert_eq!(mesh.positions()[0], Vec3::new(0.0, 0.1, 1.0));
        assert_eq!(mesh.triangles(), &[[3, 2, 1], [3, 1, 0], [2, 3, 4]]);
    }

    #[test]
    fn loose_vertices_and_unused_texture_coordinates_are_named() {
        let loose = write("loose.obj", "v 0 0 0\nv 1 0 0\nv 9 9 9\nv 0 1 0\nf 1 2 4\n");
        let e = read_cloth_obj(&loose, 1.0, 1.0, &Isometry3::identity()).unwrap_err();
        assert!(e.contains("line 3") && e.contains("vertex 3"), "{e}");
        let unused = write("unused_vt.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1 2 3\n");
        let e = read_cloth_obj(&unused, 1.0, 1.0, &Isometry3::identity()).unwrap_err();
        assert!(e.contains("line 4") && e.contains("f v/vt"), "{e}");
    }
}
