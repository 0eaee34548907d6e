//! How far apart two drapes of one garment rest: the symmetric Hausdorff distance between
//! the two cloth surfaces (each vertex of one to the nearest point of the other's
//! triangles, both ways), and, with the same numbering, how far each particle lies from
//! its own place in the other (the 99th percentile and median too). Issue 24 asks a
//! speed-up to leave the dress's rest within 5 mm; this is how it was measured.
//!
//!     cargo run --release --example rest_distance -- BEFORE/cloth.obj AFTER/cloth.obj

use cloth::formats::read_mesh;
use cloth::formats::FileMesh;
use cloth::math::Vec3;
use parry3d_f64::math::Vector;
use parry3d_f64::query::PointQuery;
use parry3d_f64::shape::TriMesh;
use std::path::Path;

fn surface(mesh: &FileMesh, path: &str) -> TriMesh {
    let vertices = mesh
        .positions
        .iter()
        .map(|p| Vector::new(p.x, p.y, p.z))
        .collect();
    TriMesh::new(vertices, mesh.triangles.clone()).unwrap_or_else(|e| {
        eprintln!("{path}: not a surface to measure to: {e}");
        std::process::exit(1)
    })
}

/// The farthest any vertex of `from` lies from the surface `to`.
fn one_way(from: &[Vec3], to: &TriMesh) -> f64 {
    from.iter()
        .map(|p| to.distance_to_local_point(Vector::new(p.x, p.y, p.z), true))
        .fold(0.0, f64::max)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [path_a, path_b] = &args[..] else {
        eprintln!("usage: rest_distance BEFORE.obj AFTER.obj");
        std::process::exit(2);
    };
    let read = |path: &str| {
        read_mesh(Path::new(path)).unwrap_or_else(|e| {
            eprintln!("{e}");
            std::process::exit(1)
        })
    };
    let (a, b) = (read(path_a), read(path_b));
    let hausdorff =
        one_way(&a.positions, &surface(&b, path_b)).max(one_way(&b.positions, &surface(&a, path_a)));
    print!("hausdorff {:.2} mm", 1e3 * hausdorff);
    if a.positions.len() == b.positions.len() {
        let mut d: Vec<f64> = a
            .positions
            .iter()
            .zip(&b.positions)
            .map(|(p, q)| (p - q).norm())
            .collect();
        d.sort_by(f64::total_cmp);
        let at = |q: f64| 1e3 * d[((d.len() - 1) as f64 * q).round() as usize];
        print!(
            ", particle to particle: max {:.2} mm, p99 {:.2} mm, median {:.2} mm",
            at(1.0),
            at(0.99),
            at(0.5)
        );
    }
    println!();
}
