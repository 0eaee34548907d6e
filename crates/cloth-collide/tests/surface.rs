//! Rigid-body surfaces: primitives, file input, validation errors, sharp features.

use std::collections::HashSet;
use std::f64::consts::PI;
use std::path::{Path, PathBuf};

use cloth_collide::surface::{SharpFeature, SurfaceError, SurfaceOptions, TriSurface};
use cloth_core::Vec3;
use nalgebra::{Isometry3, Vector3};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

fn scratch(name: &str) -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR")).join(name)
}

fn defaults() -> SurfaceOptions {
    SurfaceOptions::default()
}

fn edges(s: &TriSurface) -> HashSet<(u32, u32)> {
    s.triangles()
        .iter()
        .flat_map(|t| (0..3).map(move |k| (t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3]))))
        .collect()
}

fn euler(s: &TriSurface) -> i64 {
    s.vertices().len() as i64 - edges(s).len() as i64 + s.triangles().len() as i64
}

/// Number of vertex-connected components.
fn components(s: &TriSurface) -> usize {
    let mut parent: Vec<usize> = (0..s.vertices().len()).collect();
    fn root(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            i = p[i];
        }
        i
    }
    for (a, b) in edges(s) {
        let (ra, rb) = (root(&mut parent, a as usize), root(&mut parent, b as usize));
        parent[ra] = rb;
    }
    (0..parent.len()).filter(|&i| parent[i] == i).count()
}

/// Volume of a stack of frusta of regular `segments`-gon pyramids: exactly the volume of a
/// surface of revolution built from planar trapezoids, given its (radius, z) profile.
fn polygonal_revolution_volume(profile: &[(f64, f64)], segments: usize) -> f64 {
    let area = |r: f64| 0.5 * segments as f64 * r * r * (2.0 * PI / segments as f64).sin();
    profile
        .windows(2)
        .map(|w| {
            let (a1, a2) = (area(w[0].0), area(w[1].0));
            (w[0].1 - w[1].1) / 3.0 * (a1 + a2 + (a1 * a2).sqrt())
        })
        .sum()
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs()
}

fn assert_closed(s: &TriSurface, components_expected: usize) {
    assert_eq!(components(s), components_expected);
    assert_eq!(euler(s), 2 * components_expected as i64, "Euler characteristic");
    assert_eq!(
        2 * edges(s).len(),
        3 * s.triangles().len(),
        "every edge has two triangles"
    );
    assert!(s.volume() > 0.0, "outward");
}

#[test]
fn uv_sphere_is_closed_outward_with_the_right_volume() {
    let (r, segments, rings) = (1.3, 64, 32);
    let s = TriSurface::sphere(r, segments, rings).unwrap();
    assert_closed(&s, 1);
    assert_eq!(s.vertices().len(), 2 + segments * (rings - 1));
    assert_eq!(s.triangles().len(), 2 * segments * (rings - 1));
    let profile: Vec<(f64, f64)> = (0..=rings)
        .map(|j| {
            let t = PI * j as f64 / rings as f64;
            (r * t.sin(), r * t.cos())
        })
        .collect();
    let exact = polygonal_revolution_volume(&profile, segments);
    assert!(
        close(s.volume(), exact, 1e-9),
        "{} vs polyhedral {exact}",
        s.volume()
    );
    let ball = 4.0 / 3.0 * PI * r.powi(3);
    assert!(close(s.volume(), ball, 0.01), "{} vs {ball}", s.volume());
    assert!(s.volume() < ball, "inscribed polyhedron");
    assert!(close(s.area(), 4.0 * PI * r * r, 0.01));
}

