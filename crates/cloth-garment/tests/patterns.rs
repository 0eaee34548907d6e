//! Patterns in our TOML format: reading, meshing, seam pairing, welding, and bad input.

use cloth_collide::Bodies;
use cloth_garment::mannequin::{Mannequin, Measurements};
use cloth_garment::meshing::ANGLE_LIMIT_DEGREES;
use cloth_garment::{GarmentBuilder, Gather, Pattern, PatternError};

const SKIRT: &str = include_str!("../../../assets/patterns/skirt.toml");
const DRESS: &str = include_str!("../../../assets/patterns/dress.toml");
const TSHIRT: &str = include_str!("../../../assets/patterns/tshirt.toml");

/// A two-panel tube: a 40 x 30 cm front with a 20 cm arc at the top and a circular hole,
/// and a back, joined at the sides; the back's right side 8% longer (ease).
fn tube(back_right_height: f64, extra: &str) -> String {
    format!(
        r#"
units = "cm"
[[panels]]
name = "front"
grain = [1, 1]
outline = [
    {{ start = [-20, 0], name = "hem" }},
    {{ start = [20, 0], name = "right" }},
    {{ start = [20, 30], name = "top", arc = {{ radius = 25, ccw = true }} }},
    {{ start = [-20, 30], name = "left" }},
]
holes = [[ {{ start = [-3, 10] }}, {{ start = [3, 10], arc = {{ radius = 3 }} }} ]]
placement = {{ rotation = [90, 0, 0], translation = [0, -20, 50] }}

[[panels]]
name = "back"
outline = [
    {{ start = [-20, 0], name = "hem" }},
    {{ start = [20, 0], name = "right" }},
    {{ start = [20, {back_right_height}], name = "top" }},
    {{ start = [-20, 30], name = "left" }},
]
placement = {{ rotation = [90, 0, 180], translation = [0, 20, 50] }}

[[seams]]
a = {{ panel = "front", edge = "right" }}
b = {{ panel = "back", edge = "left" }}

[[seams]]
a = {{ panel = "front", edge = 3 }}
b = {{ panel = "back", edge = "right" }}
{extra}
"#
    )
}

