//! Scenes shared by the integration tests.
#![allow(dead_code)]

use cloth::{math::Vec3, Fabric, GridBuilder, Pin, SimulationBuilder, SolverSettings};

/// A square sheet of `n` x `n` particles and `size` metres hanging in the x-z plane from
/// its two top corners (row j = 0 at z = 0, the weft pointing down).
pub fn two_corner_sheet(n: usize, size: f64, fabric: Fabric, settings: SolverSettings) -> SimulationBuilder {
    let mesh = GridBuilder::new(n, n)
        .size(size, size)
        .axes(Vec3::x(), -Vec3::z())
        .build()
        .expect("valid grid");
    let g = mesh.grid().expect("grid");
    SimulationBuilder::new(mesh, fabric)
        .settings(settings)
        .pin(Pin::fixed(g.index(0, 0)))
        .pin(Pin::fixed(g.index(n - 1, 0)))
}

pub fn max_distance(a: &[Vec3], b: &[Vec3]) -> f64 {
    a.iter().zip(b).map(|(p, q)| (p - q).norm()).fold(0.0, f64::max)
}

/// `f` run in a rayon pool of `threads` threads.
pub fn on_threads<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool")
        .install(f)
}

/// GarmentCode's design `design` (a pattern in assets/garmentcode/patterns) on its mean
/// body, y up, at `edge_length`, in cotton poplin, the body's contact layer thinning to
/// 1 mm where it is flat, as `cloth drape` sets it: the scene and its preparation.
pub fn garmentcode_scene(
    design: &str,
    edge_length: f64,
) -> (cloth::scene_file::SceneFile, cloth::scene_file::Prepared) {
    let assets = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/garmentcode");
    let text = format!(
        "name = \"{design}\"\n[[bodies]]\nfile = \"bodies/mean_all.obj\"\nup_axis = \"y\"\n\
         min_thickness = 0.001\n\
         [cloth.garment]\nedge_length = {edge_length}\npattern = \"patterns/{design}.json\"\n\
         [fabric]\npreset = \"cotton_poplin\"\n"
    );
    let scene = cloth::scene_file::SceneFile::from_toml_str(&text, "scene.toml").unwrap();
    let prepared = scene.prepare("scene.toml", &assets).unwrap();
    (scene, prepared)
}
