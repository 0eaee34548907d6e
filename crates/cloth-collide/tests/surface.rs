//! Rigid-body surfaces: primitives, file input, validation errors, sharp features.

use cloth_core::math::union_find::union;
use std::collections::HashSet;
use std::f64::consts::PI;
use std::path::{Path, PathBuf};

use cloth_collide::surface::{
    SharpFeature, SurfaceDefect, SurfaceError, SurfaceOptions, TriSurface, WindingTree,
};
use cloth_collide::Body;
use cloth_core::math::Vec3;
use cloth_formats::FormatError;
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
    for (a, b) in edges(s) {
        union(&mut parent, a as usize, b as usize);
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
    assert_unit_cube_of_side_2(&TriSurface::read(&data("cube_quads.obj"), &defaults()).unwrap());
}

#[test]
fn ascii_and_binary_stl_weld_to_a_cube() {
    for name in ["cube_ascii.stl", "cube_binary.stl"] {
        let s = TriSurface::read(&data(name), &defaults()).unwrap();
        assert_unit_cube_of_side_2(&s);
        assert!(s.defects().is_empty(), "joining STL's corners is no defect");
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

/// The defect of kind `kind` (by its name), if the surface has one.
fn defect<'a>(s: &'a TriSurface, kind: &str) -> Option<&'a SurfaceDefect> {
    s.defects().iter().find(|d| format!("{d:?}").starts_with(kind))
}

/// The cube `[-1, 1]^3` with `more` as a second part, as one mesh.
fn cube_and(more: &TriSurface) -> TriSurface {
    let (mut v, mut t) = cube();
    let offset = v.len() as u32;
    v.extend_from_slice(more.vertices());
    t.extend(more.triangles().iter().map(|tri| tri.map(|i| i + offset)));
    TriSurface::new(v, t, &defaults()).unwrap()
}

#[test]
fn zero_area_triangles_are_dropped_unless_nothing_is_left() {
    let (v, mut t) = cube();
    t.push([0, 0, 1]);
    let s = TriSurface::new(v, t, &defaults()).unwrap();
    assert_eq!(s.triangles().len(), 12);
    assert_eq!(
        defect(&s, "Degenerate"),
        Some(&SurfaceDefect::Degenerate {
            triangles: 1,
            first: 12
        })
    );
    assert!(s.is_watertight(), "dropping it leaves the cube closed");
    let flat = vec![
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(1.0, 0.0, 0.0),
        Vector3::new(2.0, 0.0, 0.0),
    ];
    let e = err(flat, vec![[0, 1, 2]]);
    assert!(matches!(e, SurfaceError::Degenerate { triangles: 1, .. }), "{e}");
}

#[test]
fn vertices_the_faces_keep_apart_are_never_joined() {
    // Two closed cubes a nanometre apart: every vertex of one face lies within the weld
    // distance of one of the other's, but no edge is open, so nothing is welded.
    let (v, t) = cube();
    let shifted: Vec<Vec3> = v.iter().map(|p| p + Vector3::new(2.0 + 1e-9, 0.0, 0.0)).collect();
    let other = TriSurface::new(shifted, t, &defaults()).unwrap();
    let s = cube_and(&other);
    assert_eq!(s.vertices().len(), 16);
    assert!(defect(&s, "Welded").is_none() && defect(&s, "NonManifold").is_none());
    assert_closed(&s, 2);
}

