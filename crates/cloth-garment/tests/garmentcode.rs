//! Import of GarmentCode specifications: the two files in assets/patterns/garmentcode,
//! checked against hand-computed points, and small inline files for each rule and error.
//!
//! GarmentCode's world is y-up in cm with the body facing +z; ours is z-up in metres with
//! the body facing -y: a point (x, y, z) there is (x, -z, y) / 100 here.

use cloth_core::math::Vec3;
use cloth_garment::garmentcode::{from_json_str, from_path, ImportOptions};
use cloth_garment::{Curve, GarmentBuilder, GarmentError, Panel, Pattern, PatternError, SeamOrientation};
use nalgebra::Vector2;
use std::path::{Path, PathBuf};

type P2 = Vector2<f64>;

fn asset(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/patterns/garmentcode")
        .join(name)
}

fn load(name: &str) -> Pattern {
    from_path(&asset(name), &ImportOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

fn skirt() -> Pattern {
    load("straight_skirt_specification.json")
}

fn dress() -> Pattern {
    load("shift_dress_specification.json")
}

fn panel<'a>(pattern: &'a Pattern, name: &str) -> &'a Panel {
    let k = pattern
        .panel_index(name)
        .unwrap_or_else(|| panic!("no panel '{name}'"));
    &pattern.panels[k]
}

fn near3(got: Vec3, want: Vec3) {
    assert!((got - want).norm() < 1e-9, "got {got:?}, want {want:?}");
}

fn near2(got: P2, want: P2) {
    assert!((got - want).norm() < 1e-9, "got {got:?}, want {want:?}");
}

fn import(text: &str) -> Result<Pattern, PatternError> {
    from_json_str(text, "inline.json", &ImportOptions::default())
}

/// A pattern of squares 20 cm wide, 20 cm tall: "front" at z = +15 drawn counter-clockwise,
/// "back" at z = -15 drawn clockwise (GarmentCode's way), with the front's edges, the
/// stitches and the properties given.
fn squares(front_edges: &str, stitches: &str, properties: &str) -> String {
    format!(
        r#"{{
  "pattern": {{
    "panels": {{
      "front": {{
        "translation": [0, 100, 15], "rotation": [0, 0, 0],
        "vertices": [[-10, 0], [10, 0], [10, 20], [-10, 20]],
        "edges": {front_edges}
      }},
      "back": {{
        "translation": [0, 100, -15], "rotation": [0, 0, 0],
        "vertices": [[-10, 0], [10, 0], [10, 20], [-10, 20]],
        "edges": [{{"endpoints": [0, 3]}}, {{"endpoints": [3, 2]}}, {{"endpoints": [2, 1]}}, {{"endpoints": [1, 0]}}]
      }}
    }},
    "stitches": {stitches}
  }},
  "properties": {properties}
}}"#
    )
}

const SQUARE: &str =
    r#"[{"endpoints": [0, 1]}, {"endpoints": [1, 2]}, {"endpoints": [2, 3]}, {"endpoints": [3, 0]}]"#;
const SIDES: &str = r#"[[{"panel": "front", "edge": 1}, {"panel": "back", "edge": 2}],
                        [{"panel": "front", "edge": 3}, {"panel": "back", "edge": 0}]]"#;
const CM: &str = r#"{"units_in_meter": 100, "curvature_coords": "relative", "normalized_edge_loops": true}"#;

/// One counter-clockwise 10 cm square with the given placement and properties.
fn one_square(vertices: &str, translation: &str, rotation: &str, properties: &str) -> String {
    format!(
        r#"{{"pattern": {{"panels": {{"p": {{
            "translation": {translation}, "rotation": {rotation}, "vertices": {vertices},
            "edges": [{{"endpoints": [0, 1]}}, {{"endpoints": [1, 2]}}, {{"endpoints": [2, 3]}}, {{"endpoints": [3, 0]}}]
        }}}}}}, "properties": {properties}}}"#
    )
}