#[test]
fn icosphere_is_closed_outward_with_the_right_volume_and_counts() {
    let s = TriSurface::icosphere(0.7, 4).unwrap();
    assert_closed(&s, 1);
    assert_eq!(s.triangles().len(), 20 * 4usize.pow(4));
    assert!(s.vertices().iter().all(|p| (p.norm() - 0.7).abs() < 1e-12));
    assert!(close(s.volume(), 4.0 / 3.0 * PI * 0.7f64.powi(3), 0.01));
    assert_eq!(TriSurface::icosphere(1.0, 5).unwrap().triangles().len(), 20480);
    let fine = TriSurface::icosphere(2.0, 6).unwrap();
    assert_eq!(fine.triangles().len(), 81920);
    assert_closed(&fine, 1);
}

#[test]
fn cuboid_is_closed_outward_with_exact_volume() {
    let s = TriSurface::cuboid(Vector3::new(0.5, 1.0, 1.5)).unwrap();
    assert_closed(&s, 1);
    assert_eq!((s.vertices().len(), s.triangles().len()), (8, 12));
    assert!(close(s.volume(), 6.0, 1e-14));
    assert!(close(s.area(), 2.0 * (2.0 + 3.0 + 6.0), 1e-14));
    assert_eq!(
        s.bounding_box(),
        (Vector3::new(-0.5, -1.0, -1.5), Vector3::new(0.5, 1.0, 1.5))
    );
}

#[test]
fn cylinder_is_closed_outward_with_the_right_volume() {
    let (r, h, segments) = (0.4, 0.9, 64);
    let s = TriSurface::cylinder(r, h, segments).unwrap();
    assert_closed(&s, 1);
    let prism = polygonal_revolution_volume(&[(0.0, h), (r, h), (r, -h), (0.0, -h)], segments);
    assert!(close(s.volume(), prism, 1e-12));
    assert!(close(s.volume(), PI * r * r * 2.0 * h, 0.01));
}

#[test]
fn capsule_is_closed_outward_with_the_right_volume() {
    let (r, h, segments, rings) = (0.3, 0.5, 64, 16);
    let s = TriSurface::capsule(r, h, segments, rings).unwrap();
    assert_closed(&s, 1);
    let analytic = PI * r * r * 2.0 * h + 4.0 / 3.0 * PI * r.powi(3);
    assert!(close(s.volume(), analytic, 0.01), "{} vs {analytic}", s.volume());
    let (lo, hi) = s.bounding_box();
    assert!((lo.z + h + r).abs() < 1e-15 && (hi.z - h - r).abs() < 1e-15);
}

#[test]
fn table_is_five_closed_boxes_standing_on_the_floor() {
    let (top, height, w, inset) = (Vector3::new(0.8, 0.5, 0.02), 0.75, 0.03, 0.05);
    let s = TriSurface::table(top, height, w, inset).unwrap();
    assert_closed(&s, 5);
    assert_eq!(euler(&s), 10);
    let leg_length = height - 2.0 * top.z;
    let expected = 8.0 * top.x * top.y * top.z + 4.0 * (2.0 * w) * (2.0 * w) * leg_length;
    assert!(close(s.volume(), expected, 1e-12));
    let (lo, hi) = s.bounding_box();
    assert!((lo - Vector3::new(-0.8, -0.5, 0.0)).norm() < 1e-15);
    assert!((hi - Vector3::new(0.8, 0.5, 0.75)).norm() < 1e-15);
    // Legs reach the underside exactly and sit `inset` in from the edges.
    let leg_top = s
        .vertices()
        .iter()
        .filter(|p| (p.z - leg_length).abs() < 1e-15)
        .count();
    assert_eq!(
        leg_top,
        4 * 4 + 4,
        "4 corners of each leg top and of the table's underside"
    );
    let max_leg_x = s
        .vertices()
        .iter()
        .filter(|p| p.z < 0.5 * leg_length)
        .map(|p| p.x)
        .fold(f64::MIN, f64::max);
    assert!((max_leg_x - (top.x - inset)).abs() < 1e-15);
}

