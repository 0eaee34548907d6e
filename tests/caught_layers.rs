//! A layer caught between a seam's sides: two panels lying on a block are sewn edge to
//! edge, and the edge of a third panel lies between them where they meet (as GarmentCode
//! hangs a hood's edge between the shoulders). The seam closes over it; the side that
//! puts it where the rest of it lies is let through it (the farther from the block when
//! it lies over the seam's panels, the nearer when under), and the weld makes no crossing.

use cloth::collide::{Bodies, Body, TriSurface};
use cloth::garment::sewing::{sew, SewingSettings, Sewn};
use cloth::garment::{Garment, GarmentBuilder, Pattern};
use cloth::presets::FabricLibrary;
use cloth::{count_self_intersections, math::Vec3, Interrupt};
use nalgebra::Isometry3;
use std::ops::ControlFlow;
use std::sync::Arc;

/// `under` flat at z = 0 left of x = 0; `over` 1 cm above, right of x = 1 cm; their facing
/// edges sewn. The flap lies between, at z = 5 mm, from x = `flap` cm to the second:
/// over `under` and, past x = 1 cm, under `over`.
fn pattern(flap: Option<[f64; 2]>) -> Pattern {
    let square = |name: &str| {
        format!(
            r#"
[[panels]]
name = "{name}"
outline = [
    {{ start = [0, 0], name = "bottom" }},
    {{ start = [10, 0], name = "right" }},
    {{ start = [10, 10], name = "top" }},
    {{ start = [0, 10], name = "left" }},
]
"#
        )
    };
    let mut text = String::from("units = \"cm\"\n");
    text += &square("under");
    text += "placement = { translation = [-10, 0, 0] }\n";
    text += &square("over");
    text += "placement = { translation = [1, 0, 1] }\n";
    if let Some([flap_start, flap_end]) = flap {
        let width = flap_end - flap_start;
        text += &format!(
            r#"
[[panels]]
name = "flap"
outline = [
    {{ start = [0, 0], name = "bottom" }},
    {{ start = [{width}, 0], name = "right" }},
    {{ start = [{width}, 6], name = "top" }},
    {{ start = [0, 6], name = "left" }},
]
placement = {{ translation = [{flap_start}, 2, 0.5] }}
"#
        );
    }
    text += r#"
[[seams]]
a = { panel = "under", edge = "right" }
b = { panel = "over", edge = "left" }
"#;
    Pattern::from_toml_str(&text, "caught.toml").unwrap()
}

fn sew_flat(flap: Option<[f64; 2]>) -> (Garment, Sewn) {
    let block = Body::new("block", TriSurface::cuboid(Vec3::new(0.3, 0.3, 0.05)).unwrap())
        .with_pose(Isometry3::translation(0.0, 0.05, -0.055))
        .unwrap();
    let bodies = Arc::new(Bodies::new(vec![block]));
    let garment = GarmentBuilder::new(pattern(flap))
        .edge_length(0.01)
        .build()
        .unwrap();
    let fabric = FabricLibrary::builtin().fabric("cotton_poplin").unwrap();
    let fabrics = vec![fabric; garment.panel_names.len()];
    let sewn = sew(
        &garment,
        &fabrics,
        bodies,
        &SewingSettings::default(),
        &Interrupt::default(),
        |_, _, _| ControlFlow::Continue(()),
    )
    .unwrap();
    (garment, sewn)
}

#[test]
fn the_side_farther_from_the_body_is_let_through_a_layer_lying_over_the_seams_panels() {
    // Mostly over `under`.
    let (garment, sewn) = sew_flat(Some([-3.0, 2.5]));
    assert_flap_let_through(&garment, &sewn, "over", Above::Over);
}

#[test]
fn the_side_nearer_the_body_is_let_through_a_layer_lying_under_the_seams_panels() {
    // Mostly under `over`: its edge caught between the sides, the rest under the seam.
    let (garment, sewn) = sew_flat(Some([-0.5, 4.5]));
    assert_flap_let_through(&garment, &sewn, "under", Above::Under);
}