#[test]
fn files_import_with_their_panels_edges_and_seams() {
    let skirt = skirt();
    assert_eq!(skirt.name, "straight_skirt");
    // panel_order wins over the file's order (front, back).
    let names: Vec<&str> = skirt.panels.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["back", "front"]);
    assert!(skirt.panels.iter().all(|p| p.outline.len() == 6));
    assert_eq!(skirt.seams.len(), 4);

    let dress = dress();
    assert_eq!(dress.name, "shift_dress");
    // No panel_order: the file's order, not the sorted one.
    let names: Vec<&str> = dress.panels.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["front", "back"]);
    assert!(dress.panels.iter().all(|p| p.outline.len() == 10));
    assert_eq!(dress.seams.len(), 6);

    for p in skirt.panels.iter().chain(&dress.panels) {
        assert!(p.holes.is_empty() && p.fabric.is_none() && p.placement.wrap.is_none());
        assert_eq!(p.grain, P2::new(0.0, 1.0));
        assert!(p.outline.iter().all(|e| e.name.is_none()));
    }
}

#[test]
fn vertices_land_where_the_frame_change_puts_them() {
    let skirt = skirt();
    // Front vertex 4, the waist's left end (-20, 0) cm, translated by (0, 102, 18):
    // GarmentCode (-20, 102, 18) cm, ours (-0.20, -0.18, 1.02) m.
    let front = panel(&skirt, "front");
    near2(front.outline[4].start, P2::new(-0.20, 0.0));
    near3(
        front.placement.place(front.outline[4].start),
        Vec3::new(-0.20, -0.18, 1.02),
    );
    // Vertex 0, the hem's left end (-26, -55): (-26, 47, 18) cm.
    near3(
        front.placement.place(front.outline[0].start),
        Vec3::new(-0.26, -0.18, 0.47),
    );
    // The back is turned half round y: (x, y) goes to (-x, y, 0), then (0, 102, -18).
    let back = panel(&skirt, "back");
    near3(
        back.placement.place(back.outline[4].start),
        Vec3::new(0.20, 0.18, 1.02),
    );
    near3(front.placement.normal(P2::zeros()), Vec3::new(0.0, -1.0, 0.0));
    near3(back.placement.normal(P2::zeros()), Vec3::new(0.0, 1.0, 0.0));

    let dress = dress();
    // Front vertex 5, the neckline's right end (8, 40), at (0, 102, 16): (8, 142, 16) cm.
    let front = panel(&dress, "front");
    near3(
        front.placement.place(front.outline[5].start),
        Vec3::new(0.08, -0.16, 1.42),
    );
    // The back is drawn clockwise with no rotation: mirrored in x, and turned half round
    // its y axis so its vertex 4 (-8, 40) still lands at (-8, 142, -14) cm.
    let back = panel(&dress, "back");
    near2(back.outline[4].start, P2::new(0.08, 0.40));
    near3(
        back.placement.place(back.outline[4].start),
        Vec3::new(-0.08, 0.14, 1.42),
    );
    near3(back.placement.normal(P2::zeros()), Vec3::new(0.0, 1.0, 0.0));
}

#[test]
fn every_panel_runs_counter_clockwise_and_faces_away_from_the_body() {
    for pattern in [skirt(), dress()] {
        for p in &pattern.panels {
            let pts: Vec<P2> = p.outline.iter().map(|e| e.start).collect();
            let area: f64 = (0..pts.len())
                .map(|i| pts[i].perp(&pts[(i + 1) % pts.len()]))
                .sum();
            assert!(area > 0.0, "{}: {area}", p.name);
            let centre = pts.iter().sum::<P2>() / pts.len() as f64;
            let at = p.placement.place(centre);
            let out = p.placement.normal(centre);
            assert!(out.x * at.x + out.y * at.y > 0.0, "{} faces the body", p.name);
        }
    }
}

#[test]
fn quadratic_edges_bend_by_their_relative_control_point() {
    let skirt = skirt();
    let front = panel(&skirt, "front");
    // Waist, legacy form [0.5, 0.03] from (20, 0) to (-20, 0): the edge vector (-40, 0)
    // turned left is (0, -40), so the control point is (0, -1.2) cm and the Bezier's
    // midpoint a quarter of the chord's ends plus half the control point, (0, -0.6) cm.
    let waist = &front.outline[3];
    assert_eq!(
        waist.curve,
        Curve::Quadratic {
            control: P2::new(0.0, -0.012)
        }
    );
    near2(waist.point(0.5), P2::new(0.0, -0.006));
    // Hip, [0.5, -0.08] from (26, -18) to (20, 0): (23, -9) + 0.08 * (18, 6) = (24.44, -8.52).
    let Curve::Quadratic { control } = front.outline[2].curve else {
        panic!("{:?}", front.outline[2].curve)
    };
    near2(control, P2::new(0.2444, -0.0852));

    // The dress's back neckline, {"type": "quadratic", "params": [[0.5, -0.25]]} from
    // (-8, 40) to (8, 40): control (0, 40 - 4), midpoint 2 cm below the chord, at
    // (0, 140, -14) cm in GarmentCode's world. (The back is mirrored; x = 0 stays.)
    let dress = dress();
    let back = panel(&dress, "back");
    let neck = &back.outline[4];
    near2(neck.point(0.5), P2::new(0.0, 0.38));
    near3(back.placement.place(neck.point(0.5)), Vec3::new(0.0, 0.14, 1.40));
}