#[test]
fn primitives_reject_bad_parameters_by_name() {
    let name = |e: SurfaceError| match e {
        SurfaceError::Parameter { name, .. } => name,
        other => panic!("expected a parameter error, got {other}"),
    };
    assert_eq!(name(TriSurface::sphere(0.0, 8, 4).unwrap_err()), "radius");
    assert_eq!(name(TriSurface::sphere(1.0, 2, 4).unwrap_err()), "segments");
    assert_eq!(name(TriSurface::sphere(1.0, 8, 1).unwrap_err()), "rings");
    assert_eq!(name(TriSurface::icosphere(f64::NAN, 1).unwrap_err()), "radius");
    assert_eq!(name(TriSurface::icosphere(1.0, 9).unwrap_err()), "subdivisions");
    assert_eq!(
        name(TriSurface::cuboid(Vector3::new(1.0, -1.0, 1.0)).unwrap_err()),
        "half_extents.y"
    );
    assert_eq!(
        name(TriSurface::cylinder(1.0, 0.0, 8).unwrap_err()),
        "half_height"
    );
    assert_eq!(name(TriSurface::capsule(1.0, 1.0, 8, 0).unwrap_err()), "rings");
    let top = Vector3::new(0.5, 0.5, 0.02);
    assert_eq!(
        name(TriSurface::table(top, 0.04, 0.03, 0.0).unwrap_err()),
        "height"
    );
    assert_eq!(
        name(TriSurface::table(top, 0.7, 0.2, 0.1).unwrap_err()),
        "leg_inset"
    );
    assert_eq!(
        name(TriSurface::table(top, 0.7, 0.03, -0.1).unwrap_err()),
        "leg_inset"
    );
}

fn is_mirror_symmetric(points: &[Vec3], mirror: impl Fn(&Vec3) -> Vec3) -> bool {
    points.iter().all(|p| {
        let q = mirror(p);
        points.iter().any(|r| (r - q).norm() < 1e-12)
    })
}

#[test]
fn uv_sphere_has_the_mirror_symmetries_of_the_sphere() {
    let s = TriSurface::sphere(1.0, 64, 32).unwrap();
    let centroids: Vec<Vec3> = s
        .triangles()
        .iter()
        .map(|t| t.iter().map(|&i| s.vertices()[i as usize]).sum::<Vec3>() / 3.0)
        .collect();
    type Mirror = (&'static str, fn(&Vec3) -> Vec3);
    let mirrors: [Mirror; 4] = [
        ("x -> -x", |p| Vector3::new(-p.x, p.y, p.z)),
        ("y -> -y", |p| Vector3::new(p.x, -p.y, p.z)),
        ("x <-> y", |p| Vector3::new(p.y, p.x, p.z)),
        ("z -> -z", |p| Vector3::new(p.x, p.y, -p.z)),
    ];
    for (what, mirror) in mirrors {
        assert!(
            is_mirror_symmetric(s.vertices(), mirror),
            "vertices not symmetric under {what}"
        );
        // Triangle centroids too: the diagonals that split the quads are symmetric as well.
        assert!(
            is_mirror_symmetric(&centroids, mirror),
            "triangles not symmetric under {what}"
        );
    }
}

fn assert_unit_cube_of_side_2(s: &TriSurface) {
    assert_eq!((s.vertices().len(), s.triangles().len()), (8, 12));
    assert!(close(s.volume(), 8.0, 1e-12));
    assert_eq!(s.bounding_box(), (Vector3::repeat(-1.0), Vector3::repeat(1.0)));
}

#[test]
fn obj_with_quads_in_two_objects_reads_as_one_welded_cube() {
    assert_unit_cube_of_side_2(&TriSurface::from_obj(&data("cube_quads.obj"), &defaults()).unwrap());
    assert_unit_cube_of_side_2(&TriSurface::read(&data("cube_quads.obj"), &defaults()).unwrap());
}

#[test]
fn ascii_and_binary_stl_weld_to_a_cube() {
    for name in ["cube_ascii.stl", "cube_binary.stl"] {
        let s = TriSurface::from_stl(&data(name), &defaults()).unwrap();
        assert_unit_cube_of_side_2(&s);
        assert_unit_cube_of_side_2(&TriSurface::read(&data(name), &defaults()).unwrap());
    }
}

#[test]
fn extension_is_case_insensitive() {
    let upper = scratch("CUBE.STL");
    std::fs::copy(data("cube_binary.stl"), &upper).unwrap();
    assert_unit_cube_of_side_2(&TriSurface::read(&upper, &defaults()).unwrap());
}

#[test]
fn scale_option_scales_file_coordinates() {
    let centimetres = SurfaceOptions {
        scale: 0.01,
        ..defaults()
    };
    let s = TriSurface::read(&data("cube_quads.obj"), &centimetres).unwrap();
    assert!(close(s.volume(), 8e-6, 1e-9));
    assert_eq!(s.bounding_box(), (Vector3::repeat(-0.01), Vector3::repeat(0.01)));
    let bad = SurfaceOptions {
        scale: -1.0,
        ..defaults()
    };
    let e = TriSurface::read(&data("cube_quads.obj"), &bad).unwrap_err();
    assert!(
        matches!(e, SurfaceError::InFile { ref source, .. }
        if matches!(**source, SurfaceError::Parameter { name: "scale", .. })),
        "{e}"
    );
}

#[test]
fn written_obj_reads_back() {
    let s = TriSurface::icosphere(0.25, 2)
        .unwrap()
        .transformed(&Isometry3::translation(1.0, 2.0, 3.0));
    let path = scratch("icosphere.obj");
    s.write_obj(&path).unwrap();
    let back = TriSurface::read(&path, &defaults()).unwrap();
    assert_eq!(back.vertices().len(), s.vertices().len());
    // tobj renumbers vertices in order of first use but keeps the triangles in order; it is
    // built for f32 coordinates, so the round trip is exact to f32 only.
    for (t, u) in back.triangles().iter().zip(s.triangles()) {
        for k in 0..3 {
            let (p, q) = (back.vertices()[t[k] as usize], s.vertices()[u[k] as usize]);
            assert!((p - q).norm() < 1e-6 * q.norm(), "{p} vs {q}");
        }
    }
    assert!(close(back.volume(), s.volume(), 1e-5));
}

// ---- construction from arrays: welding and each validation error ----

fn cube() -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let s = TriSurface::cuboid(Vector3::repeat(1.0)).unwrap();
    (s.vertices().to_vec(), s.triangles().to_vec())
}

