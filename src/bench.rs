//! The standard benchmark scenes behind `cloth bench`: a fixed set of runs whose time per
//! step and CG iterations are printed as JSON, to track speed over time.

use crate::scene_file::{ClothSpec, Prepared, PreparedCloth, SceneFile, Silent};
use cloth_collide::{Bodies, Body, TriSurface};
use cloth_core::{
    math::Vec3, Fabric, GridBuilder, Interrupt, Pin, SelfCollision, Simulation, SimulationBuilder,
    SolverSettings,
};
use cloth_garment::sewing::{drape_simulation, sew, Sewn};
use serde::Serialize;
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

/// One benchmark's figures.
#[derive(Debug, Clone, Serialize)]
pub struct BenchResult {
    pub name: String,
    pub particles: usize,
    pub steps: usize,
    /// Wall time per step, ms.
    pub median_ms_per_step: f64,
    pub median_cg_iterations: usize,
    /// Medians over the steps of the cloth's contacts with itself and of the wall time in
    /// self-collision, ms.
    pub median_self_contacts: usize,
    pub median_self_collision_ms: f64,
}

/// A whole run to rest: each stage's steps and wall time.
#[derive(Debug, Clone, Serialize)]
pub struct ToRestResult {
    pub name: &'static str,
    pub particles: usize,
    pub sewing_steps: u64,
    pub sewing_seconds: f64,
    pub drape_steps: u64,
    pub drape_seconds: f64,
}

/// What `cloth bench` measures: steps of each scene, and the main job from placed panels
/// to rest.
#[derive(Debug, Clone, Serialize)]
pub struct Benchmarks {
    pub scenes: Vec<BenchResult>,
    pub to_rest: Vec<ToRestResult>,
}

/// Runs the standard scenes for `steps` steps each: the source's 110 x 110 hanging sheet,
/// a 60 x 60 sheet dropped on a sphere, a 110 x 110 one landed on it, and the basic dress
/// draping on the default mannequin at about 12,000 particles (timed after it is sewn),
/// with self-collision (as everywhere, by default) and without; and the main job, the
/// dress scene from its placed panels to rest, run as `cloth run` runs it (without writing
/// outputs). `quick` runs them at about a tenth of the particles, for a smoke test.
pub fn standard_benchmarks(steps: usize, quick: bool) -> Result<Benchmarks, String> {
    let e = |e: &dyn std::fmt::Display| e.to_string();
    let mut results = Vec::new();

    let side = if quick { 35 } else { 110 };
    results.push(time_steps("hanging_sheet".into(), hanging_sheet(side)?, steps)?);

    let sim = sheet_on_sphere(if quick { 20 } else { 60 }).map_err(|x| e(&x))?;
    results.push(time_steps("sheet_on_sphere".into(), sim, steps)?);

    // The source's model size landed on the sphere: steps with the sheet lying on it, where
    // contacts, friction and the cloth's collision with itself all work.
    let mut sim = sheet_on_sphere(side).map_err(|x| e(&x))?;
    for _ in 0..LANDING_STEPS {
        sim.step().map_err(|x| format!("sphere_drop: {x}"))?;
    }
    results.push(time_steps(format!("sphere_drop_{side}x{side}"), sim, steps)?);

    // The main job's scene, run as `cloth run` runs it (without writing outputs).
    let dress = DressScene::load(if quick { Some(0.035) } else { None })?;
    let run = dress
        .prepare()?
        .run(&dress.scene, None, &mut Silent)
        .map_err(|x| e(&x))?;
    let report = &run.report;
    if !run.finished() {
        return Err(format!("dress_to_rest: the run ended {:?}", report.outcome));
    }
    let stage = |name: &str| report.stages.iter().find(|s| s.stage == name);
    let (Some(sewing), Some(draping)) = (stage("sewing"), stage("draping")) else {
        return Err("dress_to_rest: the run has no sewing and draping stages".into());
    };
    let to_rest = vec![ToRestResult {
        name: "dress_to_rest",
        particles: report.particles,
        sewing_steps: sewing.steps,
        sewing_seconds: sewing.seconds,
        drape_steps: draping.steps,
        drape_seconds: draping.seconds,
    }];

    // The drape's steps timed from the dress sewn again.
    let (sewn, bodies) = dress.sew()?;
    // Draped with self-collision and without, from the same sewn dress.
    for (name, self_collision) in [
        ("dress_drape", SelfCollision::default()),
        ("dress_drape_without_self_collision", SelfCollision::off()),
    ] {
        let solver = SolverSettings {
            self_collision,
            ..SolverSettings::default()
        };
        let sim = drape_simulation(&sewn, bodies.clone(), solver, 0.0).map_err(|x| e(&x))?;
        results.push(time_steps(name.into(), sim, steps)?);
    }
    Ok(Benchmarks {
        scenes: results,
        to_rest,
    })
}