#[test]
fn cubic_edges_follow_their_relative_control_points() {
    let dress = dress();
    let front = panel(&dress, "front");
    // Armhole from (25, 19) to (18, 38), params [[0.3, 0.15], [0.75, 0.05]]: edge vector
    // (-7, 19), turned left (-19, -7); controls (20.05, 23.65) and (18.8, 32.9).
    let armhole = &front.outline[3];
    let Curve::Cubic { control: [c, d] } = armhole.curve else {
        panic!("{:?}", armhole.curve)
    };
    near2(c, P2::new(0.2005, 0.2365));
    near2(d, P2::new(0.188, 0.329));
    // B(1/2) = (a + 3c + 3d + b) / 8 = (159.55, 226.65) / 8 cm.
    near2(armhole.point(0.5), P2::new(0.1994375, 0.2833125));
}

#[test]
fn arcs_have_the_radius_and_turn_the_file_gives() {
    let dress = dress();
    let front = panel(&dress, "front");
    // Neckline: radius 100/12 cm from (8, 40) to (-8, 40), right = 0, so it bulges left of
    // its leftward run, downwards: sagitta r - sqrt(r^2 - 8^2) = 6 cm.
    let neck = &front.outline[5];
    let r = 1.0 / 12.0;
    let Curve::Arc { radius, large, ccw } = neck.curve else {
        panic!("{:?}", neck.curve)
    };
    assert!((radius - r).abs() < 1e-15 && !large && !ccw, "{:?}", neck.curve);
    near2(neck.point(0.5), P2::new(0.0, 0.34));
    let angle = 2.0 * (0.08 / r).asin();
    assert!(
        (neck.length() - r * angle).abs() < 1e-12,
        "{} vs {}",
        neck.length(),
        r * angle
    );
    // Hem: radius 226 cm, chord 60, right = 1 running rightwards: it bulges down by
    // 226 - 224 = 2 cm. The back's hem (right = 0, running leftwards, then mirrored) is
    // the same curve.
    let back = panel(&dress, "back");
    for hem in [&front.outline[0], &back.outline[9]] {
        near2(hem.point(0.5), P2::new(0.0, -0.44));
        let want = 2.26 * 2.0 * (0.30f64 / 2.26).asin();
        assert!((hem.length() - want).abs() < 1e-12, "{} vs {want}", hem.length());
    }
}

#[test]
fn stitches_join_the_edges_they_name_end_to_start() {
    let skirt = skirt();
    let named: Vec<(&str, usize, &str, usize)> = skirt
        .seams
        .iter()
        .map(|s| {
            let (a, b) = (&skirt.panels[s.a.panel], &skirt.panels[s.b.panel]);
            (a.name.as_str(), s.a.edge, b.name.as_str(), s.b.edge)
        })
        .collect();
    assert_eq!(
        named,
        [
            ("front", 1, "back", 5),
            ("front", 2, "back", 4),
            ("front", 4, "back", 2),
            ("front", 5, "back", 1)
        ]
    );
    // GarmentCode pairs the end of the first edge with the start of the second: placed,
    // those ends differ only across the gap between front and back (y).
    for pattern in [skirt, dress()] {
        for s in &pattern.seams {
            assert_eq!(s.orientation, SeamOrientation::Opposite);
            let (pa, pb) = (&pattern.panels[s.a.panel], &pattern.panels[s.b.panel]);
            let (ea, eb) = (&pa.outline[s.a.edge], &pb.outline[s.b.edge]);
            for (x, y) in [(ea.end, eb.start), (ea.start, eb.end)] {
                let gap = pa.placement.place(x) - pb.placement.place(y);
                assert!(
                    gap.x.abs() < 1e-9 && gap.z.abs() < 1e-9,
                    "{}: {gap:?}",
                    pattern.describe(&s.a)
                );
            }
            assert!((ea.length() - eb.length()).abs() < 1e-9);
        }
    }
}