#[test]
fn welding_keeps_first_occurrences_in_order_and_drops_unused_vertices() {
    let (v, t) = cube();
    // Every corner repeated per triangle, nudged by 1e-9, plus a vertex nobody uses.
    let mut vertices = vec![Vector3::new(9.0, 9.0, 9.0)];
    let mut triangles = Vec::new();
    for tri in &t {
        let first = vertices.len() as u32;
        vertices.extend(tri.iter().map(|&i| v[i as usize] * (1.0 + 1e-9)));
        triangles.push([first, first + 1, first + 2]);
    }
    let s = TriSurface::new(vertices.clone(), triangles, &defaults()).unwrap();
    assert_eq!((s.vertices().len(), s.triangles().len()), (8, 12));
    // The kept vertices are the first occurrences, in input order.
    let mut firsts: Vec<Vec3> = Vec::new();
    for p in &vertices[1..] {
        if !firsts.iter().any(|q| (q - p).norm() < 1e-6) {
            firsts.push(*p);
        }
    }
    assert_eq!(s.vertices(), &firsts[..]);
    assert!(close(s.volume(), 8.0, 1e-8));
}

fn err(v: Vec<Vec3>, t: Vec<[u32; 3]>) -> SurfaceError {
    TriSurface::new(v, t, &defaults()).unwrap_err()
}

#[test]
fn empty_mesh_is_refused() {
    assert!(matches!(
        err(vec![Vec3::zeros()], vec![]),
        SurfaceError::Empty { .. }
    ));
    assert!(matches!(err(vec![], vec![[0, 1, 2]]), SurfaceError::Empty { .. }));
}