#[test]
fn edges_of_more_than_two_triangles_load_with_a_warning() {
    // Two cubes sharing one edge: it has four triangles.
    let (v, t) = cube();
    let mut vertices = v.clone();
    let mut triangles = t.clone();
    let shift = Vector3::new(2.0, 2.0, 0.0);
    let mut map = Vec::new();
    for p in &v {
        let moved = p + shift;
        match vertices.iter().position(|q| (q - moved).norm() < 1e-12) {
            Some(i) => map.push(i as u32),
            None => {
                vertices.push(moved);
                map.push(vertices.len() as u32 - 1)
            }
        }
    }
    triangles.extend(t.iter().map(|tri| tri.map(|i| map[i as usize])));
    let s = TriSurface::new(vertices, triangles, &defaults()).unwrap();
    assert!(
        matches!(
            defect(&s, "NonManifold"),
            Some(SurfaceDefect::NonManifold { edges: 1, .. })
        ),
        "{:?}",
        s.defects()
    );
    assert!(!s.is_watertight());
    assert!(close(s.volume(), 16.0, 1e-12));
    let body = Body::new("two cubes", s);
    for (p, inside) in [
        (Vector3::new(0.0, 0.0, 0.0), true),
        (Vector3::new(2.0, 2.0, 0.5), true),
        (Vector3::new(0.9, 1.1, 0.0), false),
        (Vector3::new(2.0, 0.0, 0.0), false),
    ] {
        assert_eq!(body.signed_distance(0.0, &p) < 0.0, inside, "{p:?}");
    }
}

#[test]
fn a_hole_loads_with_a_warning_and_the_winding_number_tells_inside() {
    let (v, mut t) = cube();
    t.truncate(10);
    let s = TriSurface::new(v, t, &defaults()).unwrap();
    match defect(&s, "Holes") {
        Some(&SurfaceDefect::Holes {
            loops,
            edges,
            perimeter,
            ..
        }) => assert_eq!((loops, edges, perimeter), (1, 4, 8.0)),
        other => panic!("expected holes, got {other:?}"),
    }
    assert!(!s.is_watertight());
    let body = Body::new("open cube", s);
    // The missing face is the last two triangles of the cuboid: find which it was.
    let (v, t) = cube();
    let [a, b, c] = t[10].map(|i| v[i as usize]);
    let out = (b - a).cross(&(c - a)).normalize();
    for (p, inside) in [
        (Vector3::zeros(), true),
        (0.5 * out, true),
        (
            0.9 * out + 0.5 * out.cross(&Vector3::new(0.3, 0.5, 0.7)).normalize(),
            true,
        ),
        (1.1 * out, false),
        (1.5 * out, false),
        (Vector3::new(3.0, 0.0, 0.0), false),
    ] {
        assert_eq!(body.signed_distance(0.0, &p) < 0.0, inside, "{p:?}");
    }
}

#[test]
fn a_flipped_face_is_turned_to_agree_with_its_neighbours() {
    let (v, mut t) = cube();
    t[4].swap(1, 2);
    let s = TriSurface::new(v, t, &defaults()).unwrap();
    assert_eq!(s.defects(), &[SurfaceDefect::Reoriented { triangles: 1 }]);
    assert!(s.is_watertight());
    assert!(close(s.volume(), 8.0, 1e-12));
}

#[test]
fn an_inward_part_is_turned_outward() {
    let (v, mut t) = cube();
    t.iter_mut().for_each(|tri| tri.swap(1, 2));
    let s = TriSurface::new(v, t, &defaults()).unwrap();
    assert_eq!(s.defects(), &[SurfaceDefect::Inward { parts: 1 }]);
    assert!(s.is_watertight());
    assert!(close(s.volume(), 8.0, 1e-12));
}

#[test]
fn one_inward_box_among_outward_ones_is_turned_and_touching_faces_are_buried() {
    let table = TriSurface::table(Vector3::new(0.5, 0.5, 0.02), 0.7, 0.03, 0.05).unwrap();
    let mut t = table.triangles().to_vec();
    // The last 12 triangles are one leg: turn it inside out. The total stays positive.
    t.iter_mut().rev().take(12).for_each(|tri| tri.swap(1, 2));
    let fixed = TriSurface::new(table.vertices().to_vec(), t, &defaults()).unwrap();
    assert!(close(fixed.volume(), table.volume(), 1e-12));
    assert_eq!(
        defect(&fixed, "Inward"),
        Some(&SurfaceDefect::Inward { parts: 1 })
    );
    // Each leg's top face lies on the top's underside: inside the top, out of reach.
    assert_eq!(
        defect(&fixed, "Overlapping"),
        Some(&SurfaceDefect::Overlapping { parts: 4, buried: 8 })
    );
}

