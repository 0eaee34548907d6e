//! A cloth read from an OBJ file: its texture coordinates are the material coordinates;
//! a file without them must be flat and is its own rest shape.

use cloth_core::{ClothMesh, Vec3};
use nalgebra::Vector2;
use std::path::Path;

/// How far from its best plane a mesh without texture coordinates may be, relative to its
/// size.
const FLAT_TOLERANCE: f64 = 1e-6;

/// Reads `path` (positions times `scale` then moved by `offset`, texture coordinates times
/// `uv_scale`, both to metres). Errors say what is wrong in words; the caller adds the file.
pub fn read_cloth_obj(path: &Path, scale: f64, uv_scale: f64, offset: Vec3) -> Result<ClothMesh, String> {
    let options = tobj::LoadOptions {
        triangulate: true,
        ..Default::default()
    };
    let (models, _) = tobj::load_obj(path, &options).map_err(|e| e.to_string())?;
    let (mut positions, mut triangles, mut corner_uv) = (Vec::new(), Vec::new(), Vec::new());
    let mut has_uv = None;
    for model in &models {
        let m = &model.mesh;
        let base = positions.len();
        positions.extend(
            m.positions
                .chunks_exact(3)
                .map(|p| scale * Vec3::new(p[0], p[1], p[2]) + offset),
        );
        let with_uv = !m.texcoords.is_empty();
        if *has_uv.get_or_insert(with_uv) != with_uv {
            return Err("some objects have texture coordinates (vt) and some do not".into());
        }
        for (k, face) in m.indices.chunks_exact(3).enumerate() {
            triangles.push([face[0], face[1], face[2]].map(|i| base + i as usize));
            if with_uv {
                // tobj gives texture indices per corner when they differ from the positions'.
                let uv_index = |c: usize| {
                    let i = if m.texcoord_indices.is_empty() {
                        face[c]
                    } else {
                        m.texcoord_indices[3 * k + c]
                    } as usize;
                    m.texcoords
                        .get(2 * i..2 * i + 2)
                        .map(|t| uv_scale * Vector2::new(t[0], t[1]))
                        .ok_or_else(|| {
                            format!(
                                "face {k} of '{}' names texture coordinate {}, which does not exist",
                                model.name,
                                i + 1
                            )
                        })
                };
                corner_uv.push([uv_index(0)?, uv_index(1)?, uv_index(2)?]);
            }
        }
    }
    if triangles.is_empty() {
        return Err("no faces".into());
    }
    if has_uv == Some(true) {
        return ClothMesh::with_corner_uv(positions, triangles, corner_uv).map_err(|e| e.to_string());
    }
    let uv = flat_coordinates(&positions)?;
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

    fn write(name: &str, text: &str) -> std::path::PathBuf {
        let path = std::env::temp_dir().join(format!("cloth_file_{}_{name}", std::process::id()));
        std::fs::write(&path, text).unwrap();
        path
    }

    #[test]
    fn texture_coordinates_are_the_rest_shape() {
        // A unit square in space, its material square 0.5 m.
        let path = write(
            "uv.obj",
            "v 0 0 1\nv 1 0 1\nv 1 1 1.2\nv 0 1 1.2\nvt 0 0\nvt 0.5 0\nvt 0.5 0.5\nvt 0 0.5\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n",
        );
        let mesh = read_cloth_obj(&path, 1.0, 1.0, Vec3::zeros()).unwrap();
        assert_eq!(mesh.vertex_count(), 4);
        assert!((mesh.total_rest_area() - 0.25).abs() < 1e-12);
        let scaled = read_cloth_obj(&path, 1.0, 2.0, Vec3::zeros()).unwrap();
        assert!((scaled.total_rest_area() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_flat_mesh_without_uv_is_its_own_rest_shape_and_a_bent_one_is_refused() {
        let flat = write(
            "flat.obj",
            "v 0 0 2\nv 0.3 0 2\nv 0.3 0.2 2\nv 0 0.2 2\nf 1 2 3\nf 1 3 4\n",
        );
        let mesh = read_cloth_obj(&flat, 1.0, 1.0, Vec3::zeros()).unwrap();
        assert!((mesh.total_rest_area() - 0.06).abs() < 1e-12);
        // The warp (u) runs along x.
        let uv = mesh.uv();
        assert!(((uv[1] - uv[0]).x.abs() - 0.3).abs() < 1e-12 && (uv[1] - uv[0]).y.abs() < 1e-12);
        let bent = write(
            "bent.obj",
            "v 0 0 0\nv 1 0 0\nv 1 1 0.3\nv 0 1 0\nf 1 2 3\nf 1 3 4\n",
        );
        let e = read_cloth_obj(&bent, 1.0, 1.0, Vec3::zeros()).unwrap_err();
        assert!(e.contains("not flat") && e.contains("vt"), "{e}");
        let bad = write("bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n");
        assert!(read_cloth_obj(&bad, 1.0, 1.0, Vec3::zeros()).is_err());
    }
}