#[test]
fn a_pattern_meshes_with_seams_paired_one_to_one() {
    let pattern = Pattern::from_toml_str(&tube(32.4, ""), "tube.toml").unwrap();
    assert_eq!(pattern.panels.len(), 2);
    assert_eq!(pattern.panels[0].holes.len(), 1);
    // Units: the front's hem is 40 cm.
    assert!((pattern.panels[0].outline[0].length() - 0.4).abs() < 1e-12);
    let h = 0.02;
    let garment = GarmentBuilder::new(pattern.clone())
        .edge_length(h)
        .build()
        .unwrap();
    let mesh = &garment.mesh;
    // Both sides of each seam have the same count: the longer side's length over h (the
    // back's right side is the longer one of the second seam).
    assert_eq!(garment.seams[0].pairs.len(), 15 + 1);
    assert_eq!(garment.seams[1].pairs.len(), 16 + 1);
    // Paired vertices are the edges' resampled points: equal fractions of arc length.
    let x = mesh.positions();
    for seam in &garment.seams {
        let n = seam.pairs.len();
        for (k, &[a, b]) in seam.pairs.iter().enumerate() {
            let f = k as f64 / (n - 1) as f64;
            // The front's side is 30 cm, the back's 30 or 32.4 cm: both start at z = 0.5.
            let (za, zb) = (x[a].z - 0.5, x[b].z - 0.5);
            assert!(
                (za / 0.3 - f).abs() < 1e-9 || (za / 0.3 - (1.0 - f)).abs() < 1e-9,
                "{za} at {f}"
            );
            assert!((-1e-12..=0.324 + 1e-12).contains(&zb), "{zb}");
        }
    }
    // The hole is cut: no triangle centroid in the half disc of 3 cm over (0, 10) of the
    // front (a line, then a half circle back counter-clockwise).
    let front = |t: usize| garment.triangle_panel[t] == 0;
    for (t, tri) in mesh.triangles().iter().enumerate().filter(|(t, _)| front(*t)) {
        let c = tri.iter().map(|&i| x[i]).sum::<cloth_core::math::Vec3>() / 3.0;
        let in_hole = c.z > 0.6 && (c.x.powi(2) + (c.z - 0.6).powi(2)).sqrt() < 0.029;
        assert!(!in_hole, "triangle {t} in the hole");
    }
    let area: f64 = (0..mesh.triangles().len())
        .filter(|&t| front(t))
        .map(|t| mesh.rest_area(t))
        .sum();
    let expected = 0.4 * 0.3 + segment_area(0.25, 0.4) - 0.5 * std::f64::consts::PI * 0.03f64.powi(2);
    assert!((area / expected - 1.0).abs() < 0.01, "{area} vs {expected}");
    // Quality: no angle under the refinement's limit but where the outline forces one
    // (at a corner of the outline, or between boundary points).
    let uv = mesh.uv();
    let mut small = 0;
    for tri in mesh.triangles() {
        for k in 0..3 {
            let (a, b, c) = (uv[tri[k]], uv[tri[(k + 1) % 3]], uv[tri[(k + 2) % 3]]);
            let angle = (b - a).angle(&(c - a)).to_degrees();
            if angle < ANGLE_LIMIT_DEGREES - 1e-6 {
                small += 1;
            }
        }
    }
    assert!(small <= 8, "{small} angles under {ANGLE_LIMIT_DEGREES} degrees");
    // Grain: the front's warp runs along its diagonal, so its hem (along x) is at 45
    // degrees to u; the back's grain is the default (along y).
    let (a, b) = (garment.seams[0].pairs[0][0], garment.seams[0].pairs[1][0]);
    let d = uv[b] - uv[a];
    // (To the mesher's bow of straight edges, a millionth of their length.)
    assert!((d.x.abs() - d.y.abs()).abs() < 1e-6, "{d:?}");
    // Welding joins each pair and rebuilds hinges across the seams.
    let welded = garment.weld(x).unwrap();
    let pairs = garment.seam_pairs().len();
    assert_eq!(welded.mesh.vertex_count(), mesh.vertex_count() - pairs);
    assert!(welded.mesh.hinges().len() > mesh.hinges().len());
    assert!(welded.mesh.has_seams());
}

#[test]
fn unequal_seam_sides_are_gathers_reported_not_refused() {
    // 34 cm onto 30: more than ease, so reported; 32.4 is within ease.
    let gathered = Pattern::from_toml_str(&tube(34.0, ""), "tube.toml").unwrap();
    let gathers = gathered.gathers();
    assert_eq!(gathers.len(), 1);
    let g = &gathers[0];
    assert_eq!(g.seam, 1);
    assert!((g.ratio() - 34.0 / 30.0).abs() < 1e-12 && !g.excessive());
    assert!(g.to_string().contains("34.0 cm onto 30.0 cm (1.13:1)"), "{g}");
    let eased = Pattern::from_toml_str(&tube(32.4, ""), "tube.toml").unwrap();
    assert!(eased.gathers().is_empty());
    // Both sides get the longer side's count, spaced evenly along each: the pairing is
    // proportional to arc length, so each side keeps its own rest lengths.
    let h = 0.02;
    let garment = GarmentBuilder::new(gathered).edge_length(h).build().unwrap();
    let x = garment.mesh.positions();
    let pairs = &garment.seams[1].pairs;
    assert_eq!(pairs.len(), (0.34 / h).round() as usize + 1);
    let spacing = |side: usize| {
        let steps: Vec<f64> = pairs
            .windows(2)
            .map(|w| (x[w[1][side]] - x[w[0][side]]).norm())
            .collect();
        (
            steps.iter().cloned().fold(f64::MAX, f64::min),
            steps.iter().cloned().fold(0.0, f64::max),
        )
    };
    for (side, length) in [(0, 0.30), (1, 0.34)] {
        let (lo, hi) = spacing(side);
        let even = length / (pairs.len() - 1) as f64;
        assert!(
            (lo - even).abs() < 1e-9 && (hi - even).abs() < 1e-9,
            "side {side}: {lo} to {hi}, {even}"
        );
    }
    // A gather past 5:1 of a few millimetres is a drafting detail, not refused.
    let gather = |long: f64, short: f64| Gather {
        seam: 0,
        name: String::new(),
        long,
        short,
    };
    assert!(!gather(0.006, 0.001).excessive());
    assert!(gather(0.2, 0.03).excessive() && !gather(0.2, 0.05).excessive());
}

