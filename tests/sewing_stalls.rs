//! Seams that stall: a tube sewn round a post thicker than it fits. The post's friction
//! is let go of, then the pull is raised until the cloth gives; held open against the
//! strongest pull, the seams are welded where they stand if near enough, zipped shut if
//! nothing lies between their sides however far apart, and the sewing fails naming the
//! seam and the body between if it lies between.

use cloth::collide::{Bodies, Body, TriSurface};
use cloth::garment::sewing::{sew, SewingSettings, Sewn, StallThen, FORCED_WELD};
use cloth::garment::{GarmentBuilder, GarmentError, HeldOpen, Pattern};
use cloth::presets::FabricLibrary;
use cloth::Interrupt;
use cloth::StrainReport;
use std::ops::ControlFlow;
use std::sync::Arc;

/// The post's radius, m.
const RADIUS: f64 = 0.06;

/// A tube of two 10 cm tall panels, each `width` cm round, wrapped 2 cm clear of the post.
fn tube(width: f64) -> Pattern {
    let r = 100.0 * RADIUS + 2.0;
    let half = width / 2.0;
    let text = format!(
        r#"
units = "cm"
[[panels]]
name = "front"
outline = [
    {{ start = [-{half}, 0], name = "hem" }},
    {{ start = [{half}, 0], name = "right" }},
    {{ start = [{half}, 10], name = "top" }},
    {{ start = [-{half}, 10], name = "left" }},
]
placement = {{ rotation = [90, 0, 0], translation = [0, -{r}, -5], wrap = {{ radius = {r} }} }}

[[panels]]
name = "back"
outline = [
    {{ start = [-{half}, 0], name = "hem" }},
    {{ start = [{half}, 0], name = "right" }},
    {{ start = [{half}, 10], name = "top" }},
    {{ start = [-{half}, 10], name = "left" }},
]
placement = {{ rotation = [90, 0, 180], translation = [0, {r}, -5], wrap = {{ radius = {r} }} }}

[[seams]]
a = {{ panel = "front", edge = "right" }}
b = {{ panel = "back", edge = "left" }}

[[seams]]
a = {{ panel = "front", edge = "left" }}
b = {{ panel = "back", edge = "right" }}
"#
    );
    Pattern::from_toml_str(&text, "tube.toml").unwrap()
}

/// Sews a tube `fit` times the post's girth (at the cloth's contact distance) round it.
fn sew_tube(fit: f64) -> Result<Sewn, GarmentError> {
    let post = Body::new("post", TriSurface::cylinder(RADIUS, 0.15, 64).unwrap());
    let thickness = post.thickness();
    let bodies = Arc::new(Bodies::new(vec![post]));
    let girth = std::f64::consts::TAU * (RADIUS + thickness);
    sew_in_cotton(tube(100.0 * fit * girth / 2.0), bodies)
}

/// Sews `pattern`'s two panels of cotton poplin at 2 cm round `bodies`, unobserved.
fn sew_in_cotton(pattern: Pattern, bodies: Arc<Bodies>) -> Result<Sewn, GarmentError> {
    let garment = GarmentBuilder::new(pattern).edge_length(0.02).build().unwrap();
    let fabric = FabricLibrary::builtin().fabric("cotton_poplin").unwrap();
    sew(
        &garment,
        &[fabric.clone(), fabric],
        bodies,
        &SewingSettings::default(),
        &Interrupt::default(),
        |_, _, _| ControlFlow::Continue(()),
    )
}

#[test]
fn a_tube_a_little_tight_closes_once_the_pull_is_raised() {
    // 8 % short of the post: the pull at its first strength leaves the seams open. The
    // first stall lets go of the post's friction, and the pull raised from the next
    // stretches the cloth until they close.
    let sewn = sew_tube(0.92).unwrap();
    let stalls = &sewn.report.stalls;
    let (first, pulled) = stalls.split_first().expect("no stall");
    assert_eq!(first.then, StallThen::FrictionReleased, "{first:?}");
    assert_eq!(first.pull_factor, 1.0);
    assert!(!pulled.is_empty(), "{stalls:?}");
    assert!(pulled.iter().all(|s| s.then == StallThen::Pulled), "{stalls:?}");
    assert!(pulled
        .windows(2)
        .all(|w| w[1].pull_factor > w[0].pull_factor && w[1].gap < w[0].gap));
    assert!(sewn.report.max_gap < SewingSettings::default().gap_tolerance);
}