#[test]
fn an_edge_listed_end_to_start_is_turned_round() {
    // Edge 1 is listed from vertex 2 down to vertex 1, bent by [0.5, 0.1] of its own
    // frame: control (10, 20) + 0.5 (0, -20) + 0.1 (20, 0) = (12, 10) cm.
    let edges = r#"[{"endpoints": [0, 1]}, {"endpoints": [2, 1], "curvature": [0.5, 0.1]},
                    {"endpoints": [2, 3]}, {"endpoints": [3, 0]}]"#;
    let p = import(&squares(edges, SIDES, CM)).unwrap_or_else(|e| panic!("{e}"));
    let front = panel(&p, "front");
    let edge = &front.outline[1];
    near2(edge.start, P2::new(0.10, 0.0));
    near2(edge.end, P2::new(0.10, 0.20));
    assert_eq!(
        edge.curve,
        Curve::Quadratic {
            control: P2::new(0.12, 0.10)
        }
    );
    // The seam on it has no trustworthy direction left: nearest pairing. The other keeps
    // GarmentCode's rule.
    assert_eq!(p.seams[0].orientation, SeamOrientation::Auto);
    assert_eq!(p.seams[1].orientation, SeamOrientation::Opposite);

    // The first edge reversed, and an arc turned round keeps its points.
    let edges = r#"[{"endpoints": [1, 0]}, {"endpoints": [1, 2], "curvature": {"type": "circle", "params": [10, 0, 0]}},
                    {"endpoints": [2, 3]}, {"endpoints": [3, 0]}]"#;
    // (Only the straight sides are sewn: a half circle is far longer than its partner.)
    let one_side = r#"[[{"panel": "front", "edge": 3}, {"panel": "back", "edge": 0}]]"#;
    let straight = import(&squares(edges, one_side, CM)).unwrap_or_else(|e| panic!("{e}"));
    let edges = r#"[{"endpoints": [1, 0]}, {"endpoints": [2, 1], "curvature": {"type": "circle", "params": [10, 0, 1]}},
                    {"endpoints": [2, 3]}, {"endpoints": [3, 0]}]"#;
    let turned = import(&squares(edges, one_side, CM)).unwrap_or_else(|e| panic!("{e}"));
    let (a, b) = (
        &panel(&straight, "front").outline,
        &panel(&turned, "front").outline,
    );
    near2(a[0].start, P2::new(-0.10, 0.0));
    // A half circle of radius 10 cm to the left of the upward run: through (0, 10).
    near2(a[1].point(0.5), P2::new(0.0, 0.10));
    near2(b[1].point(0.5), P2::new(0.0, 0.10));
    assert_eq!(a[1], b[1]);
}