#[test]
fn shipped_patterns_read() {
    let skirt = Pattern::from_toml_str(SKIRT, "skirt.toml").unwrap();
    assert_eq!((skirt.panels.len(), skirt.seams.len()), (2, 2));
    let dress = Pattern::from_toml_str(DRESS, "dress.toml").unwrap();
    assert_eq!((dress.panels.len(), dress.seams.len()), (2, 4));
    let shirt = Pattern::from_toml_str(TSHIRT, "tshirt.toml").unwrap();
    assert_eq!((shirt.panels.len(), shirt.seams.len()), (4, 10));
    for pattern in [skirt, dress, shirt] {
        GarmentBuilder::new(pattern).edge_length(0.03).build().unwrap();
    }
}

/// Area between a chord of length `c` and its minor arc of radius `r`.
fn segment_area(r: f64, c: f64) -> f64 {
    let angle = 2.0 * (c / (2.0 * r)).asin();
    0.5 * r * r * (angle - angle.sin())
}

fn error(text: &str) -> String {
    Pattern::from_toml_str(text, "bad.toml").unwrap_err().to_string()
}

#[test]
fn bad_patterns_are_refused_with_the_panel_and_edge() {
    // A self-intersecting outline (a bow tie).
    let bow = tube(30.0, "")
        .replace(
            "{ start = [20, 0], name = \"right\" }",
            "{ start = [20, 30], name = \"right\" }",
        )
        .replacen(
            "{ start = [20, 30], name = \"top\", arc = { radius = 25, ccw = true } }",
            "{ start = [20, 0], name = \"top\" }",
            1,
        );
    let e = error(&bow);
    assert!(e.contains("panel 'front'") && e.contains("crosses"), "{e}");

    // A seam naming a missing panel, and a missing edge.
    let e = error(&tube(
        30.0,
        "[[seams]]\na = { panel = \"sleeve\", edge = 0 }\nb = { panel = \"back\", edge = 0 }",
    ));
    assert!(
        e.contains("seam 2") && e.contains("no panel named 'sleeve'") && e.contains("front, back"),
        "{e}"
    );
    let e = error(&tube(
        30.0,
        "[[seams]]\na = { panel = \"front\", edge = \"collar\" }\nb = { panel = \"back\", edge = 0 }",
    ));
    assert!(
        e.contains("seam 2") && e.contains("panel 'front' has no edge 'collar'") && e.contains("hem, right"),
        "{e}"
    );
    let e = error(&tube(
        30.0,
        "[[seams]]\na = { panel = \"front\", edge = 9 }\nb = { panel = \"back\", edge = 0 }",
    ));
    assert!(e.contains("has no edge 9"), "{e}");

    // A gather beyond 5:1: 160 cm onto 30.
    let e = error(&tube(160.0, ""));
    assert!(
        e.contains("seam 1") && e.contains("panel 'back', edge 'right'") && e.contains("5.3:1"),
        "{e}"
    );

    // An edge sewn twice.
    let e = error(&tube(
        30.0,
        "[[seams]]\na = { panel = \"front\", edge = \"right\" }\nb = { panel = \"back\", edge = \"hem\" }",
    ));
    assert!(e.contains("already sewn by seam 0"), "{e}");

    // Unknown keys and syntax errors carry the line.
    let e = error(&tube(30.0, "").replace("grain = [1, 1]", "grian = [1, 1]"));
    assert!(
        e.contains("bad.toml") && e.contains("line") && e.contains("grian"),
        "{e}"
    );

    // An arc too small for its chord names the edge.
    let e = error(&tube(30.0, "").replace("radius = 25", "radius = 5"));
    assert!(
        e.contains("panel 'front'") && e.contains("'top'") && e.contains("under half the chord"),
        "{e}"
    );

    // A hole outside the outline.
    let e = error(
        &tube(30.0, "")
            .replace("start = [-3, 10] }}, {{ start = [3, 10]", "x")
            .replace(
                "{ start = [-3, 10] }, { start = [3, 10], arc = { radius = 3 } }",
                "{ start = [30, 10] }, { start = [36, 10], arc = { radius = 3 } }",
            ),
    );
    assert!(e.contains("hole 0 is not inside the outline"), "{e}");
    assert!(matches!(
        Pattern::from_toml_str("units = \"cm\"\npanels = []", "empty.toml"),
        Err(PatternError::Pattern { .. })
    ));
}