#[test]
fn non_finite_coordinate_is_named_before_bad_indices() {
    let (mut v, mut t) = cube();
    v[5].y = f64::NAN;
    t[0][0] = 100;
    assert!(matches!(err(v, t), SurfaceError::NonFinite { vertex: 5, value } if value.is_nan()));
}

#[test]
fn index_out_of_range_names_the_triangle() {
    let (v, mut t) = cube();
    t[7][2] = 8;
    assert!(matches!(
        err(v, t),
        SurfaceError::IndexOutOfRange {
            triangle: 7,
            index: 8,
            count: 8
        }
    ));
}

#[test]
fn triangle_collapsed_by_welding_or_flat_is_degenerate() {
    let (mut v, t) = cube();
    // Corners 0 and 1 share edge x: bring them within the weld distance.
    v[1] = v[0] + Vector3::new(1e-12, 0.0, 0.0);
    assert!(matches!(err(v, t.clone()), SurfaceError::Degenerate { .. }));
    let flat = vec![
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(1.0, 0.0, 0.0),
        Vector3::new(2.0, 0.0, 0.0),
    ];
    let e = err(flat, vec![[0, 1, 2]]);
    assert!(matches!(e, SurfaceError::Degenerate { triangle: 0, .. }), "{e}");
}

#[test]
fn three_triangles_on_one_edge_are_non_manifold() {
    let v = vec![
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(1.0, 0.0, 0.0),
        Vector3::new(0.5, 1.0, 0.0),
        Vector3::new(0.5, -1.0, 0.0),
        Vector3::new(0.5, 0.0, 1.0),
    ];
    let e = err(v, vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]]);
    assert!(
        matches!(
            e,
            SurfaceError::NonManifold {
                a: 0,
                b: 1,
                count: 3,
                ..
            }
        ),
        "{e}"
    );
    assert!(
        e.to_string().contains("[1.0, 0.0, 0.0]"),
        "names the positions: {e}"
    );
}

#[test]
fn cube_missing_a_face_is_open() {
    let (v, mut t) = cube();
    t.truncate(10);
    assert!(matches!(
        err(v, t),
        SurfaceError::Open {
            boundary_edges: 4,
            ..
        }
    ));
}

#[test]
fn one_flipped_face_is_inconsistent() {
    let (v, mut t) = cube();
    t[4].swap(1, 2);
    assert!(matches!(err(v, t), SurfaceError::Inconsistent { .. }));
}

#[test]
fn all_flipped_is_inward_unless_asked_to_flip() {
    let (v, mut t) = cube();
    t.iter_mut().for_each(|tri| tri.swap(1, 2));
    let e = err(v.clone(), t.clone());
    assert!(matches!(e, SurfaceError::Inward { volume, .. } if close(volume, -8.0, 1e-12)));
    assert!(e.to_string().contains("flip_inward"));
    let flip = SurfaceOptions {
        flip_inward: true,
        ..defaults()
    };
    let s = TriSurface::new(v, t, &flip).unwrap();
    assert!(close(s.volume(), 8.0, 1e-12));
}

#[test]
fn one_inward_box_among_outward_ones_is_caught() {
    let table = TriSurface::table(Vector3::new(0.5, 0.5, 0.02), 0.7, 0.03, 0.0).unwrap();
    let mut t = table.triangles().to_vec();
    // The last 12 triangles are one leg: turn it inside out. The total stays positive.
    t.iter_mut().rev().take(12).for_each(|tri| tri.swap(1, 2));
    let e = TriSurface::new(table.vertices().to_vec(), t.clone(), &defaults()).unwrap_err();
    assert!(matches!(e, SurfaceError::Inward { triangle: 48, .. }), "{e}");
    let flip = SurfaceOptions {
        flip_inward: true,
        ..defaults()
    };
    let fixed = TriSurface::new(table.vertices().to_vec(), t, &flip).unwrap();
    assert!(close(fixed.volume(), table.volume(), 1e-12));
}