#[test]
fn right_wrong_pairs_start_with_start_and_unnormalized_loops_pair_by_distance() {
    let stitches = r#"[[{"panel": "front", "edge": 1}, {"panel": "back", "edge": 2}, "right_wrong"],
                       [{"panel": "front", "edge": 3}, {"panel": "back", "edge": 0}]]"#;
    let p = import(&squares(SQUARE, stitches, CM)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(p.seams[0].orientation, SeamOrientation::Same);
    assert_eq!(p.seams[1].orientation, SeamOrientation::Opposite);
    let old = import(&squares(SQUARE, SIDES, r#"{"units_in_meter": 100}"#)).unwrap_or_else(|e| panic!("{e}"));
    assert!(old.seams.iter().all(|s| s.orientation == SeamOrientation::Auto));
}

#[test]
fn rotation_applies_x_then_y_then_z_about_fixed_axes() {
    // R = Rz(90) Ry(0) Rx(90): (10, 0, 0) stays under Rx, then goes to (0, 10, 0);
    // (0, 10, 0) goes to (0, 0, 10) under Rx and stays under Rz. Translated by
    // (0, 100, 0) cm: ours (0, 0, 1.10) and (0, -0.10, 1.00). The other order would swap
    // the two.
    let text = one_square(
        "[[0, 0], [10, 0], [10, 10], [0, 10]]",
        "[0, 100, 0]",
        "[90, 0, 90]",
        CM,
    );
    let p = import(&text).unwrap_or_else(|e| panic!("{e}"));
    let sq = &p.panels[0];
    near3(sq.placement.place(sq.outline[1].start), Vec3::new(0.0, 0.0, 1.10));
    near3(
        sq.placement.place(sq.outline[3].start),
        Vec3::new(0.0, -0.10, 1.00),
    );
}

#[test]
fn units_scale_everything_and_the_offset_moves_the_garment() {
    let curved = |scale: f64| {
        format!(
            r#"{{"pattern": {{"panels": {{"p": {{
            "translation": [{t0}, {t1}, {t2}], "rotation": [0, 30, 0],
            "vertices": [[0, 0], [{a}, 0], [{a}, {a}], [0, {a}]],
            "edges": [{{"endpoints": [0, 1], "curvature": {{"type": "circle", "params": [{r}, 0, 1]}}}},
                      {{"endpoints": [1, 2], "curvature": [0.5, 0.1]}}, {{"endpoints": [2, 3]}}, {{"endpoints": [3, 0]}}]
        }}}}}}, "properties": {{"units_in_meter": {u}}}}}"#,
            t0 = 5.0 * scale,
            t1 = 100.0 * scale,
            t2 = 20.0 * scale,
            a = 10.0 * scale,
            r = 8.0 * scale,
            u = 100.0 * scale
        )
    };
    let cm = import(&curved(1.0)).unwrap_or_else(|e| panic!("{e}"));
    let mm = import(&curved(10.0)).unwrap_or_else(|e| panic!("{e}"));
    let offset = Vec3::new(0.5, -0.25, 0.1);
    let moved =
        from_json_str(&curved(10.0), "mm.json", &ImportOptions { offset }).unwrap_or_else(|e| panic!("{e}"));
    let (c, m, o) = (&cm.panels[0], &mm.panels[0], &moved.panels[0]);
    for k in 0..4 {
        for t in [0.0, 0.3, 0.5] {
            let (pc, pm) = (c.outline[k].point(t), m.outline[k].point(t));
            near2(pm, pc);
            near3(m.placement.place(pm), c.placement.place(pc));
            near3(o.placement.place(pm), c.placement.place(pc) + offset);
        }
    }
    // The corner (10, 0) cm, turned 30 degrees about y: (10 cos 30, 0, -10 sin 30) + t.
    let (s, co) = (30f64.to_radians().sin(), 30f64.to_radians().cos());
    let want = Vec3::new(0.05 + 0.10 * co, -(0.20 - 0.10 * s), 1.00);
    near3(c.placement.place(c.outline[1].start), want);
}

#[test]
fn normalized_panel_translation_lands_where_garmentcode_puts_it() {
    // GarmentCode moves the vertices' mean (5, 5) to the origin and adds it, unrotated,
    // to the translation: (10, 0) becomes (5, -5), turned 90 degrees about z (5, 5), plus
    // (0, 100, 0) + (5, 5, 0): (10, 110, 0) cm. Without the quirk it would be (0, 110, 0).
    let props = r#"{"units_in_meter": 100, "normalize_panel_translation": true}"#;
    let text = one_square(
        "[[0, 0], [10, 0], [10, 10], [0, 10]]",
        "[0, 100, 0]",
        "[0, 0, 90]",
        props,
    );
    let p = import(&text).unwrap_or_else(|e| panic!("{e}"));
    let sq = &p.panels[0];
    near3(
        sq.placement.place(sq.outline[1].start),
        Vec3::new(0.10, 0.0, 1.10),
    );
}

#[test]
fn absolute_curvature_coords_are_panel_points() {
    let props = r#"{"units_in_meter": 100, "curvature_coords": "absolute", "normalized_edge_loops": true}"#;
    for bend in [r#"[12, 10]"#, r#"{"type": "quadratic", "params": [[12, 10]]}"#] {
        let edges = format!(
            r#"[{{"endpoints": [0, 1]}}, {{"endpoints": [1, 2], "curvature": {bend}}},
                {{"endpoints": [2, 3]}}, {{"endpoints": [3, 0]}}]"#
        );
        let p = import(&squares(&edges, SIDES, props)).unwrap_or_else(|e| panic!("{e}"));
        let edge = &panel(&p, "front").outline[1];
        assert_eq!(
            edge.curve,
            Curve::Quadratic {
                control: P2::new(0.12, 0.10)
            }
        );
    }
}

// ---- errors ----