#[test]
fn a_panel_starting_inside_the_body_is_warned_with_the_fix() {
    let mannequin = Mannequin::new(&Measurements::default()).unwrap();
    let bodies = Bodies::new(mannequin.bodies());
    // The skirt as shipped starts clear of the body.
    let skirt = Pattern::from_toml_str(SKIRT, "skirt.toml").unwrap();
    let garment = GarmentBuilder::new(skirt.clone())
        .edge_length(0.03)
        .build()
        .unwrap();
    assert!(garment.placement_warnings(&bodies).is_empty());
    // Its front panel pushed 12 cm back goes through the hips.
    let mut pushed = skirt;
    pushed.panels[0].placement.translation.y += 0.12;
    let garment = GarmentBuilder::new(pushed).edge_length(0.03).build().unwrap();
    let warnings = garment.placement_warnings(&bodies);
    assert_eq!(warnings.len(), 1);
    let w = &warnings[0];
    assert_eq!((w.panel.as_str(), w.body.as_str()), ("front", "torso"));
    assert!(w.depth > 0.01 && w.outward.y < -0.5, "{w:?}");
    let text = w.to_string();
    assert!(
        text.contains("panel 'front' starts") && text.contains("move it"),
        "{text}"
    );
}

#[test]
fn a_panel_starting_inside_the_body_is_moved_out_whole() {
    let mannequin = Mannequin::new(&Measurements::default()).unwrap();
    let bodies = Bodies::new(mannequin.bodies());
    let mut pushed = Pattern::from_toml_str(SKIRT, "skirt.toml").unwrap();
    pushed.panels[0].placement.translation.y += 0.12;
    let mut garment = GarmentBuilder::new(pushed).edge_length(0.03).build().unwrap();
    let before = garment.mesh.positions().to_vec();
    let moved = garment.move_out_of(&bodies);
    assert_eq!(moved.len(), 1);
    let w = &moved[0];
    let distance = w.moved.expect("cleared");
    assert!(distance > w.depth, "{w:?}");
    assert!(w.to_string().contains("moved"), "{w}");
    // Nothing inside now, and the front panel a clearance off the body.
    assert!(garment.placement_warnings(&bodies).is_empty());
    let (deepest, _) = bodies.deepest_inside(0.0, garment.mesh.positions());
    assert_eq!(deepest, 0.0);
    // Moved whole: every particle by the same vector, the front's along its outward
    // normal, the back's not at all.
    let shifts: Vec<cloth_core::math::Vec3> = garment
        .mesh
        .positions()
        .iter()
        .zip(&before)
        .map(|(a, b)| a - b)
        .collect();
    let front = shifts.iter().find(|d| d.norm() > 0.0).copied().unwrap();
    assert!((front - w.outward * distance).norm() < 1e-12, "{front}");
    assert!(shifts
        .iter()
        .all(|d| d.norm() == 0.0 || (d - front).norm() < 1e-12));
    assert!(shifts.iter().any(|d| d.norm() == 0.0));
}