#[test]
fn a_tube_too_tight_to_close_is_welded_where_it_stalls() {
    // 15 % short: the cloth stiffens past what even the strongest pull stretches it by,
    // and the seams stop a few millimetres open: welded there.
    let sewn = sew_tube(0.85).unwrap();
    let last = sewn.report.stalls.last().expect("stalled");
    assert_eq!(last.then, StallThen::Welded, "{last:?}");
    assert_eq!(last.pull_factor, 1024.0);
    assert!(last.seam.contains("panel 'front'"), "{}", last.seam);
    // Open past the tolerance, but by less than the weld allows (a fraction of the pairs'
    // spacing, at most the edge length).
    let gap = sewn.report.max_gap;
    assert!(
        gap > SewingSettings::default().gap_tolerance && gap <= FORCED_WELD * 0.02,
        "{gap}"
    );
}

#[test]
fn a_tube_far_too_tight_with_nothing_between_its_sides_is_zipped_shut() {
    // 30 % short: still centimetres open under the strongest pull, too far to weld where
    // they stand; the line between the sides clears the post (cloth round a post of 6 cm,
    // 14 mm apart), so they are drawn together and welded.
    let sewn = sew_tube(0.7).unwrap();
    let last = sewn.report.stalls.last().expect("stalled");
    assert_eq!(last.then, StallThen::Zipped, "{last:?}");
    assert_eq!(last.pull_factor, 1024.0);
    assert!(last.seam.contains("panel 'front'") && last.seam.contains("panel 'back'"));
    assert!(last.gap > FORCED_WELD * 0.02, "{last:?}");
    // Closed, within what a weld where they stand allows.
    assert!(
        sewn.report.max_gap <= FORCED_WELD * 0.02,
        "{}",
        sewn.report.max_gap
    );
    // Round the post, not through it: every particle outside it, and the cloth stretched
    // as far as its girth asks (a tube 70 % of it: 43 % longer round).
    let x = sewn.welded.mesh.positions();
    let nearest = x.iter().map(|p| p.xy().norm()).fold(f64::INFINITY, f64::min);
    assert!(nearest > RADIUS, "{nearest}");
    let strain = StrainReport::new(&sewn.welded.mesh, x);
    assert!(strain.p99_warp.max(strain.p99_weft) > 30.0, "{strain:?}");
}

#[test]
fn a_tube_far_too_small_with_nothing_between_its_sides_is_zipped_however_far_apart() {
    // 40 % short: the sides stop farther apart than a weld where they stand reaches (and
    // a spacing), the line between them still clear of the post. Nothing lies between,
    // so they are zipped all the same, and the stall says what closing asked of the way
    // round the post: about the girth over 60 % of it, 67 % (a little less, the open
    // pairs' gaps being chords).
    let sewn = sew_tube(0.6).unwrap();
    let last = sewn.report.stalls.last().expect("stalled");
    assert_eq!(last.then, StallThen::Zipped, "{last:?}");
    assert_eq!(last.pull_factor, 1024.0);
    assert!(last.gap > 0.02, "{last:?}");
    let asks = last.ring_asks.expect("a ring round the post");
    assert!(asks > 0.5 && asks < 0.67, "{asks}");
    // Welded when drawn shut: what one step's solve after the last draw lets the cloth
    // pull the sides apart again, less than half what the strongest pull left open.
    assert!(
        sewn.report.max_gap < 0.5 * last.gap,
        "{} of {}",
        sewn.report.max_gap,
        last.gap
    );
    // Round the post, not through it, and stretched as far as closing asked.
    let x = sewn.welded.mesh.positions();
    let nearest = x.iter().map(|p| p.xy().norm()).fold(f64::INFINITY, f64::min);
    assert!(nearest > RADIUS, "{nearest}");
    let strain = StrainReport::new(&sewn.welded.mesh, x);
    assert!(strain.p99_warp.max(strain.p99_weft) > 50.0, "{strain:?}");
}

#[test]
fn a_tube_half_the_posts_girth_fails_saying_the_post_lies_between_its_sides() {
    // Centimetres open across the post: the line between the widest pair's sides runs
    // through it, and the failure says the garment is too small to go round it.
    match sew_tube(0.5) {
        Err(e @ GarmentError::Stalled { .. }) => {
            let GarmentError::Stalled {
                gap_mm,
                held_by,
                others_held_by,
                ..
            } = &e
            else {
                unreachable!()
            };
            assert!(*gap_mm > 40.0, "{gap_mm}");
            assert_eq!(*held_by, HeldOpen::Body);
            assert!(e.to_string().contains("the body lies between its sides"), "{e}");
            // The other side seam is open across the post as well, and said to be, apart.
            assert_eq!(*others_held_by, HeldOpen::Body, "{e}");
            assert!(
                e.to_string().ends_with(
                    "; between the sides of the other seams' pairs too far apart to weld lies the body"
                ),
                "{e}"
            );
        }
        other => panic!("{:?}", other.map(|s| s.report)),
    }
}