fn message(result: Result<Pattern, PatternError>) -> (PatternError, String) {
    match result {
        Ok(_) => panic!("imported"),
        Err(e) => {
            let text = e.to_string();
            (e, text)
        }
    }
}

#[test]
fn a_json_syntax_error_names_its_line_and_column() {
    let text = "{\n  \"pattern\": {\n    \"panels\": {}\n    \"stitches\": []\n  }\n}\n";
    let (e, text) = message(import(text));
    let PatternError::Parse { file, message } = e else {
        panic!("{text}")
    };
    assert_eq!(file, "inline.json");
    assert!(
        message.starts_with("line 4, column 5: expected `,` or `}`"),
        "{message}"
    );
}

#[test]
fn a_missing_key_is_a_parse_error_with_its_position() {
    let text =
        squares(SQUARE, SIDES, CM).replace(r#""vertices": [[-10, 0], [10, 0], [10, 20], [-10, 20]],"#, "");
    let (e, text) = message(import(&text));
    assert!(matches!(e, PatternError::Parse { .. }), "{text}");
    assert!(
        text.contains("missing field `vertices`") && text.contains("line "),
        "{text}"
    );
    let (e, text) = message(import(r#"{"pattern": {"panels": {}}}"#));
    assert!(
        matches!(e, PatternError::Parse { .. }) && text.contains("`properties`"),
        "{text}"
    );
}

#[test]
fn a_stitch_naming_a_missing_panel_is_a_seam_error() {
    let stitches = r#"[[{"panel": "front", "edge": 1}, {"panel": "back", "edge": 2}],
                       [{"panel": "front", "edge": 3}, {"panel": "sleeve", "edge": 0}]]"#;
    let (e, text) = message(import(&squares(SQUARE, stitches, CM)));
    assert!(matches!(e, PatternError::Seam { seam: 1, .. }), "{text}");
    assert!(text.contains("side 1 names panel 'sleeve'"), "{text}");
}

#[test]
fn a_stitch_edge_out_of_range_names_the_panel_and_edge() {
    let stitches = r#"[[{"panel": "front", "edge": 7}, {"panel": "back", "edge": 2}]]"#;
    let (e, text) = message(import(&squares(SQUARE, stitches, CM)));
    assert!(matches!(e, PatternError::Seam { seam: 0, .. }), "{text}");
    assert!(text.contains("panel 'front' has no edge 7"), "{text}");
    // A stitch with one side is not a stitch.
    let (e, text) = message(import(&squares(
        SQUARE,
        r#"[[{"panel": "front", "edge": 1}]]"#,
        CM,
    )));
    assert!(matches!(e, PatternError::Parse { .. }), "{text}");
}

#[test]
fn an_edge_loop_that_does_not_close_names_the_edge() {
    let open =
        r#"[{"endpoints": [0, 1]}, {"endpoints": [1, 2]}, {"endpoints": [2, 3]}, {"endpoints": [3, 1]}]"#;
    let (e, text) = message(import(&squares(open, SIDES, CM)));
    let PatternError::Panel {
        panel, edge, reason, ..
    } = e
    else {
        panic!("{text}")
    };
    assert_eq!((panel.as_str(), edge.as_deref()), ("front", Some("3")));
    assert!(reason.contains("not closed"), "{reason}");
    let broken =
        r#"[{"endpoints": [0, 1]}, {"endpoints": [2, 3]}, {"endpoints": [3, 0]}, {"endpoints": [1, 2]}]"#;
    let (e, text) = message(import(&squares(broken, SIDES, CM)));
    assert!(
        matches!(&e, PatternError::Panel { edge: Some(k), .. } if k == "1")
            && text.contains("do not form a loop"),
        "{text}"
    );
}

#[test]
fn a_vertex_index_out_of_range_names_the_edge() {
    let edges =
        r#"[{"endpoints": [0, 1]}, {"endpoints": [1, 9]}, {"endpoints": [2, 3]}, {"endpoints": [3, 0]}]"#;
    let (e, text) = message(import(&squares(edges, SIDES, CM)));
    assert!(
        matches!(&e, PatternError::Panel { edge: Some(k), .. } if k == "1"),
        "{text}"
    );
    assert!(
        text.contains("panel 'front', edge 1: endpoint 9 is out of range"),
        "{text}"
    );
}

#[test]
fn bad_units_are_refused() {
    for units in ["0", "-100"] {
        let props = format!(r#"{{"units_in_meter": {units}}}"#);
        let (e, text) = message(import(&squares(SQUARE, SIDES, &props)));
        assert!(matches!(e, PatternError::Pattern { .. }), "{text}");
        assert!(text.contains(&format!("units_in_meter is {units}")), "{text}");
    }
}

#[test]
fn an_unknown_curvature_type_names_the_edge() {
    let edges = r#"[{"endpoints": [0, 1]}, {"endpoints": [1, 2], "curvature": {"type": "spline", "params": []}},
                    {"endpoints": [2, 3]}, {"endpoints": [3, 0]}]"#;
    let (e, text) = message(import(&squares(edges, SIDES, CM)));
    assert!(
        matches!(&e, PatternError::Panel { edge: Some(k), .. } if k == "1"),
        "{text}"
    );
    assert!(text.contains("unknown curvature type 'spline'"), "{text}");
    let edges = r#"[{"endpoints": [0, 1]}, {"endpoints": [1, 2], "curvature": {"type": "circle", "params": [5, 0]}},
                    {"endpoints": [2, 3]}, {"endpoints": [3, 0]}]"#;
    let (_, text) = message(import(&squares(edges, SIDES, CM)));
    assert!(
        text.contains("circle params must be [radius, large_arc, right]"),
        "{text}"
    );
}

#[test]
fn panel_order_must_name_each_panel_once() {
    let with_order = |order: &str| {
        squares(SQUARE, SIDES, CM).replace(
            r#""stitches":"#,
            &format!(r#""panel_order": {order}, "stitches":"#),
        )
    };
    let (e, text) = message(import(&with_order(r#"["front", "sleeve"]"#)));
    assert!(
        matches!(e, PatternError::Pattern { .. }) && text.contains("'sleeve'"),
        "{text}"
    );
    let (_, text) = message(import(&with_order(r#"["front"]"#)));
    assert!(
        text.contains("panel 'back' is missing from panel_order"),
        "{text}"
    );
    let p = import(&with_order(r#"["back", "front"]"#)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(p.panels[0].name, "back");
    // Seams follow the panels to their new indices.
    assert_eq!((p.seams[0].a.panel, p.seams[0].b.panel), (1, 0));
}

#[test]
fn a_missing_file_is_an_io_error() {
    let missing = asset("no_such_specification.json");
    match from_path(&missing, &ImportOptions::default()) {
        Err(PatternError::Io { path, .. }) => assert_eq!(path, missing),
        other => panic!("{other:?}"),
    }
}

#[test]
fn imported_patterns_mesh_with_outward_triangles_and_matching_seam_pairs() {
    use cloth_garment::garment::GarmentBuilder;
    for (name, pattern) in [("skirt", skirt()), ("dress", dress())] {
        let garment = GarmentBuilder::new(pattern)
            .edge_length(0.03)
            .build()
            .unwrap_or_else(|e| panic!("{e}"));
        let x = garment.mesh.positions();
        // Every triangle's normal points away from the body: the panels' windings agree,
        // so welded seams join triangles wound the same way.
        for t in garment.mesh.triangles() {
            let n = (x[t[1]] - x[t[0]]).cross(&(x[t[2]] - x[t[0]]));
            let c = (x[t[0]] + x[t[1]] + x[t[2]]) / 3.0;
            assert!(n.x * c.x + n.y * c.y > 0.0, "{name}: an inward triangle at {c:?}");
        }
        // Front and back are placed flat, apart in y only: paired seam vertices share x, z.
        for seam in &garment.seams {
            for &[i, j] in &seam.pairs {
                let gap = x[i] - x[j];
                assert!(
                    gap.x.abs() < 1e-6 && gap.z.abs() < 1e-6,
                    "{name}, {}: {gap:?}",
                    seam.name
                );
            }
        }
    }
}

#[test]
fn a_pattern_in_the_wrong_units_is_refused_before_meshing() {
    // GarmentCode's sampled skirt with its units read as millimetres per kilometre: panels
    // 45 km wide. Refused at once, naming the panel and the count, with nothing meshed.
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/garmentcode/patterns/rand_1_001.json"),
    )
    .unwrap()
    .replace("\"units_in_meter\": 100", "\"units_in_meter\": 0.001");
    let pattern = from_json_str(&text, "rand_1_001.json", &ImportOptions::default()).unwrap();
    let (estimate, _) = pattern.estimated_triangles(0.015);
    assert!(estimate > 1e12, "{estimate}");
    let e = GarmentBuilder::new(pattern).build().unwrap_err();
    assert!(
        matches!(e, GarmentError::TooLarge { limit: 2_000_000, .. }),
        "{e}"
    );
    let message = e.to_string();
    assert!(
        message.contains("panel, 'wb_front', is 45198.000 m by 4696.740 m")
            && message.contains("max_triangles"),
        "{message}"
    );
    // The estimate is close to what meshing gives, at the real units.
    let pattern = load("../../garmentcode/patterns/rand_1_001.json");
    let (estimate, _) = pattern.estimated_triangles(0.015);
    let garment = GarmentBuilder::new(pattern).edge_length(0.015).build().unwrap();
    let ratio = estimate / garment.mesh.triangles().len() as f64;
    assert!((0.8..1.25).contains(&ratio), "estimate / meshed = {ratio}");
}

#[test]
fn seams_on_edges_shorter_than_a_cell_are_sewn_keeping_each_side_length() {
    // GarmentCode's sampled top pairs a 1.5 mm edge of the front torso with a 0.75 mm edge
    // of the back, ten times shorter than the cells: sewn as one piece on each side, each
    // keeping its own length.
    let pattern = from_path(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/garmentcode/patterns/rand_1_057.json"),
        &ImportOptions::default(),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let length = |side: &cloth_garment::SeamSide| pattern.panels[side.panel].outline[side.edge].length();
    let short: Vec<usize> = (0..pattern.seams.len())
        .filter(|&k| length(&pattern.seams[k].a).max(length(&pattern.seams[k].b)) < 0.002)
        .collect();
    assert_eq!(short.len(), 2, "the left and right torso's");
    let k = short[0];
    let seam = &pattern.seams[k];
    let (la, lb) = (length(&seam.a), length(&seam.b));
    assert!(la.min(lb) < 0.001, "{la} {lb}");
    let h = 0.015;
    let garment = GarmentBuilder::new(pattern)
        .edge_length(h)
        .build()
        .unwrap_or_else(|e| panic!("{e}"));
    let x = garment.mesh.positions();
    let pairs = &garment.seams[k].pairs;
    assert_eq!(pairs.len(), 2, "{}", garment.seams[k].name);
    for (side, length) in [(0, la), (1, lb)] {
        let d = (x[pairs[1][side]] - x[pairs[0][side]]).norm();
        assert!((d - length).abs() < 1e-9, "side {side}: {d} against {length}");
    }
}

#[test]
fn labelled_edges_are_attached_as_garmentcodes_simulator_holds_them() {
    // The front's top held up (a waist), its side at -x (the body's right) held from
    // moving further to -x (a right neckline), its side at +x from moving further to +x;
    // an armhole label holds nothing.
    let edges = r#"[{"endpoints": [0, 1], "label": "right_armhole"},
                    {"endpoints": [1, 2], "label": "left_collar"},
                    {"endpoints": [2, 3], "label": "lower_interface"},
                    {"endpoints": [3, 0], "label": "right_collar"}]"#;
    let pattern = import(&squares(edges, SIDES, CM)).unwrap();
    let front = pattern.panel_index("front").unwrap();
    let held: Vec<(usize, Vec3)> = pattern
        .attachments
        .iter()
        .map(|a| {
            assert_eq!(a.edge.panel, front);
            (a.edge.edge, a.direction)
        })
        .collect();
    assert_eq!(held, vec![(1, -Vec3::x()), (2, Vec3::z()), (3, Vec3::x())]);
    // Each edge's particles, and only theirs, are attached in the garment.
    let garment = GarmentBuilder::new(pattern).edge_length(0.02).build().unwrap();
    let x = garment.mesh.positions();
    let counts: Vec<usize> = garment.attached.iter().map(|(p, _)| p.len()).collect();
    assert_eq!(counts, vec![11, 11, 11], "20 cm at 2 cm: 11 particles an edge");
    for (particles, d) in &garment.attached {
        for &i in particles {
            // Front at y = -0.15; its top at z = 1.2, its sides at x = -0.1 (right) and 0.1.
            assert!((x[i].y + 0.15).abs() < 1e-6);
            if *d == Vec3::z() {
                assert!((x[i].z - 1.2).abs() < 1e-6);
            } else {
                assert!((x[i].x + 0.1 * d.x).abs() < 1e-6, "{} {}", x[i].x, d.x);
            }
        }
    }
}