#[test]
fn a_layer_still_passing_when_the_closed_seams_window_ends_gets_another() {
    // Wider under `over`: still on its way through the seam 12 steps after it was found
    // (it was welded over then, 34 crossings, before closed seams got another window for
    // a layer still passing); through at step 44.
    let (garment, sewn) = sew_flat(Some([-0.5, 6.5]));
    assert_flap_let_through(&garment, &sewn, "under", Above::Under);
}

/// The flap was found caught in the seam, `passing` let through it until apart, the weld
/// crossed nothing, and the flap ends `above` the closed seam.
fn assert_flap_let_through(garment: &Garment, sewn: &Sewn, passing: &str, above: Above) {
    let caught = &sewn.report.caught;
    assert!(!caught.is_empty(), "nothing found across the seam");
    for c in caught {
        assert_eq!((c.layer.as_str(), c.passing.as_str()), ("flap", passing), "{c:?}");
        assert!(c.seam.contains("panel 'under'"), "{}", c.seam);
        assert!(c.pairs > 0);
    }
    assert!(caught.iter().any(|c| c.passed.is_some()), "{caught:?}");
    assert_eq!(
        sewn.report.weld_crossings.found, 0,
        "{:?}",
        sewn.report.weld_crossings
    );
    assert_flap_ends(garment, sewn, above);
}

/// Which of the flap and the closed seam ends on top where one lies over the other.
#[derive(Debug, PartialEq)]
enum Above {
    Over,
    Under,
}

/// The weld crosses nothing, and the flap ends `above` the closed seam wherever one lies
/// over the other (not beside it, level with it).
fn assert_flap_ends(garment: &Garment, sewn: &Sewn, above: Above) {
    let welded = &sewn.welded.mesh;
    let crossings = count_self_intersections(welded, &[], 1e-3, welded.positions());
    assert_eq!(crossings.count, 0, "{crossings:?}");
    let x = welded.positions();
    let mut joins = vec![0; x.len()];
    for &p in &sewn.welded.particle_of {
        joins[p] += 1;
    }
    let flap = garment.panel_names.iter().position(|n| n == "flap").unwrap();
    let seam: Vec<usize> = (0..x.len()).filter(|&i| joins[i] > 1).collect();
    // The flap's height over each seam particle it lies over or under: on the flap's
    // triangle whose plan holds the particle's.
    let mut overlapping = 0;
    for (t, tri) in welded.triangles().iter().enumerate() {
        if garment.triangle_panel[t] != flap {
            continue;
        }
        let [a, b, c] = tri.map(|i| x[i]);
        let area = (b - a).xy().perp(&(c - a).xy());
        // Seen edge-on from above, it lies over nothing.
        if area.abs() < 1e-12 {
            continue;
        }
        for &s in &seam {
            let p = x[s];
            let w = [
                (b - p).xy().perp(&(c - p).xy()) / area,
                (c - p).xy().perp(&(a - p).xy()) / area,
                (a - p).xy().perp(&(b - p).xy()) / area,
            ];
            if w.iter().any(|&w| w < 0.0) {
                continue;
            }
            let height = w[0] * a.z + w[1] * b.z + w[2] * c.z;
            assert_eq!(
                height > p.z,
                above == Above::Over,
                "the flap at {height} m over seam particle {s} at {p:?}"
            );
            overlapping += 1;
        }
    }
    assert!(overlapping > 0, "the flap lies over or under no part of the seam");
}

#[test]
fn without_the_flap_nothing_is_caught() {
    let (_, sewn) = sew_flat(None);
    assert!(sewn.report.caught.is_empty(), "{:?}", sewn.report.caught);
    assert_eq!(sewn.report.weld_crossings.found, 0);
}