#[test]
fn double_sided_sheet_encloses_no_volume() {
    let v = vec![
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(1.0, 0.0, 0.0),
        Vector3::new(0.0, 1.0, 0.0),
    ];
    let e = err(v, vec![[0, 1, 2], [0, 2, 1]]);
    assert!(matches!(e, SurfaceError::ZeroVolume { .. }), "{e}");
}

// ---- the same errors from files: each must name the file ----

fn file_err(name: &str, options: &SurfaceOptions) -> (SurfaceError, String) {
    let path = data(name);
    let e = TriSurface::read(&path, options).unwrap_err();
    let message = e.to_string();
    assert!(message.contains(&path.display().to_string()), "{message}");
    (e, message)
}

fn inner(e: &SurfaceError) -> &SurfaceError {
    match e {
        SurfaceError::InFile { source, .. } => source,
        other => panic!("expected an error wrapped with its file, got {other}"),
    }
}

#[test]
fn malformed_files_give_their_error_with_the_path() {
    for name in ["empty.obj", "empty.stl"] {
        assert!(matches!(
            inner(&file_err(name, &defaults()).0),
            SurfaceError::Empty { .. }
        ));
    }
    let (e, _) = file_err("nan.obj", &defaults());
    assert!(matches!(inner(&e), SurfaceError::NonFinite { value, .. } if value.is_nan()));
    let (e, _) = file_err("open_cube.obj", &defaults());
    assert!(matches!(
        inner(&e),
        SurfaceError::Open {
            boundary_edges: 4,
            ..
        }
    ));
    let (e, _) = file_err("nonmanifold.obj", &defaults());
    assert!(matches!(inner(&e), SurfaceError::NonManifold { count: 3, .. }));
    let (e, _) = file_err("inconsistent_cube.obj", &defaults());
    assert!(matches!(inner(&e), SurfaceError::Inconsistent { .. }));
    let (e, message) = file_err("inward_cube.obj", &defaults());
    assert!(matches!(inner(&e), SurfaceError::Inward { .. }));
    assert!(message.contains("flip_inward"));
    let flip = SurfaceOptions {
        flip_inward: true,
        ..defaults()
    };
    let s = TriSurface::read(&data("inward_cube.obj"), &flip).unwrap();
    assert!(close(s.volume(), 8.0, 1e-12));
}

#[test]
fn obj_parse_error_names_the_path_and_line() {
    let (e, message) = file_err("bad_vertex.obj", &defaults());
    assert!(
        matches!(e, SurfaceError::Parse { line: Some(4), .. }),
        "{message}"
    );
    assert!(message.contains("line 4"), "{message}");
}

#[test]
fn unknown_extension_and_missing_file_name_the_path() {
    let ply = data("cube.ply");
    let e = TriSurface::read(&ply, &defaults()).unwrap_err();
    assert!(matches!(e, SurfaceError::UnknownFormat { .. }));
    assert!(e.to_string().contains(&ply.display().to_string()));
    let missing = data("no_such_body.stl");
    let e = TriSurface::read(&missing, &defaults()).unwrap_err();
    assert!(matches!(e, SurfaceError::Io { .. }));
    assert!(e.to_string().contains(&missing.display().to_string()));
}

// ---- rigid motion, union, sharp features ----

#[test]
fn rigid_motion_and_union_keep_volume() {
    let sphere = TriSurface::sphere(0.5, 16, 8).unwrap();
    let pose = Isometry3::new(Vector3::new(3.0, -1.0, 2.0), Vector3::new(0.3, -0.7, 1.1));
    let moved = sphere.transformed(&pose);
    assert!(close(moved.volume(), sphere.volume(), 1e-12));
    assert!(close(moved.area(), sphere.area(), 1e-12));
    let both = TriSurface::merged(&[sphere.clone(), moved]);
    assert!(close(both.volume(), 2.0 * sphere.volume(), 1e-12));
    assert_closed(&both, 2);
}