/// The main job's dress scene, its edge length possibly changed.
struct DressScene {
    scene: SceneFile,
    dir: PathBuf,
}

impl DressScene {
    fn load(edge_length: Option<f64>) -> Result<Self, String> {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/dress.toml");
        let (mut scene, dir) = SceneFile::from_path(&path).map_err(|x| x.to_string())?;
        if let (Some(h), ClothSpec::Garment { edge_length, .. }) = (edge_length, &mut scene.cloth) {
            *edge_length = h;
        }
        Ok(Self { scene, dir })
    }

    fn prepare(&self) -> Result<Prepared, String> {
        (self.scene)
            .prepare("dress.toml", &self.dir)
            .map_err(|x| x.to_string())
    }

    /// The dress sewn as its scene's sewing stage sews it, and the bodies it is on.
    fn sew(&self) -> Result<(Sewn, Arc<Bodies>), String> {
        let prepared = self.prepare()?;
        let PreparedCloth::Garment { garment, fabrics } = prepared.cloth else {
            return Err("the dress scene is not a garment".into());
        };
        let bodies = prepared.bodies;
        let sewn = sew(
            &garment,
            &fabrics,
            bodies.clone(),
            &self.scene.sewing_settings(),
            &Interrupt::default(),
            |_, _, _| ControlFlow::Continue(()),
        )
        .map_err(|x| x.to_string())?;
        Ok((sewn, bodies))
    }
}

/// Steps of the sheet dropped on the sphere before its steps are timed: by then it lies
/// on the sphere, its sides still swinging down.
const LANDING_STEPS: usize = 40;

/// How a step's cost grows with the particles, from about 3,000 to 200,000.
#[derive(Debug, Clone, Serialize)]
pub struct Scaling {
    /// The hanging sheet at 55, 110, 224 and 447 particles a side.
    pub sheet: Vec<BenchResult>,
    /// The main job's dress at 2, 1, 1/2 and 1/4 times its edge length.
    pub dress: Vec<DressScaling>,
}

/// The dress at one edge length: its sewing, and then steps of its drape timed.
#[derive(Debug, Clone, Serialize)]
pub struct DressScaling {
    /// m.
    pub edge_length: f64,
    pub sewing_steps: u64,
    pub sewing_seconds: f64,
    pub sewing_cg_iterations: usize,
    pub drape: BenchResult,
}

/// The hanging sheet at 55, 110, 224 and 447 particles a side (3,025 to 199,809), and the
/// main job's dress sewn at twice, once, half and a quarter its edge length (about 3,000
/// to 190,000 particles), then `steps` steps of its drape timed, for how the cost of a
/// step grows with the particles; `quick` at 12, 24 and 48 a side, and the dress at 14
/// and 7 cm.
pub fn scaling_benchmarks(steps: usize, quick: bool) -> Result<Scaling, String> {
    let sides: &[usize] = if quick {
        &[12, 24, 48]
    } else {
        &[55, 110, 224, 447]
    };
    let sheet = sides
        .iter()
        .map(|&n| time_steps(format!("hanging_sheet_{n}x{n}"), hanging_sheet(n)?, steps))
        .collect::<Result<_, _>>()?;
    let edge_lengths = match DressScene::load(None)?.scene.cloth {
        _ if quick => vec![0.14, 0.07],
        ClothSpec::Garment { edge_length, .. } => [2.0, 1.0, 0.5, 0.25].map(|s| s * edge_length).to_vec(),
        _ => return Err("the dress scene is not a garment".into()),
    };
    let dress = edge_lengths
        .into_iter()
        .map(|h| {
            let (sewn, bodies) = DressScene::load(Some(h))?.sew()?;
            let sim =
                drape_simulation(&sewn, bodies, SolverSettings::default(), 0.0).map_err(|x| x.to_string())?;
            Ok(DressScaling {
                edge_length: h,
                sewing_steps: sewn.report.steps,
                sewing_seconds: sewn.report.seconds,
                sewing_cg_iterations: sewn.report.cg_iterations,
                drape: time_steps(format!("dress_drape_{:.1}mm", h * 1e3), sim, steps)?,
            })
        })
        .collect::<Result<_, String>>()?;
    Ok(Scaling { sheet, dress })
}

