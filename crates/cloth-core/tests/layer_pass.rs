//! Cloth let through other cloth (a layer caught between a seam's sides, let through by
//! one of them): the two pass through each other, the pass ends once they are through and
//! apart, and from then on they collide as any cloth does.

use cloth_core::{
    math::Vec3, ClothMesh, Fabric, GridBuilder, LayerPass, Pin, Simulation, SimulationBuilder, SolverSettings,
};

/// A square sheet of `n` x `n` particles, `size` wide, its corner at `corner`.
fn sheet(n: usize, size: f64, corner: Vec3) -> ClothMesh {
    GridBuilder::new(n, n)
        .size(size, size)
        .origin(corner)
        .build()
        .unwrap()
}

/// A layer 0.3 m square at z = 0 held by its border, and a sheet 0.1 m square 1 cm above
/// its middle moving down at 0.3 m/s, gravity off; and the layer's particle count (they
/// come first).
fn sheet_onto_layer() -> (Simulation, usize) {
    // The sheet's grid is offset from the layer's, so no particle falls on an edge.
    let pieces = [
        sheet(21, 0.3, Vec3::zeros()),
        sheet(11, 0.1, Vec3::new(0.1037, 0.1041, 0.01)),
    ];
    let layer = pieces[0].vertex_count();
    let mesh = ClothMesh::join(&pieces).unwrap();
    let n = mesh.vertex_count();
    let border = (0..layer).filter(|&i| {
        let (r, c) = (i / 21, i % 21);
        r == 0 || c == 0 || r == 20 || c == 20
    });
    let v = (0..n)
        .map(|i| {
            if i < layer {
                Vec3::zeros()
            } else {
                Vec3::new(0.0, 0.0, -0.3)
            }
        })
        .collect();
    let sim = SimulationBuilder::new(mesh, Fabric::cotton_like())
        .settings(SolverSettings {
            time_step: 1.0 / 60.0,
            gravity: Vec3::zeros(),
            ..SolverSettings::default()
        })
        .pins(border.map(Pin::fixed))
        .velocities(v)
        .build()
        .unwrap();
    (sim, layer)
}

/// [`sheet_onto_layer`], the sheet let through the layer.
fn sheet_let_through_layer() -> (Simulation, usize) {
    let (mut sim, layer) = sheet_onto_layer();
    let n = sim.positions().len();
    sim.add_layer_passes([LayerPass {
        layer: (0..layer).collect(),
        side: (layer..n).collect(),
    }])
    .unwrap();
    (sim, layer)
}

fn highest(x: &[Vec3]) -> f64 {
    x.iter().map(|p| p.z).fold(f64::MIN, f64::max)
}

fn lowest(x: &[Vec3]) -> f64 {
    x.iter().map(|p| p.z).fold(f64::MAX, f64::min)
}

#[test]
fn a_sheet_let_through_a_layer_passes_it_and_collides_with_it_once_apart() {
    let (mut sim, layer) = sheet_let_through_layer();
    for _ in 0..20 {
        sim.step().unwrap();
    }
    let x = sim.positions();
    assert!(
        highest(&x[layer..]) < lowest(&x[..layer]) - 0.01,
        "the sheet is not through: its top at {}, the layer's lowest at {}",
        highest(&x[layer..]),
        lowest(&x[..layer])
    );
    let pass = &sim.layer_passes()[0];
    assert!(pass.crossed, "never seen crossing");
    let ended = pass.ended.expect("the pass still holds");
    assert!(ended < 20, "{ended}");
    // Thrown back up, it meets the layer from below and stays there.
    let mut v = sim.velocities().to_vec();
    v[layer..].iter_mut().for_each(|v| *v = Vec3::new(0.0, 0.0, 0.3));
    sim.set_velocities(&v).unwrap();
    for _ in 0..40 {
        sim.step().unwrap();
        assert_eq!(sim.self_intersections().count, 0, "step {}", sim.step_count());
    }
    let x = sim.positions();
    let mean = |s: &[Vec3]| s.iter().map(|p| p.z).sum::<f64>() / s.len() as f64;
    let middle: Vec<Vec3> = x[..layer]
        .iter()
        .filter(|p| (0.1..0.2).contains(&p.x) && (0.1..0.2).contains(&p.y))
        .copied()
        .collect();
    assert!(
        mean(&x[layer..]) < mean(&middle),
        "the sheet went back through: {} against the layer's {}",
        mean(&x[layer..]),
        mean(&middle)
    );
    // It came up against the layer, not short of it.
    assert!(
        highest(&x[layer..]) > mean(&middle) - 0.005,
        "the sheet stopped short: its top at {}",
        highest(&x[layer..])
    );
}