#[test]
fn tight_curves_are_sampled_finer_and_the_mesh_graded_from_them() {
    // A 40 x 30 cm panel with a notch of 3 cm radius in its top edge, meshed at 5 cm.
    let text = r#"
[[panels]]
name = "notched"
outline = [
    { start = [-20, 0] },
    { start = [20, 0] },
    { start = [20, 30] },
    { start = [3, 30], name = "notch", arc = { radius = 3, ccw = false } },
    { start = [-3, 30] },
    { start = [-20, 30] },
]
"#;
    let pattern = Pattern::from_toml_str(text, "notched.toml").unwrap();
    let notch = &pattern.panels[0].outline[3];
    assert!((notch.turning() - std::f64::consts::PI).abs() < 1e-12);
    let garment = GarmentBuilder::new(pattern).edge_length(0.05).build().unwrap();
    let mesh = &garment.mesh;
    // 15 degrees a segment: 12 segments on the half circle, where its 9.4 cm alone
    // would give 2.
    // (Placed with the default placement, at its 2D coordinates in the z = 0 plane.)
    let from_centre = |p: &cloth_core::math::Vec3| (p.x.powi(2) + (p.y - 0.3).powi(2)).sqrt();
    let on_notch = mesh
        .positions()
        .iter()
        .filter(|p| (from_centre(p) - 0.03).abs() < 1e-4)
        .count();
    assert_eq!(on_notch, 13);
    // Graded: triangles at the notch are far smaller than the mesh's typical one.
    let mut areas: Vec<f64> = (0..mesh.triangles().len()).map(|t| mesh.rest_area(t)).collect();
    areas.sort_by(f64::total_cmp);
    let median = areas[areas.len() / 2];
    assert!(areas[0] < 0.1 * median, "{} vs {median}", areas[0]);
}

#[test]
fn a_dart_is_two_edges_of_one_panel_sewn_together() {
    // A 40 x 30 cm panel with a 4 cm wide, 10 cm deep dart cut into its top edge.
    let text = r#"
[[panels]]
name = "bodice"
outline = [
    { start = [-20, 0] },
    { start = [20, 0] },
    { start = [20, 30] },
    { start = [2, 30], name = "dart_right" },
    { start = [0, 20], name = "dart_left" },
    { start = [-2, 30] },
    { start = [-20, 30] },
]

[[seams]]
a = { panel = "bodice", edge = "dart_left" }
b = { panel = "bodice", edge = "dart_right" }
"#;
    let pattern = Pattern::from_toml_str(text, "dart.toml").unwrap();
    let garment = GarmentBuilder::new(pattern).edge_length(0.02).build().unwrap();
    // The legs run tip-out and out-tip: sewn opposite, the tip meets itself and is dropped,
    // so each of the legs' other points pairs with its mirror image across the dart.
    let pairs = &garment.seams[0].pairs;
    let x = garment.mesh.positions();
    assert_eq!(pairs.len(), 5);
    for &[a, b] in pairs {
        assert!(a != b);
        assert!(
            (x[a].x + x[b].x).abs() < 1e-9 && (x[a].y - x[b].y).abs() < 1e-9,
            "{} {}",
            x[a],
            x[b]
        );
    }
    // Welded, the dart closes: no triangle collapses and the vertices are 5 fewer.
    let welded = garment.weld(x).unwrap();
    assert_eq!(welded.mesh.vertex_count(), garment.mesh.vertex_count() - 5);
}

#[test]
fn each_seam_pair_stands_for_its_share_of_the_shorter_side() {
    // The back's right side is 34 cm, gathered onto the front's 30 cm left side.
    let pattern = Pattern::from_toml_str(&tube(34.0, ""), "tube.toml").unwrap();
    let garment = GarmentBuilder::new(pattern).edge_length(0.02).build().unwrap();
    let shares = garment.seam_shares();
    assert_eq!(shares.len(), garment.seam_pairs().len());
    let mut from = 0;
    for (seam, sides) in garment.seams.iter().zip([(0.30f64, 0.30f64), (0.30, 0.34)]) {
        let own = &shares[from..from + seam.pairs.len()];
        from += seam.pairs.len();
        // Half the way to each neighbour: the ends half an interior pair's, and together the
        // length of the shorter side.
        let total: f64 = own.iter().sum();
        assert!((total - sides.0.min(sides.1)).abs() < 1e-9, "{total}");
        let spacing = sides.0.min(sides.1) / (own.len() - 1) as f64;
        assert!((own[0] - 0.5 * spacing).abs() < 1e-9 && (own[own.len() - 1] - 0.5 * spacing).abs() < 1e-9);
        assert!(
            own[1..own.len() - 1].iter().all(|s| (s - spacing).abs() < 1e-9),
            "{own:?}"
        );
    }
}