#[test]
fn cuboid_has_twelve_sharp_edges_and_eight_corners() {
    let s = TriSurface::cuboid(Vector3::new(1.0, 2.0, 3.0)).unwrap();
    let features = s.sharp_features(30f64.to_radians());
    let (corners, sharp_edges): (Vec<&SharpFeature>, Vec<&SharpFeature>) =
        features.iter().partition(|f| f.a == f.b);
    assert_eq!((sharp_edges.len(), corners.len()), (12, 8));
    for f in &sharp_edges {
        let (p, q) = (s.vertices()[f.a as usize], s.vertices()[f.b as usize]);
        // A box edge runs along one axis; its normal points out along the other two.
        let expected = Vector3::from_fn(|k, _| if p[k] != q[k] { 0.0 } else { p[k].signum() }).normalize();
        assert!(
            (f.normal - expected).norm() < 1e-12,
            "edge {:?}: {} vs {expected}",
            (f.a, f.b),
            f.normal
        );
    }
    for f in &corners {
        let expected = s.vertices()[f.a as usize].map(f64::signum) / 3f64.sqrt();
        assert!(
            (f.normal - expected).norm() < 1e-12,
            "corner {}: {}",
            f.a,
            f.normal
        );
    }
}

#[test]
fn smooth_sphere_has_no_sharp_features() {
    let s = TriSurface::sphere(1.0, 64, 32).unwrap();
    assert!(s.sharp_features(30f64.to_radians()).is_empty());
}

#[test]
fn cylinder_rims_are_sharp_edges_without_corners() {
    let s = TriSurface::cylinder(0.5, 1.0, 64).unwrap();
    let features = s.sharp_features(30f64.to_radians());
    assert_eq!(features.len(), 128, "two rims of 64 edges, no corners");
    assert!(features.iter().all(|f| f.a != f.b && f.normal.z.abs() > 0.7));
}

#[test]
fn a_crease_that_fades_out_ends_in_a_corner() {
    // Pyramid of height 1 over a polygon tangent to the unit circle: every side leans 45
    // degrees, so the fold between neighbouring sides follows the turn of the base. One turn
    // of 120 degrees, twelve of 20: only one side edge is sharp at 30 degrees, and the apex,
    // where it ends, is a corner with one sharp edge.
    let mut normal_angle = 0.0f64;
    let mut directions = vec![];
    for turn in std::iter::once(120.0).chain(std::iter::repeat_n(20.0, 12)) {
        directions.push(Vector3::new(normal_angle.cos(), normal_angle.sin(), 0.0));
        normal_angle += f64::to_radians(turn);
    }
    let n = directions.len();
    let mut vertices = vec![Vector3::new(0.0, 0.0, 1.0), Vector3::zeros()];
    for k in 0..n {
        let (u, w) = (directions[k], directions[(k + 1) % n]);
        vertices.push((u + w) / (1.0 + u.dot(&w)));
    }
    let rim = |k: usize| (2 + k % n) as u32;
    let mut triangles = vec![];
    for k in 0..n {
        triangles.push([0, rim(k), rim(k + 1)]);
        triangles.push([1, rim(k + 1), rim(k)]);
    }
    let s = TriSurface::new(vertices, triangles, &defaults()).unwrap();
    let features = s.sharp_features(30f64.to_radians());
    let sharp_edges: Vec<_> = features.iter().filter(|f| f.a != f.b).collect();
    let corners: Vec<u32> = features.iter().filter(|f| f.a == f.b).map(|f| f.a).collect();
    // The 120-degree turn is between the first two edge directions: rim vertex 0 (index 2).
    assert_eq!(sharp_edges.len(), n + 1, "the base rim and one side edge");
    assert!(sharp_edges.iter().any(|f| (f.a, f.b) == (0, 2)));
    assert_eq!(
        corners,
        vec![0, 2],
        "apex (one sharp edge) and the sharp rim vertex (three)"
    );
    let apex = features.iter().find(|f| f.a == 0 && f.b == 0).unwrap();
    assert!((apex.normal.norm() - 1.0).abs() < 1e-12 && apex.normal.z > 0.5);
}