#[test]
fn overlapping_parts_leave_their_buried_triangles_out_of_contact() {
    // An "arm" pushed through the cube's side: its inner end cap lies inside the cube.
    let arm = TriSurface::cuboid(Vector3::new(1.25, 0.3, 0.3))
        .unwrap()
        .transformed(&Isometry3::translation(1.75, 0.0, 0.0));
    let s = cube_and(&arm);
    assert_eq!(
        defect(&s, "Overlapping"),
        Some(&SurfaceDefect::Overlapping { parts: 1, buried: 2 })
    );
    let buried: Vec<usize> = (0..s.triangles().len()).filter(|&t| s.is_buried(t)).collect();
    for &t in &buried {
        assert!(s.triangles()[t]
            .iter()
            .all(|&i| (s.vertices()[i as usize].x - 0.5).abs() < 1e-12));
    }
    let body = Body::new("torso and arm", s);
    for (p, inside) in [
        (Vector3::new(0.75, 0.0, 0.0), true),
        (Vector3::new(0.75, 0.0, 0.6), true),
        (Vector3::new(2.0, 0.0, 0.0), true),
        (Vector3::new(2.0, 0.0, 0.5), false),
        (Vector3::new(0.0, 0.0, 1.2), false),
    ] {
        assert_eq!(body.signed_distance(0.0, &p) < 0.0, inside, "{p:?}");
    }
}

#[test]
fn a_double_sided_sheet_encloses_no_volume_and_is_refused() {
    let v = vec![
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(1.0, 0.0, 0.0),
        Vector3::new(0.0, 1.0, 0.0),
    ];
    let e = err(v, vec![[0, 1, 2], [0, 2, 1]]);
    assert!(matches!(e, SurfaceError::ZeroVolume { .. }), "{e}");
}

#[test]
fn fast_winding_numbers_match_the_exact_sum() {
    let sphere = TriSurface::sphere(1.0, 48, 24).unwrap();
    let (v, mut t) = (sphere.vertices().to_vec(), sphere.triangles().to_vec());
    // Open a hole at the top: the winding number then falls off near it only.
    t.retain(|tri| tri.iter().all(|&i| v[i as usize].z < 0.9));
    let tree = WindingTree::new(&v, &t);
    let mut worst: f64 = 0.0;
    for k in 0..400 {
        // Points on a spiral from the centre to three radii out.
        let r = 3.0 * (k as f64 + 0.5) / 400.0;
        let (theta, phi) = (2.4 * k as f64, (1.0 - 2.0 * (k as f64 + 0.5) / 400.0).acos());
        let p = r * Vector3::new(phi.sin() * theta.cos(), phi.sin() * theta.sin(), phi.cos());
        worst = worst.max((tree.winding_number(&p) - tree.exact_winding_number(&p)).abs());
    }
    // First-order clusters at two radii: within 0.03 (see `FAR`), far from the 1/2 that decides.
    assert!(worst < 0.03, "largest difference {worst}");
    assert!(
        (tree.winding_number(&Vector3::zeros()) - 0.95).abs() < 0.01,
        "the cap is 5 % of the sphere"
    );
    assert!(tree.winding_number(&Vector3::new(0.0, 0.0, -3.0)).abs() < 0.01);
}

// ---- the same from files: each error names the file ----

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
    // The reader refuses it with its line (a NaN built in memory is `NonFinite`).
    let (e, message) = file_err("nan.obj", &defaults());
    assert!(
        matches!(e, SurfaceError::Format(FormatError::Parse { line: Some(8), .. })),
        "{message}"
    );
    let (e, _) = file_err("nonmanifold.obj", &defaults());
    assert!(
        matches!(inner(&e), SurfaceError::ZeroVolume { .. }),
        "a fan of three encloses nothing"
    );
}