/// Two flat panels 10 cm tall, 7 cm in front of and behind a post of 4 cm radius, from
/// 20 cm left of its axis to 8 cm right of it: their hems sewn to each other (the post
/// between the sides of the hem's middle pairs, not its end pairs) and their left sides
/// too, as GarmentCode's flounce beside one leg reaches past the other.
fn flap_past_a_post() -> Result<Sewn, GarmentError> {
    // The back panel is turned half round about the vertical, so its outline runs from
    // the world's right to its left: it spans -8 to 20 cm in its own frame.
    let panel = |name: &str, turn: f64, y: f64, from: f64, to: f64| {
        format!(
            r#"
[[panels]]
name = "{name}"
outline = [
    {{ start = [{from}, 0], name = "hem" }},
    {{ start = [{to}, 0], name = "right" }},
    {{ start = [{to}, 10], name = "top" }},
    {{ start = [{from}, 10], name = "left" }},
]
placement = {{ rotation = [90, 0, {turn}], translation = [0, {y}, -5] }}
"#
        )
    };
    let text = format!(
        "units = \"cm\"\n{}{}\n\
         [[seams]]\na = {{ panel = \"front\", edge = \"hem\" }}\nb = {{ panel = \"back\", edge = \"hem\" }}\n\n\
         [[seams]]\na = {{ panel = \"front\", edge = \"left\" }}\nb = {{ panel = \"back\", edge = \"right\" }}\n",
        panel("front", 0.0, -7.0, -20.0, 8.0),
        panel("back", 180.0, 7.0, -8.0, 20.0),
    );
    let pattern = Pattern::from_toml_str(&text, "flap.toml").unwrap();
    let post = Body::new("post", TriSurface::cylinder(0.04, 0.15, 64).unwrap());
    sew_in_cotton(pattern, Arc::new(Bodies::new(vec![post])))
}

#[test]
fn a_seam_placed_across_a_post_between_clear_ends_is_sewn_again_from_its_joined_end_beside_it() {
    // Pulled straight, the hem closes on both sides of the post and stalls with the post
    // between its sides. They were not clear of it as placed, but the hem's ends were,
    // and its left end is joined to the left side's seam: the sewing starts over with the
    // left side drawn shut first and the hem pulled from there a pair at a time, and it
    // closes beside the post, the panels drawn off it to the left.
    let sewn = flap_past_a_post().unwrap();
    let stalls = &sewn.report.stalls;
    let hem = "panel 'front', edge 'hem' (0) to panel 'back', edge 'hem' (0)";
    let then = |then: StallThen| -> Vec<_> { stalls.iter().filter(|s| s.then == then).collect() };
    let over = then(StallThen::StartedOver);
    assert_eq!(over.len(), 1, "{stalls:?}");
    assert_eq!(over[0].seam, hem);
    assert!(over[0].gap > 0.04, "{:?}", over[0]);
    // The hem alone is pulled from its end, from where it was placed, 14 cm open.
    let from_end = then(StallThen::FromClearEnd);
    assert_eq!(from_end.len(), 1, "{stalls:?}");
    assert_eq!(from_end[0].seam, hem);
    assert!((from_end[0].gap - 0.14).abs() < 1e-6, "{:?}", from_end[0]);
    assert_eq!(from_end[0].step, over[0].step);
    assert!(
        sewn.report.max_gap <= FORCED_WELD * 0.02,
        "{}",
        sewn.report.max_gap
    );
    // Beside the post, not round it: all the cloth left of its axis (placed, it reached
    // 8 cm right of it), none in it.
    let x = sewn.welded.mesh.positions();
    let right = x.iter().map(|p| p.x).fold(f64::NEG_INFINITY, f64::max);
    assert!(right < 0.0, "cloth {right} m right of the post's axis");
    let inside = x
        .iter()
        .filter(|p| p.x.hypot(p.y) < 0.04 && p.z.abs() < 0.15)
        .count();
    assert_eq!(inside, 0);
}
