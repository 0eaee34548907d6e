//! A layer caught between a seam's sides: two panels lying on a block are sewn edge to
//! edge, and the edge of a third panel lies between them where they meet (as GarmentCode
//! hangs a hood's edge between the shoulders). The seam closes over it; the side farther
//! from the block is let through it, and the weld makes no crossing.

use cloth::collide::{Bodies, Body, TriSurface};
use cloth::garment::sewing::{sew, SewingSettings, Sewn};
use cloth::garment::{Garment, GarmentBuilder, Pattern};
use cloth::presets::FabricLibrary;
use cloth::{count_self_intersections, Interrupt, Vec3};
use nalgebra::Isometry3;
use std::ops::ControlFlow;
use std::sync::Arc;

/// `under` flat at z = 0 left of x = 0; `over` 1 cm above, right of x = 1 cm; their facing
/// edges sewn. The flap lies between, at z = 5 mm, from x = -3 cm to `flap_end` cm: over
/// `under` and, past x = 1 cm, under `over`.
fn pattern(with_flap: bool, flap_end: f64) -> Pattern {
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
    if with_flap {
        let width = flap_end + 3.0;
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
placement = {{ translation = [-3, 2, 0.5] }}
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

fn sew_flat(with_flap: bool, flap_end: f64) -> (Garment, Sewn) {
    let block = Body::new("block", TriSurface::cuboid(Vec3::new(0.3, 0.3, 0.05)).unwrap())
        .with_pose(Isometry3::translation(0.0, 0.05, -0.055))
        .unwrap();
    let bodies = Arc::new(Bodies::new(vec![block]));
    let garment = GarmentBuilder::new(pattern(with_flap, flap_end))
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
fn the_side_farther_from_the_body_is_let_through_a_caught_layer_and_the_weld_crosses_nothing() {
    let (garment, sewn) = sew_flat(true, 2.5);
    let caught = &sewn.report.caught;
    assert!(!caught.is_empty(), "nothing found across the seam");
    for c in caught {
        assert_eq!((c.layer.as_str(), c.passing.as_str()), ("flap", "over"), "{c:?}");
        assert!(c.seam.contains("panel 'under'"), "{}", c.seam);
        assert!(c.pairs > 0);
    }
    assert!(caught.iter().any(|c| c.passed.is_some()), "{caught:?}");
    assert_eq!(
        sewn.report.weld_crossings.found, 0,
        "{:?}",
        sewn.report.weld_crossings
    );
    let welded = &sewn.welded.mesh;
    let crossings = count_self_intersections(welded, &[], 1e-3, welded.positions());
    assert_eq!(crossings.count, 0, "{crossings:?}");
    // The flap ends on top: over the closed seam, wherever it lies above it.
    let x = welded.positions();
    let mut joins = vec![0; x.len()];
    for &p in &sewn.welded.particle_of {
        joins[p] += 1;
    }
    let flap = garment.panel_names.iter().position(|n| n == "flap").unwrap();
    let mut on_flap = vec![false; x.len()];
    for (t, tri) in welded.triangles().iter().enumerate() {
        if garment.triangle_panel[t] == flap {
            tri.iter().for_each(|&i| on_flap[i] = true);
        }
    }
    let seam: Vec<usize> = (0..x.len()).filter(|&i| joins[i] > 1).collect();
    let mut over = 0;
    for i in (0..x.len()).filter(|&i| on_flap[i]) {
        for &s in &seam {
            if (x[i] - x[s]).xy().norm() < 0.005 {
                assert!(
                    x[i].z > x[s].z,
                    "flap particle {i} at {:?} under seam particle {s} at {:?}",
                    x[i],
                    x[s]
                );
                over += 1;
            }
        }
    }
    assert!(over > 0, "the flap lies over no part of the seam");
}

#[test]
fn without_the_flap_nothing_is_caught() {
    let (_, sewn) = sew_flat(false, 0.0);
    assert!(sewn.report.caught.is_empty(), "{:?}", sewn.report.caught);
    assert_eq!(sewn.report.weld_crossings.found, 0);
}