#[test]
fn imperfect_files_load_with_what_was_found() {
    let read = |name: &str| TriSurface::read(&data(name), &defaults()).unwrap();
    assert!(matches!(
        defect(&read("open_cube.obj"), "Holes"),
        Some(SurfaceDefect::Holes { edges: 4, .. })
    ));
    let s = read("inconsistent_cube.obj");
    assert!(matches!(
        defect(&s, "Reoriented"),
        Some(SurfaceDefect::Reoriented { .. })
    ));
    assert!(close(s.volume(), 8.0, 1e-12));
    let s = read("inward_cube.obj");
    assert_eq!(s.defects(), &[SurfaceDefect::Inward { parts: 1 }]);
    assert!(close(s.volume(), 8.0, 1e-12));
}

#[test]
fn obj_parse_error_names_the_path_and_line() {
    let (e, message) = file_err("bad_vertex.obj", &defaults());
    assert!(
        matches!(e, SurfaceError::Format(FormatError::Parse { line: Some(4), .. })),
        "{message}"
    );
    assert!(message.contains("line 4"), "{message}");
}

#[test]
fn unknown_extension_and_missing_file_name_the_path() {
    let other = data("cube.3ds");
    let e = TriSurface::read(&other, &defaults()).unwrap_err();
    assert!(matches!(
        e,
        SurfaceError::Format(FormatError::UnknownFormat { .. })
    ));
    assert!(e.to_string().contains(&other.display().to_string()));
    let missing = data("no_such_body.stl");
    let e = TriSurface::read(&missing, &defaults()).unwrap_err();
    assert!(matches!(e, SurfaceError::Format(FormatError::Io { .. })));
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

#[test]
fn a_watertight_avatar_with_near_vertices_loads_as_given() {
    // GarmentCode's mean body: 13 vertex pairs lie closer than 2e-7 m (mouth, eyes) without
    // being the same vertex. Welding them broke the surface; it must load untouched.
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/garmentcode/bodies/mean_all.obj");
    let s = TriSurface::read(&path, &defaults()).unwrap();
    assert_eq!((s.vertices().len(), s.triangles().len()), (23_752, 47_500));
    assert!(s.defects().is_empty(), "{:?}", s.defects());
    assert!(s.is_watertight());
    // About 70 litres: an adult of about 70 kg.
    assert!(s.volume() > 0.05 && s.volume() < 0.1, "{}", s.volume());
}

#[test]
fn ply_ascii_quads_and_binary_triangles_read_as_the_cube() {
    for name in ["cube.ply", "cube_binary.ply"] {
        let s = TriSurface::read(&data(name), &defaults()).unwrap();
        assert_eq!((s.vertices().len(), s.triangles().len()), (8, 12), "{name}");
        assert!(s.defects().is_empty(), "{name}: {:?}", s.defects());
        assert!(close(s.volume(), 8.0, 1e-12), "{name}");
    }
}

#[test]
fn gltf_and_glb_read_with_their_node_transforms() {
    // The cube of side 2 sits under a node moved 5 m along y and a child halving it.
    for name in ["cube.gltf", "cube.glb"] {
        let s = TriSurface::read(&data(name), &defaults()).unwrap();
        assert!(s.defects().is_empty(), "{name}: {:?}", s.defects());
        assert!(close(s.volume(), 1.0, 1e-12), "{name}: {}", s.volume());
        let (lo, hi) = s.bounding_box();
        assert!((lo - Vector3::new(-0.5, 4.5, -0.5)).norm() < 1e-6, "{name}: {lo}");
        assert!((hi - Vector3::new(0.5, 5.5, 0.5)).norm() < 1e-6, "{name}: {hi}");
    }
}

#[test]
fn an_avatar_with_holes_and_a_part_through_it_answers_inside_as_the_watertight_one() {
    // GarmentCode's body with the triangles around two points cut away (a mouth and an
    // ear left open) and a bar pushed through its chest: it loads with both defects named,
    // and points a few millimetres off the skin and further away are inside or outside
    // exactly as for the body as given.
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/garmentcode/bodies/mean_all.obj");
    let whole = TriSurface::read(&path, &defaults()).unwrap();
    let (v, t) = (whole.vertices().to_vec(), whole.triangles().to_vec());
    let near = |tri: &[u32; 3], c: Vec3, r: f64| tri.iter().any(|&i| (v[i as usize] - c).norm() < r);
    let (mouth, ear) = (Vector3::new(0.0, 1.55, 0.09), Vector3::new(0.075, 1.6, 0.0));
    let mut cut: Vec<[u32; 3]> = t
        .iter()
        .filter(|tri| !near(tri, mouth, 0.02) && !near(tri, ear, 0.015))
        .copied()
        .collect();
    assert!(
        cut.len() < t.len() - 20,
        "the holes cut {} triangles",
        t.len() - cut.len()
    );
    let bar = TriSurface::cuboid(Vector3::new(0.3, 0.02, 0.02))
        .unwrap()
        .transformed(&Isometry3::translation(0.0, 1.3, 0.0));
    let mut vertices = v.clone();
    let offset = vertices.len() as u32;
    vertices.extend_from_slice(bar.vertices());
    cut.extend(bar.triangles().iter().map(|tri| tri.map(|i| i + offset)));
    let imperfect = TriSurface::new(vertices, cut, &defaults()).unwrap();
    assert!(
        matches!(defect(&imperfect, "Holes"), Some(SurfaceDefect::Holes { loops, .. }) if *loops >= 2),
        "{:?}",
        imperfect.defects()
    );
    assert!(
        defect(&imperfect, "Overlapping").is_some(),
        "{:?}",
        imperfect.defects()
    );
    let (reference, body) = (
        Body::new("given", whole.clone()),
        Body::new("imperfect", imperfect),
    );
    // Points along the vertex normals, 5 mm and 5 cm out and in, away from the cuts and the bar.
    let mut normals = vec![Vector3::zeros(); v.len()];
    for tri in &t {
        let [a, b, c] = tri.map(|i| v[i as usize]);
        let n = (b - a).cross(&(c - a));
        tri.iter().for_each(|&i| normals[i as usize] += n);
    }
    let (mut checked, mut disagree) = (0, Vec::new());
    for (i, p) in v.iter().enumerate().step_by(7) {
        let away = (p - mouth).norm() > 0.06 && (p - ear).norm() > 0.05 && (p.y - 1.3).abs() > 0.08;
        let Some(n) = normals[i].try_normalize(1e-12) else {
            continue;
        };
        if !away {
            continue;
        }
        for d in [0.005, 0.05, -0.005] {
            let q = p + d * n;
            let want = reference.signed_distance(0.0, &q) < 0.0;
            if (body.signed_distance(0.0, &q) < 0.0) != want {
                disagree.push((q, d));
            }
            checked += 1;
        }
    }
    assert!(checked > 5000, "{checked}");
    assert!(
        disagree.is_empty(),
        "{} of {checked} points disagree, e.g. {:?}",
        disagree.len(),
        &disagree[..disagree.len().min(5)]
    );
    // Inside the bar where it stands out of the body, and in the body where the bar crosses it.
    for (p, inside) in [
        (Vector3::new(0.28, 1.3, 0.0), true),
        (Vector3::new(0.0, 1.3, 0.0), true),
        (Vector3::new(0.28, 1.3, 0.1), false),
    ] {
        assert_eq!(body.signed_distance(0.0, &p) < 0.0, inside, "{p:?}");
    }
}
