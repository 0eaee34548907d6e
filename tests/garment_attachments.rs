//! GarmentCode's attached edges: a tiered skirt whose tiers are placed far out and below
//! its waist is sewn up to the waist, held there, instead of all of it meeting near the
//! tiers' mass. (Its own file: the designs draped in `garmentcode_drapes` run alongside
//! each other, not alongside this.)

mod common;

use cloth::garment::sewing::sew;
use cloth::scene_file::PreparedCloth;
use cloth::{math::Vec3, Interrupt};
use std::ops::ControlFlow;

/// Sews GarmentCode's rand_1_072 at 3 cm for 40 steps, its waist's attachments given to
/// the sewing or not; returns how far the waist's lowest particle went below the lowest
/// placed one, m, at most, and the number of waist particles.
fn tiered_waist_sinks(attached: bool) -> (f64, usize) {
    let (scene, prepared) = common::garmentcode_scene("rand_1_072", 0.03);
    let PreparedCloth::Garment { mut garment, fabrics } = prepared.cloth else {
        panic!("a garment")
    };
    let waist: Vec<usize> = garment
        .attached
        .iter()
        .flat_map(|(particles, d)| {
            assert_eq!(*d, Vec3::z(), "only the waist is labelled");
            particles.iter().copied()
        })
        .collect();
    let lowest = |x: &[Vec3]| waist.iter().map(|&i| x[i].z).fold(f64::INFINITY, f64::min);
    let placed = lowest(garment.mesh.positions());
    if !attached {
        garment.attached.clear();
    }
    let mut sank = 0.0f64;
    let sewn = sew(
        &garment,
        &fabrics,
        prepared.bodies.clone(),
        &scene.sewing_settings(),
        &Interrupt::default(),
        |sim, stats, _| {
            sank = sank.max(placed - lowest(sim.positions()));
            if stats.step < 40 {
                ControlFlow::Continue(())
            } else {
                ControlFlow::Break(())
            }
        },
    );
    assert!(matches!(sewn, Err(cloth::garment::GarmentError::Stopped { .. })));
    (sank, waist.len())
}

#[test]
fn a_tiered_skirt_placed_below_its_waist_is_sewn_up_to_the_waist_where_it_is_held() {
    // GarmentCode places the tiers far out and below the waist, the widest lowest: pulled
    // together freely, everything meets near the tiers' mass and the waist goes down the
    // legs; held at the waist, the tiers come up to it.
    let (held, particles) = tiered_waist_sinks(true);
    let (free, _) = tiered_waist_sinks(false);
    println!("{particles} waist particles; the lowest sank {held} m held, {free} m free");
    assert!(particles > 20, "{particles}");
    assert!(held < 0.06, "held waist sank {held} m");
    assert!(free > 0.2, "free waist sank only {free} m");
}