/// The source's sheet: 1 m square, `n` x `n` particles, hanging from its two top corners.
fn hanging_sheet(n: usize) -> Result<Simulation, String> {
    let e = |e: &dyn std::fmt::Display| e.to_string();
    let mesh = GridBuilder::new(n, n)
        .size(1.0, 1.0)
        .axes(Vec3::x(), -Vec3::z())
        .build()
        .map_err(|x| e(&x))?;
    let g = mesh.grid().expect("a grid");
    SimulationBuilder::new(mesh, sheet_fabric())
        .pin(Pin::fixed(g.index(0, 0)))
        .pin(Pin::fixed(g.index(n - 1, 0)))
        .build()
        .map_err(|x| e(&x))
}

/// The sheets' fabric: cotton-like, with a little stiffness damping and air drag.
fn sheet_fabric() -> Fabric {
    Fabric::cotton_like().with_damping(2e-3).with_drag(0.05)
}

/// A square metre of sheet, `n` x `n` particles, dropped flat from 2 cm above a sphere of
/// radius 0.25 m (64 x 32 facets, 3 mm thick, friction 0.5), centred over it, at 60 steps
/// a second.
fn sheet_on_sphere(n: usize) -> Result<Simulation, Box<dyn std::error::Error>> {
    let (radius, thickness) = (0.25, 0.003);
    let body = Body::new("sphere", TriSurface::sphere(radius, 64, 32)?)
        .with_thickness(thickness)?
        .with_friction(0.5)?;
    let top = Vec3::new(0.0, 0.0, radius + thickness + 0.02);
    let mesh = GridBuilder::new(n, n)
        .size(1.0, 1.0)
        .origin(top - 0.5 * (Vec3::x() + Vec3::y()))
        .axes(Vec3::x(), Vec3::y())
        .build()?;
    let bodies = Arc::new(Bodies::new(vec![body]));
    Ok(SimulationBuilder::new(mesh, sheet_fabric())
        .time_step(1.0 / 60.0)
        .collider(bodies)
        .build()?)
}

fn time_steps(name: String, mut sim: Simulation, steps: usize) -> Result<BenchResult, String> {
    let (mut ms, mut cg) = (Vec::with_capacity(steps), Vec::with_capacity(steps));
    let (mut contacts, mut self_ms) = (Vec::with_capacity(steps), Vec::with_capacity(steps));
    for _ in 0..steps {
        let start = Instant::now();
        let stats = sim.step().map_err(|x| format!("{name}: {x}"))?;
        ms.push(start.elapsed().as_secs_f64() * 1e3);
        cg.push(stats.cg_iterations);
        contacts.push(stats.self_contacts);
        self_ms.push(stats.self_collision_seconds * 1e3);
    }
    ms.sort_by(f64::total_cmp);
    self_ms.sort_by(f64::total_cmp);
    cg.sort_unstable();
    contacts.sort_unstable();
    Ok(BenchResult {
        name,
        particles: sim.mesh().vertex_count(),
        steps,
        median_ms_per_step: ms.get(steps / 2).copied().unwrap_or(0.0),
        median_cg_iterations: cg.get(steps / 2).copied().unwrap_or(0),
        median_self_contacts: contacts.get(steps / 2).copied().unwrap_or(0),
        median_self_collision_ms: self_ms.get(steps / 2).copied().unwrap_or(0.0),
    })
}

/// The worker threads the parallel loops use.
pub fn threads() -> usize {
    rayon::current_num_threads()
}
