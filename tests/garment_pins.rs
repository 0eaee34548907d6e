//! Pins by name in a garment scene: a small tube, sewn with no body, pinned by its top
//! edges hangs where the sewing left it; unpinned it falls.

use cloth::garment::sewing::{drape, sew};
use cloth::scene_file::{PreparedCloth, SceneFile};
use cloth::{math::Vec3, Interrupt};
use std::ops::ControlFlow;

/// The tube's scene (`assets/patterns/tube.toml`: two 10 x 20 cm panels 3 cm apart, sewn
/// at both sides) with `pins` (TOML array items), prepared.
fn tube(pins: &str) -> Result<(SceneFile, cloth::scene_file::Prepared), String> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/patterns");
    let text = format!(
        "[cloth.garment]\npattern = \"tube.toml\"\nedge_length = 0.02\npins = [{pins}]\n\
         [fabric]\npreset = \"cotton_poplin\"\n"
    );
    let scene = SceneFile::from_toml_str(&text, "scene.toml").map_err(|e| e.to_string())?;
    let prepared = scene.prepare("scene.toml", &dir).map_err(|e| e.to_string())?;
    Ok((scene, prepared))
}

/// Sews the tube, drapes it 40 steps, and returns the mean height's fall, m, and the
/// largest move of a pinned particle from where the sewing left it.
fn hang(pins: &str) -> (f64, f64, usize) {
    let (scene, prepared) = tube(pins).unwrap();
    let PreparedCloth::Garment { garment, fabrics } = prepared.cloth else {
        panic!("a garment")
    };
    let pinned = garment.pinned.len();
    let sewn = sew(
        &garment,
        &fabrics,
        prepared.bodies.clone(),
        &scene.sewing_settings(),
        &Interrupt::default(),
        |_, _, _| ControlFlow::Continue(()),
    )
    .unwrap();
    let draped = drape(
        &sewn,
        prepared.bodies.clone(),
        &scene.drape_settings(),
        &Interrupt::default(),
        |_, stats| {
            if stats.step < 40 {
                ControlFlow::Continue(())
            } else {
                ControlFlow::Break(())
            }
        },
    )
    .unwrap();
    let (before, after) = (sewn.welded.mesh.positions(), draped.simulation.positions());
    let mean = |x: &[Vec3]| x.iter().map(|p| p.z).sum::<f64>() / x.len() as f64;
    let moved = sewn
        .pins
        .iter()
        .map(|&i| (after[i] - before[i]).norm())
        .fold(0.0, f64::max);
    (mean(before) - mean(after), moved, pinned)
}

#[test]
fn a_tube_pinned_by_its_top_edges_hangs_where_it_was_sewn() {
    let (fell, moved, pinned) = hang(r#"{ panel = "front", edge = "top" }, { panel = "back", edge = 2 }"#);
    // Both top edges, 10 cm at 2 cm: 6 vertices each.
    assert_eq!(pinned, 12);
    assert_eq!(moved, 0.0, "a pinned particle moved");
    assert!(fell < 0.005, "the pinned tube's mean height fell {fell} m");
    let (free_fall, _, none) = hang("");
    assert_eq!(none, 0);
    // 40 steps is a fraction of a second of free fall: centimetres, not millimetres.
    assert!(free_fall > 0.02, "the free tube fell only {free_fall} m");
}

#[test]
fn a_whole_panel_can_be_pinned() {
    let (_, prepared) = tube(r#"{ panel = "back" }"#).unwrap();
    let PreparedCloth::Garment { garment, .. } = prepared.cloth else {
        panic!("a garment")
    };
    let back = garment.panel_names.iter().position(|n| n == "back").unwrap();
    let in_back = |&i: &usize| {
        garment
            .mesh
            .triangles()
            .iter()
            .zip(&garment.triangle_panel)
            .any(|(t, &p)| p == back && t.contains(&i))
    };
    assert!(garment.pinned.len() > 12);
    assert!(garment.pinned.iter().all(in_back));
}

/// Why the tube with `pins` is refused.
fn refused(pins: &str) -> String {
    match tube(pins) {
        Ok(_) => panic!("pins = [{pins}] accepted"),
        Err(e) => e,
    }
}

#[test]
fn a_pin_naming_what_the_pattern_lacks_says_what_it_has() {
    let e = refused(r#"{ panel = "sleeve" }"#);
    assert!(
        e.contains("cloth.garment.pins[0]")
            && e.contains("no panel named 'sleeve'")
            && e.contains("front, back"),
        "{e}"
    );
    let e = refused(r#"{ panel = "front", edge = "top" }, { panel = "front", edge = "neck" }"#);
    assert!(
        e.contains("cloth.garment.pins[1]")
            && e.contains("no edge 'neck'")
            && e.contains("hem, right, top, left"),
        "{e}"
    );
    let e = refused(r#"{ panel = "front", edge = 4 }"#);
    assert!(e.contains("no edge 4"), "{e}");
    let e = refused(r#"{ panel = "front", side = "top" }"#);
    assert!(e.contains("side"), "{e}");
}