#[test]
fn a_panel_through_a_thin_part_of_the_body_passes_through_it_instead() {
    use cloth_collide::{Body, TriSurface};
    use nalgebra::{Isometry3, Translation3, UnitQuaternion};
    // A hand, 3 cm thick along the front panel's normal, through the middle of it.
    let mannequin = Mannequin::new(&Measurements::default()).unwrap();
    let mut parts = mannequin.bodies();
    let hand = Body::new(
        "hand",
        TriSurface::cuboid(cloth_core::math::Vec3::new(0.04, 0.015, 0.08)).unwrap(),
    )
    .with_pose(Isometry3::from_parts(
        Translation3::new(0.0, -0.17, 0.6),
        UnitQuaternion::identity(),
    ))
    .unwrap();
    parts.push(hand);
    let bodies = Bodies::new(parts);
    let skirt = Pattern::from_toml_str(SKIRT, "skirt.toml").unwrap();
    let mut garment = GarmentBuilder::new(skirt).edge_length(0.02).build().unwrap();
    let before = garment.mesh.positions().to_vec();
    let warnings = garment.move_out_of(&bodies);
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    let w = &warnings[0];
    assert_eq!((w.panel.as_str(), w.body.as_str()), ("front", "hand"));
    assert!(w.passing > 0 && w.moved.is_none(), "{w:?}");
    assert!(w.to_string().contains("passes through"), "{w}");
    // Not moved: the whole front panel passes through.
    assert_eq!(garment.mesh.positions(), &before[..]);
    assert_eq!(garment.passing.len(), 1);
    let front: std::collections::BTreeSet<usize> = garment
        .mesh
        .triangles()
        .iter()
        .zip(&garment.triangle_panel)
        .filter(|(_, &p)| p == 0)
        .flat_map(|(t, _)| *t)
        .collect();
    assert_eq!(garment.passing[0].members, front.into_iter().collect::<Vec<_>>());
}

#[test]
fn panels_overlapping_in_one_plane_are_layered_the_higher_outside() {
    // Two tiers of a skirt front laid flat in one plane, the upper overlapping the lower
    // by 5 cm, and a back panel in its own plane.
    let text = r#"
units = "cm"
[[panels]]
name = "upper"
outline = [{ start = [-20, 0] }, { start = [20, 0] }, { start = [20, 20] }, { start = [-20, 20] }]
placement = { rotation = [90, 0, 0], translation = [0, -20, 80] }
[[panels]]
name = "lower"
outline = [{ start = [-20, 0] }, { start = [20, 0] }, { start = [20, 20] }, { start = [-20, 20] }]
placement = { rotation = [90, 0, 0], translation = [0, -20, 65] }
[[panels]]
name = "back"
outline = [{ start = [-20, 0] }, { start = [20, 0] }, { start = [20, 35] }, { start = [-20, 35] }]
placement = { rotation = [90, 0, 180], translation = [0, 20, 65] }
[[seams]]
a = { panel = "upper", edge = 0 }
b = { panel = "lower", edge = 2 }
"#;
    let pattern = Pattern::from_toml_str(text, "tiers.toml").unwrap();
    let mut garment = GarmentBuilder::new(pattern).edge_length(0.02).build().unwrap();
    let before = garment.mesh.positions().to_vec();
    let layered = garment.layer_overlapping(0.002);
    assert_eq!(layered.len(), 1, "{layered:?}");
    assert_eq!(layered[0].panels, ["upper", "lower"]);
    assert!(
        layered[0].to_string().contains("'upper', 'lower' overlap"),
        "{}",
        layered[0]
    );
    // The upper tier stays; the lower goes 2 mm in, behind it (the front faces -y); the back
    // does not move.
    for (t, tri) in garment.mesh.triangles().iter().enumerate() {
        for &i in tri {
            let shift = garment.mesh.positions()[i] - before[i];
            let expected = match garment.triangle_panel[t] {
                1 => cloth_core::math::Vec3::new(0.0, 0.002, 0.0),
                _ => cloth_core::math::Vec3::zeros(),
            };
            assert!(
                (shift - expected).norm() < 1e-12,
                "panel {}: {shift:?}",
                garment.triangle_panel[t]
            );
        }
    }
    // Layered once, they no longer overlap in one plane.
    assert!(garment.layer_overlapping(0.002).is_empty());
}