#[test]
fn without_a_pass_the_sheet_lands_on_the_layer() {
    let (mut sim, layer) = sheet_onto_layer();
    for _ in 0..20 {
        sim.step().unwrap();
        assert_eq!(sim.self_intersections().count, 0, "step {}", sim.step_count());
    }
    let x = sim.positions();
    let under: Vec<&Vec3> = x[..layer]
        .iter()
        .filter(|p| (0.11..0.19).contains(&p.x) && (0.11..0.19).contains(&p.y))
        .collect();
    assert!(lowest(&x[layer..]) > under.iter().map(|p| p.z).fold(f64::MIN, f64::max) - 1e-3);
    assert!(sim.layer_passes().is_empty());
}

#[test]
fn a_pass_ended_by_its_caller_holds_no_more() {
    let (mut sim, layer) = sheet_let_through_layer();
    sim.end_layer_passes();
    assert_eq!(sim.layer_passes()[0].ended, Some(0));
    assert!(!sim.layer_passes()[0].crossed);
    for _ in 0..20 {
        sim.step().unwrap();
        assert_eq!(sim.self_intersections().count, 0, "step {}", sim.step_count());
    }
    assert!(lowest(&sim.positions()[layer..]) > -0.01);
}

#[test]
fn the_cloth_across_a_pair_is_the_layer_between_its_particles() {
    // Three sheets 1 cm apart: a pair from the top sheet's middle to the bottom one's
    // crosses the middle sheet; a pair beside it, and a pair within one sheet, do not.
    let pieces = [
        sheet(11, 0.1, Vec3::new(0.0, 0.0, 0.01)),
        sheet(11, 0.1, Vec3::new(0.0037, 0.0041, 0.0)),
        sheet(21, 0.2, Vec3::new(0.0, 0.0, -0.01)),
    ];
    let (top, middle) = (pieces[0].vertex_count(), pieces[1].vertex_count());
    let mesh = ClothMesh::join(&pieces).unwrap();
    let sim = SimulationBuilder::new(mesh, Fabric::cotton_like())
        .build()
        .unwrap();
    let x = sim.positions();
    let bottom = top + middle;
    let above = 5 * 11 + 5;
    let below = bottom
        + (0..441)
            .find(|&i| (x[bottom + i] - x[above]).xy().norm() < 1e-9)
            .unwrap();
    let beside = bottom
        + (0..441)
            .find(|&i| x[bottom + i].x > 0.18 && x[bottom + i].y > 0.18)
            .unwrap();
    let across = sim
        .cloth_across(&[
            [above, below],
            [above, beside],
            [above, above + 1],
            [below, above],
        ])
        .unwrap();
    let crossed: Vec<usize> = across.iter().map(|&(k, _)| k).collect();
    assert!(
        !crossed.is_empty() && crossed.iter().all(|&k| k == 0 || k == 3),
        "{across:?}"
    );
    for &(_, t) in &across {
        let tri = sim.mesh().triangles()[t];
        assert!(tri.iter().all(|&i| (top..bottom).contains(&i)), "{tri:?}");
    }
    assert!(crossed.contains(&3), "the pair either way round");
}

#[test]
fn particles_not_of_the_cloth_are_refused_and_nothing_is_added() {
    let (mut sim, layer) = sheet_onto_layer();
    let n = sim.positions().len();
    let refused = sim.add_layer_passes([
        LayerPass {
            layer: (0..layer).collect(),
            side: vec![layer],
        },
        LayerPass {
            layer: vec![0],
            side: vec![n],
        },
    ]);
    assert!(refused.unwrap_err().to_string().contains("layer_passes"));
    assert!(sim.layer_passes().is_empty());
    let refused = sim.cloth_across(&[[0, n + 3]]);
    assert!(refused.unwrap_err().to_string().contains(&(n + 3).to_string()));
}