#[test]
fn panels_touching_where_no_seam_joins_them_are_found() {
    // In one plane: 'left' and 'right' meet at one corner only, as GarmentCode's godets
    // do; 'top' lies edge to edge on 'left' and is sewn to it there.
    let text = r#"
units = "cm"
[[panels]]
name = "left"
outline = [{ start = [-20, 0] }, { start = [0, 0] }, { start = [0, 20] }, { start = [-20, 20] }]
placement = { rotation = [90, 0, 0], translation = [0, -20, 80] }
[[panels]]
name = "right"
outline = [{ start = [0, -20] }, { start = [20, -20] }, { start = [20, 0] }, { start = [0, 0] }]
placement = { rotation = [90, 0, 0], translation = [0, -20, 80] }
[[panels]]
name = "top"
outline = [{ start = [-20, 20] }, { start = [0, 20] }, { start = [0, 40] }, { start = [-20, 40] }]
placement = { rotation = [90, 0, 0], translation = [0, -20, 80] }
[[seams]]
a = { panel = "left", edge = 2 }
b = { panel = "top", edge = 0 }
"#;
    let pattern = Pattern::from_toml_str(text, "corners.toml").unwrap();
    let mut garment = GarmentBuilder::new(pattern).edge_length(0.02).build().unwrap();
    let found = garment.find_touching();
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].panels, ["left", "right"]);
    assert_eq!(found[0].points, 1);
    assert!(
        found[0]
            .to_string()
            .contains("touch at 1 point where no seam joins them"),
        "{}",
        found[0]
    );
    // The pair kept for the sewing is the corner: at (0, -0.2, 0.8), one particle of each.
    assert_eq!(garment.touching.len(), 1);
    let [i, j] = garment.touching[0];
    let x = garment.mesh.positions();
    let corner = cloth_core::math::Vec3::new(0.0, -0.2, 0.8);
    assert!(
        (x[i] - corner).norm() < 1e-9 && (x[j] - corner).norm() < 1e-9,
        "{:?} {:?}",
        x[i],
        x[j]
    );
    let panel_of = |p: usize| {
        let t = garment
            .mesh
            .triangles()
            .iter()
            .position(|t| t.contains(&p))
            .unwrap();
        garment.triangle_panel[t]
    };
    assert_ne!(panel_of(i), panel_of(j));
    // Moved apart, nothing touches.
    let mut apart = garment.clone();
    let right: Vec<usize> = (0..x.len()).filter(|&p| panel_of(p) == 1).collect();
    apart
        .mesh
        .translate_vertices(&right, cloth_core::math::Vec3::new(0.01, 0.0, 0.0));
    assert!(apart.find_touching().is_empty());
    assert!(apart.touching.is_empty());
}

#[test]
fn attachments_name_an_edge_and_the_way_it_is_free_to_move() {
    let extra = r#"
[[attachments]]
panel = "back"
edge = "top"
direction = [0, 0, 2]
"#;
    let pattern = Pattern::from_toml_str(&tube(32.4, extra), "tube.toml").unwrap();
    assert_eq!(pattern.attachments.len(), 1);
    let a = &pattern.attachments[0];
    assert_eq!((a.edge.panel, a.edge.edge), (1, 2));
    assert_eq!(a.direction, cloth_core::math::Vec3::z(), "normalised");
    for (bad, says) in [
        (
            extra.replace("\"top\"", "\"waist\""),
            "panel 'back' has no edge 'waist'",
        ),
        (
            extra.replace("[0, 0, 2]", "[0, 0, 0]"),
            "attachment 0: the direction is not a direction",
        ),
        (extra.replace("\"back\"", "\"side\""), "no panel named 'side'"),
    ] {
        let e = error(&tube(32.4, &bad));
        assert!(e.contains(says), "{e}");
    }
}
