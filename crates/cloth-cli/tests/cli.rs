//! The `cloth` command run as a process: each subcommand, bad scenes, a failing run, and
//! the outputs read back.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn cloth(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_cloth"))
        .args(args)
        .output()
        .unwrap()
}

fn assets() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets")
}

/// A folder in the temporary folder for one test, removed when dropped unless the test
/// is failing (its outputs are then left to look at).
struct Scratch(PathBuf);

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        if !std::thread::panicking() {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }
}

fn scratch(name: &str) -> Scratch {
    let dir = std::env::temp_dir().join(format!("cloth-cli-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    Scratch(dir)
}

/// `cloth run SCENE --out OUT --quiet`.
fn run_quietly(scene: &Path, out: &Path) -> Output {
    cloth(&[
        "run",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ])
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A small sheet dropped on a sphere: a few seconds' run.
const SHEET: &str = r#"
name = "small sheet"
[cloth.grid]
nx = 12
ny = 12
size = [0.6, 0.6]
origin = [-0.3, -0.3, 0.35]
[fabric]
preset = "cotton_poplin"
[[bodies]]
sphere = { radius = 0.3 }
[rest]
tolerance = 1e-5
consecutive_steps = 10
max_steps = 60
"#;

#[test]
fn fabrics_lists_and_shows_presets() {
    let o = cloth(&["fabrics"]);
    assert!(o.status.success());
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("silk") && text.contains("wang_black_denim"),
        "{text}"
    );
    let o = cloth(&["fabrics", "silk"]);
    assert!(o.status.success());
    let shown = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(
        shown.contains("area_density") && shown.contains("EMT") && shown.contains("gf cm2/cm"),
        "{shown}"
    );
    let o = cloth(&["fabrics", "tweed"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("unknown fabric preset `tweed`"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn mannequin_writes_a_body_that_reads_back() {
    let dir = scratch("mannequin");
    let path = dir.join("body.obj");
    let o = cloth(&[
        "mannequin",
        "--height",
        "1.75",
        "--hip",
        "1.02",
        "--arms",
        "-o",
        path.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (models, _) = tobj::load_obj(&path, &tobj::GPU_LOAD_OPTIONS).unwrap();
    assert_eq!(models.len(), 3, "torso and two arms");
    let o = cloth(&["mannequin", "--waist=-1", "-o", path.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("waist"), "{}", stderr(&o));
}

#[test]
fn the_shipped_scenes_check() {
    for scene in [
        "dress.toml",
        "skirt.toml",
        "tshirt.toml",
        "sheet_on_sphere.toml",
        "tablecloth.toml",
        "cantilever.toml",
        "cusick.toml",
    ] {
        let path = assets().join("scenes").join(scene);
        let o = cloth(&["check", path.to_str().unwrap()]);
        assert!(o.status.success(), "{scene}: {}", stderr(&o));
        assert!(String::from_utf8_lossy(&o.stdout).contains("ok"));
    }
}

/// Writes `text` as a scene in `dir` and checks it; returns the exit status and stderr.
fn check_text(dir: &Path, text: &str) -> (Option<i32>, String) {
    let path = dir.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    let o = cloth(&["check", path.to_str().unwrap()]);
    (o.status.code(), stderr(&o))
}

#[test]
fn bad_scenes_exit_with_2_and_name_the_place() {
    let dir = scratch("bad");
    // A syntax error: the line and column.
    let (code, e) = check_text(&dir, &SHEET.replace("nx = 12", "nx = = 12"));
    assert_eq!(code, Some(2));
    assert!(e.contains("scene.toml") && e.contains("line 4"), "{e}");
    // An unknown key.
    let (code, e) = check_text(&dir, &SHEET.replace("nx = 12", "nx = 12\nnz = 3"));
    assert_eq!(code, Some(2));
    assert!(e.contains("nz") && e.contains("line"), "{e}");
    // A missing mesh file names it.
    let (code, e) = check_text(
        &dir,
        &SHEET.replace("sphere = { radius = 0.3 }", "file = \"missing.obj\""),
    );
    assert_eq!(code, Some(2));
    assert!(e.contains("bodies[0]") && e.contains("missing.obj"), "{e}");
    // A body's contact layer thinned past its thickness names the body and the key;
    // thinned within it, the scene is good.
    let (code, e) = check_text(
        &dir,
        &SHEET.replace(
            "sphere = { radius = 0.3 }",
            "sphere = { radius = 0.3 }
min_thickness = 0.005",
        ),
    );
    assert_eq!(code, Some(2));
    assert!(e.contains("bodies[0]") && e.contains("min_thickness"), "{e}");
    let (code, e) = check_text(
        &dir,
        &SHEET.replace(
            "sphere = { radius = 0.3 }",
            "sphere = { radius = 0.3 }
min_thickness = 0.001",
        ),
    );
    assert_eq!(code, Some(0), "{e}");
    // Wrong units: a length as text.
    let (code, e) = check_text(
        &dir,
        &SHEET.replace("size = [0.6, 0.6]", "size = [\"60cm\", \"60cm\"]"),
    );
    assert_eq!(code, Some(2));
    assert!(e.contains("line") && e.contains("size"), "{e}");
    // A negative stiffness names the field.
    let si = SHEET.replace(
        "[fabric]\npreset = \"cotton_poplin\"",
        "[fabric.si]\narea_density = 0.15\nwarp = { law = \"linear\", stiffness = -5.0 }\nweft = { law = \"linear\", stiffness = 1000.0 }\ncompression_warp = 100.0\ncompression_weft = 100.0\nshear_modulus = 20.0\nbending = { warp = 1e-5, weft = 1e-5 }",
    );
    let (code, e) = check_text(&dir, &si);
    assert_eq!(code, Some(2));
    assert!(e.contains("warp") && e.contains("-5"), "{e}");
    // A pin outside the grid.
    let (code, e) = check_text(&dir, &SHEET.replace("[fabric]", "pins = [[20, 0]]\n[fabric]"));
    assert_eq!(code, Some(2));
    assert!(e.contains("cloth.grid.pins[0]"), "{e}");
    // Outputs that cannot be: a picture of 5 pixels, frames every 0 steps.
    let (code, e) = check_text(&dir, &format!("{SHEET}\n[output]\nimage_size = [5, 400]\n"));
    assert_eq!(code, Some(2));
    assert!(e.contains("output.image_size") && e.contains("5 x 400"), "{e}");
    let (code, e) = check_text(&dir, &format!("{SHEET}\n[output]\nframes_every = 0\n"));
    assert_eq!(code, Some(2));
    assert!(e.contains("output.frames_every"), "{e}");
    // Self-collision: a thickness below zero names the key; set in [solver], it is refused
    // (it is the scene's, for every stage).
    let (code, e) = check_text(&dir, &format!("{SHEET}\n[self_collision]\nthickness = -0.001\n"));
    assert_eq!(code, Some(2));
    assert!(e.contains("self_collision.thickness"), "{e}");
    let (code, e) = check_text(
        &dir,
        &format!("{SHEET}\n[solver.self_collision]\nenabled = false\n"),
    );
    assert_eq!(code, Some(2));
    assert!(e.contains("self_collision") && e.contains("line"), "{e}");
}

#[test]
fn a_run_writes_outputs_that_read_back() {
    let dir = scratch("run");
    let scene = dir.join("sheet.toml");
    std::fs::write(&scene, format!("{SHEET}\n[output]\nimage_size = [320, 200]\n")).unwrap();
    let out = dir.join("out");
    let o = run_quietly(&scene, &out);
    assert!(o.status.success(), "{}", stderr(&o));
    let (models, _) = tobj::load_obj(out.join("cloth.obj"), &tobj::LoadOptions::default()).unwrap();
    let mesh = &models[0].mesh;
    assert_eq!(mesh.positions.len(), 3 * 144);
    assert_eq!(
        mesh.texcoords.len(),
        2 * 3 * mesh.indices.len() / 3,
        "one uv per corner"
    );
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    assert_eq!(report["particles"], 144);
    // The engine that wrote it, as `cloth --version` names it.
    assert_eq!(report["engine_version"], env!("CARGO_PKG_VERSION"));
    assert_eq!(report["outcome"]["kind"], "finished");
    assert!(report["strain"]["max_warp"].as_f64().unwrap().is_finite());
    assert_eq!(report["stages"][0]["steps"], 60);
    assert_eq!(report["settings"]["rest"]["max_steps"], 60);
    // Self-collision is on unless a scene turns it off, and nothing passes through.
    assert_eq!(report["settings"]["self_collision"]["enabled"], true);
    assert_eq!(report["self_intersections"], 0);
    assert_eq!(report["body_intersections"], 0);
    let ply = std::fs::read_to_string(out.join("cloth.ply")).unwrap();
    assert!(
        ply.starts_with("ply\n") && ply.contains("element vertex 144") && ply.contains("property uchar red")
    );
    assert!(out.join("report.md").exists() && out.join("bodies.obj").exists());
    // The picture decodes at the size asked for.
    let decoder = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(out.join("render.png")).unwrap(),
    ));
    let reader = decoder.read_info().unwrap();
    assert_eq!((reader.info().width, reader.info().height), (320, 200));
    // The glTF binary holds the cloth (144 particles, z up turned to y up) and the sphere.
    let (doc, buffers, _) = gltf::import(out.join("scene.glb")).unwrap();
    let names: Vec<&str> = doc.meshes().filter_map(|m| m.name()).collect();
    assert_eq!(names, ["cloth", "sphere"]);
    let cloth = doc.meshes().next().unwrap().primitives().next().unwrap();
    let reader = cloth.reader(|b| Some(&buffers[b.index()]));
    let heights: Vec<f32> = reader.read_positions().unwrap().map(|p| p[1]).collect();
    assert_eq!(heights.len(), 144);
    // Resting on the sphere of radius 0.3 at the origin: nothing far below its top.
    assert!(heights.iter().all(|&y| y > -0.35 && y < 0.36), "{heights:?}");
    // A row per step in history.csv, the last at the run's end, its energy falling as the
    // sheet settles.
    let csv = std::fs::read_to_string(out.join("history.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 60);
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let value = |row: &[&str], name: &str| row[column(name)].parse::<f64>().unwrap();
    assert_eq!(rows[59][column("stage")], "running");
    assert_eq!(value(&rows[59], "step"), 60.0);
    let simulated = report["simulated_time"].as_f64().unwrap();
    assert!((value(&rows[59], "time") - simulated).abs() < 1e-12);
    let cg: f64 = rows.iter().map(|r| value(r, "cg_iterations")).sum();
    assert_eq!(cg, report["stages"][0]["cg_iterations"].as_f64().unwrap());
    let peak = rows
        .iter()
        .map(|r| value(r, "kinetic_energy"))
        .fold(0.0, f64::max);
    assert!(
        value(&rows[59], "kinetic_energy") < 0.1 * peak,
        "the sheet settles"
    );
    // The report shows its plots, pictures that decode.
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    for plot in ["strain.png", "convergence.png"] {
        assert!(md.contains(&format!("]({plot})")), "{md}");
        let decoder = png::Decoder::new(std::io::BufReader::new(
            std::fs::File::open(out.join(plot)).unwrap(),
        ));
        assert!(decoder.read_info().unwrap().info().width > 0);
    }
    // The folder is not overwritten without --force.
    let o = run_quietly(&scene, &out);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--force"), "{}", stderr(&o));
}

#[test]
fn a_diverging_run_exits_with_1_and_writes_its_report() {
    let dir = scratch("diverge");
    let scene = dir.join("sheet.toml");
    // A speed limit the falling sheet passes at once.
    std::fs::write(&scene, format!("{SHEET}\n[solver]\nmax_speed = 0.01\n")).unwrap();
    let out = dir.join("out");
    let o = run_quietly(&scene, &out);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    assert_eq!(report["outcome"]["kind"], "failed");
    assert!(
        report["outcome"]["error"].as_str().unwrap().contains("step 1"),
        "{report}"
    );
    // The last good state, here the sheet as placed, is written too.
    let (models, _) = tobj::load_obj(out.join("cloth.obj"), &tobj::LoadOptions::default()).unwrap();
    assert_eq!(models[0].mesh.positions.len(), 3 * 144);
    assert!(std::fs::read_to_string(out.join("report.md"))
        .unwrap()
        .contains("**Failed**"));
}

#[test]
fn ctrl_c_stops_the_run_and_writes_the_state_reached() {
    signal_stops_the_run_and_writes_the_state_reached("INT");
}

/// A batch scheduler or `timeout` stops a run with SIGTERM: it ends as Ctrl-C does.
#[test]
fn sigterm_stops_the_run_and_writes_the_state_reached() {
    signal_stops_the_run_and_writes_the_state_reached("TERM");
}

fn signal_stops_the_run_and_writes_the_state_reached(signal: &str) {
    use std::io::{BufRead, BufReader};
    let dir = scratch(&format!("interrupt_{signal}"));
    let scene = dir.join("sheet.toml");
    // A run far longer than the test waits.
    std::fs::write(
        &scene,
        SHEET
            .replace("nx = 12", "nx = 40")
            .replace("ny = 12", "ny = 40")
            .replace("max_steps = 60", "max_steps = 100000")
            .replace("tolerance = 1e-5", "tolerance = 1e-12"),
    )
    .unwrap();
    let out = dir.join("out");
    let mut child = Command::new(env!("CARGO_BIN_EXE_cloth"))
        .args(["run", scene.to_str().unwrap(), "--out", out.to_str().unwrap()])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // Not a terminal: plain lines, the first when the stage begins.
    let mut lines = BufReader::new(child.stderr.take().unwrap()).lines();
    let first = lines.next().unwrap().unwrap();
    assert!(first.starts_with("running: up to 100000 steps"), "{first}");
    std::thread::sleep(std::time::Duration::from_millis(500));
    let kill = Command::new("kill")
        .args([&format!("-{signal}"), &child.id().to_string()])
        .status()
        .unwrap();
    assert!(kill.success());
    let rest: Vec<String> = lines.map_while(Result::ok).collect();
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(130), "{rest:?}");
    assert!(
        rest.iter().any(|l| l.contains("interrupted at running step")),
        "{rest:?}"
    );
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    assert_eq!(report["outcome"]["kind"], "interrupted", "{report}");
    let step = report["outcome"]["step"].as_u64().unwrap();
    assert!((1..100000).contains(&step), "{report}");
    assert_eq!(report["stages"][0]["steps"].as_u64(), Some(step));
    let (models, _) = tobj::load_obj(out.join("cloth.obj"), &tobj::LoadOptions::default()).unwrap();
    assert_eq!(models[0].mesh.positions.len(), 3 * 1600);
    // The sheet has fallen from where it started.
    let lowest = models[0]
        .mesh
        .positions
        .chunks(3)
        .map(|p| p[2])
        .fold(f64::INFINITY, f64::min);
    assert!(lowest < 0.35 - 1e-4, "lowest {lowest}");
}

/// The small sheet run with `output` (the lines of its `[output]`, no picture or glTF),
/// frames every 20 steps: its scratch folder (the output in `out`) and report, after
/// checking it wrote 3 frames.
fn sheet_frames(name: &str, output: &str) -> (Scratch, serde_json::Value) {
    let dir = scratch(name);
    let scene = dir.join("sheet.toml");
    let text = format!(
        "{SHEET}\n[output]\nframes_every = 20\nglb = false\npng = false\nhistory = false\nplots = false\n{output}"
    );
    std::fs::write(&scene, text).unwrap();
    let out = dir.join("out");
    let o = run_quietly(&scene, &out);
    assert!(o.status.success(), "{}", stderr(&o));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    assert_eq!(report["frames"].as_array().unwrap().len(), 3, "{report}");
    (dir, report)
}

#[test]
fn frames_and_checkpoints_are_written_when_asked() {
    let (dir, report) = sheet_frames("frames", "checkpoints = [1, 30, 60]\n");
    let out = dir.join("out");
    let frames = report["frames"].as_array().unwrap();
    for (k, f) in frames.iter().enumerate() {
        assert_eq!(f["step"].as_u64(), Some(20 * (k as u64 + 1)));
        assert_eq!(f["self_intersections"], 0);
        let (models, _) = tobj::load_obj(
            out.join(f["file"].as_str().unwrap()),
            &tobj::LoadOptions::default(),
        )
        .unwrap();
        assert_eq!(models[0].mesh.positions.len(), 3 * 144);
    }
    let rows = report["checkpoints"].as_array().unwrap();
    let steps: Vec<u64> = rows.iter().map(|r| r["step"].as_u64().unwrap()).collect();
    assert_eq!(steps, [1, 30, 60]);
    // The sheet stretches as it lands: more after 60 steps than after 1.
    assert!(rows[2]["max_warp"].as_f64().unwrap() > rows[0]["max_warp"].as_f64().unwrap());
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(
        md.contains("Largest stretch after N steps") && md.contains("| running | 30 |"),
        "{md}"
    );
    assert!(!out.join("scene.glb").exists() && !out.join("render.png").exists());
    for unasked in ["history.csv", "strain.png", "convergence.png"] {
        assert!(!out.join(unasked).exists(), "{unasked}");
    }
    assert!(!md.contains("## Plots"));
}

/// Asked for an animation, the frames go into one point cache per stage, beside the mesh
/// it plays on, in the output frame; the report says which sample each frame is.
#[test]
fn frames_go_into_a_point_cache_when_asked() {
    let (dir, report) = sheet_frames("pc2", "animation = \"pc2\"\nup_axis = \"y\"\n");
    let out = dir.join("out");
    let frames = report["frames"].as_array().unwrap();
    for (k, f) in frames.iter().enumerate() {
        assert_eq!(f["file"], "frames/running.pc2");
        assert_eq!(f["sample"].as_u64(), Some(k as u64));
        assert_eq!(f["step"].as_u64(), Some(20 * (k as u64 + 1)));
    }
    assert!(!out.join("frames/frame_00001.obj").exists(), "no OBJ per frame");
    let cache = cloth::formats::pc2::Pc2::read(&out.join("frames/running.pc2")).unwrap();
    assert_eq!(cache.samples.len(), 3);
    let (mesh, _) = tobj::load_obj(out.join("frames/running.obj"), &tobj::LoadOptions::default()).unwrap();
    assert_eq!(cache.samples[0].len(), 144);
    assert_eq!(
        mesh[0].mesh.positions.len(),
        3 * 144,
        "the mesh the cache plays on"
    );
    // The last frame is the final state, in the same (y-up) frame as cloth.obj.
    let obj = std::fs::read_to_string(out.join("cloth.obj")).unwrap();
    assert!(obj.contains("# y up"), "{}", &obj[..200]);
    let vertices = obj_vertices(&out.join("cloth.obj"));
    assert_eq!(vertices.len(), cache.samples[2].len());
    for (p, q) in vertices.iter().zip(&cache.samples[2]) {
        for k in 0..3 {
            assert!((p[k] - f64::from(q[k])).abs() < 1e-6, "{p:?} against {q:?}");
        }
    }
    // The sheet falls: down its y, now up.
    let mean_y = |s: &[[f32; 3]]| s.iter().map(|p| f64::from(p[1])).sum::<f64>() / s.len() as f64;
    assert!(mean_y(&cache.samples[2]) < mean_y(&cache.samples[0]));
}

/// The vertices of an OBJ in the file's own order (tobj numbers them as faces first use
/// them).
fn obj_vertices(path: &std::path::Path) -> Vec<[f64; 3]> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let v: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            [v[0], v[1], v[2]]
        })
        .collect()
}

#[test]
fn frames_go_into_a_gltf_animation_when_asked() {
    let (dir, report) = sheet_frames("gltf_animation", "animation = \"gltf\"\n");
    let out = dir.join("out");
    let frames = report["frames"].as_array().unwrap();
    for (k, f) in frames.iter().enumerate() {
        assert_eq!(f["file"], "frames/running.glb");
        assert_eq!(f["sample"].as_u64(), Some(k as u64));
    }
    let names: Vec<String> = std::fs::read_dir(out.join("frames"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, ["running.glb"], "the frames' cache is removed");

    let (doc, buffers, _) = gltf::import(out.join("frames/running.glb")).unwrap();
    let node = doc.nodes().next().unwrap();
    let primitive = node.mesh().unwrap().primitives().next().unwrap();
    let reader = primitive.reader(|b| Some(&buffers[b.index()]));
    let base: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
    let targets: Vec<Vec<[f32; 3]>> = reader
        .read_morph_targets()
        .map(|(positions, _, _)| positions.unwrap().collect())
        .collect();
    assert_eq!(targets.len(), 2, "frames 2 and 3 blend from frame 1");
    assert_eq!(base.len(), 144);

    // One animation of the weights: frame k + 1 at its time, with weight 1 on target k.
    let animation = doc.animations().next().unwrap();
    let channel = animation.channels().next().unwrap();
    assert_eq!(channel.target().node().index(), node.index());
    assert_eq!(
        channel.target().property(),
        gltf::animation::Property::MorphTargetWeights
    );
    assert_eq!(
        channel.sampler().interpolation(),
        gltf::animation::Interpolation::Linear
    );
    let reader = channel.reader(|b| Some(&buffers[b.index()]));
    let times: Vec<f32> = reader.read_inputs().unwrap().collect();
    let gltf::animation::util::ReadOutputs::MorphTargetWeights(weights) = reader.read_outputs().unwrap()
    else {
        panic!("not weights")
    };
    let weights: Vec<f32> = weights.into_f32().collect();
    let step_time = |k: usize| frames[k]["time"].as_f64().unwrap();
    for (k, &t) in times.iter().enumerate() {
        assert!(
            (f64::from(t) - (step_time(k) - step_time(0))).abs() < 1e-6,
            "{times:?}"
        );
    }
    assert_eq!(weights, [0.0, 0.0, 1.0, 0.0, 0.0, 1.0]);

    // The last frame, turned back from glTF's y up, is the final cloth.obj (z up); glTF
    // vertices come in their own order, so each is matched to its nearest.
    let vertices = obj_vertices(&out.join("cloth.obj"));
    let last: Vec<[f64; 3]> = base
        .iter()
        .zip(&targets[1])
        .map(|(b, d)| {
            let p = [b[0] + d[0], b[1] + d[1], b[2] + d[2]].map(f64::from);
            [p[0], -p[2], p[1]]
        })
        .collect();
    for p in &last {
        let nearest = vertices
            .iter()
            .map(|v| (0..3).map(|k| (v[k] - p[k]).powi(2)).sum::<f64>().sqrt())
            .fold(f64::INFINITY, f64::min);
        assert!(nearest < 1e-5, "{p:?} is {nearest} m from the final cloth");
    }
    // The sheet falls between the first frame and the last.
    let mean_height = |points: &[[f64; 3]]| points.iter().map(|p| p[2]).sum::<f64>() / points.len() as f64;
    let first: Vec<[f64; 3]> = base.iter().map(|b| [b[0], -b[2], b[1]].map(f64::from)).collect();
    let (from, to) = (mean_height(&first), mean_height(&last));
    assert!(to < from, "the mean height goes from {from} m to {to} m");
}

/// Blender, if this machine has it (`apt install blender`), imports both animations as a
/// user would and plays them to their last frame, which must be the final cloth; the test
/// passes saying it skipped where Blender is absent.
#[test]
fn blender_plays_the_animations() {
    let found = Command::new("blender").arg("--version").output();
    if !found.is_ok_and(|o| o.status.success()) {
        eprintln!("skipped: no `blender` on PATH");
        return;
    }
    let (gltf_dir, _) = sheet_frames("blender_gltf", "animation = \"gltf\"\n");
    let (pc2_dir, _) = sheet_frames("blender_pc2", "animation = \"pc2\"\n");
    let (glb, frames) = (gltf_dir.join("out/frames"), pc2_dir.join("out/frames"));
    let result = gltf_dir.join("blender.json");
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/blender_animation.py");
    let o = Command::new("blender")
        .args(["-b", "--factory-startup", "--python"])
        .arg(&script)
        .arg("--")
        .args([
            glb.join("running.glb"),
            frames.join("running.obj"),
            frames.join("running.pc2"),
        ])
        .arg("3")
        .arg(&result)
        .output()
        .unwrap();
    let read: serde_json::Value = match std::fs::read_to_string(&result) {
        Ok(text) => serde_json::from_str(&text).unwrap(),
        Err(_) => panic!("Blender wrote nothing: {}", String::from_utf8_lossy(&o.stdout)),
    };
    assert_eq!(
        read["shape_keys"],
        serde_json::json!(["Basis", "frame_00002", "frame_00003"])
    );
    // Blender turns glTF's y up into its own z up, the engine's frame.
    for (run, key, in_order) in [(&gltf_dir, "gltf_last", false), (&pc2_dir, "pc2_last", true)] {
        let cloth = obj_vertices(&run.join("out/cloth.obj"));
        let shown: Vec<[f64; 3]> = read[key]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| [0, 1, 2].map(|k| p[k].as_f64().unwrap()))
            .collect();
        assert_eq!(shown.len(), cloth.len(), "{key}");
        let distance = |a: &[f64; 3], b: &[f64; 3]| (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt();
        for (i, p) in shown.iter().enumerate() {
            let off = if in_order {
                distance(p, &cloth[i])
            } else {
                cloth.iter().map(|v| distance(p, v)).fold(f64::INFINITY, f64::min)
            };
            assert!(
                off < 1e-5,
                "{key}: Blender shows vertex {i} at {p:?}, {off} m off"
            );
        }
    }
}

#[test]
fn the_cantilever_scene_bends_like_the_elastica() {
    let dir = scratch("cantilever");
    let out = dir.join("out");
    let o = run_quietly(&assets().join("scenes/cantilever.toml"), &out);
    assert!(o.status.success(), "{}", stderr(&o));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    let m = &report["measurement"];
    assert_eq!(m["test"], "cantilever", "{report}");
    let (ours, elastica) = (
        m["drop_over_length"].as_f64().unwrap(),
        m["elastica_drop_over_length"].as_f64().unwrap(),
    );
    // The discrete strip against the inextensible elastica at the same w L^3 / B.
    assert!((ours - elastica).abs() < 0.02 * elastica, "{ours} vs {elastica}");
}

#[test]
fn a_cloth_from_a_mesh_file_runs_with_its_pins() {
    let dir = scratch("mesh");
    // A flat, level 40 cm square of two triangles per cell, held by two corners.
    let n = 9;
    let mut obj = String::new();
    for j in 0..n {
        for i in 0..n {
            obj += &format!("v {} {} 1\n", 0.05 * i as f64, 0.05 * j as f64);
        }
    }
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let a = j * n + i + 1;
            obj += &format!(
                "f {} {} {}\nf {} {} {}\n",
                a,
                a + 1,
                a + n + 1,
                a,
                a + n + 1,
                a + n
            );
        }
    }
    std::fs::write(dir.join("sheet.obj"), obj).unwrap();
    let scene = dir.join("scene.toml");
    let text = format!(
        "[cloth.mesh]\nfile = \"sheet.obj\"\npins = [0, {}]\n[fabric]\npreset = \"cotton_poplin\"\n\
         [rest]\ntolerance = 1e-5\nconsecutive_steps = 5\nmax_steps = 40\n[output]\nglb = false\npng = false\n",
        n - 1
    );
    std::fs::write(&scene, text).unwrap();
    let out = dir.join("out");
    let o = cloth(&[
        "run",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--verbose",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // --verbose: every step's statistics.
    let e = stderr(&o);
    assert!(
        e.contains("running step 1:") && e.contains("running step 40:") && e.contains("CG iterations"),
        "{e}"
    );
    let (models, _) = tobj::load_obj(out.join("cloth.obj"), &tobj::LoadOptions::default()).unwrap();
    let p = &models[0].mesh.positions;
    assert_eq!(p.len(), 3 * n * n);
    // The pinned corners stay; the free corners fall.
    assert_eq!((p[0], p[1], p[2]), (0.0, 0.0, 1.0));
    assert!(p[3 * (n * n - 1) + 2] < 0.9, "{}", p[3 * (n * n - 1) + 2]);
    // A pin past the mesh's vertices names its place.
    std::fs::write(
        &scene,
        std::fs::read_to_string(&scene)
            .unwrap()
            .replace("pins = [0,", "pins = [500,"),
    )
    .unwrap();
    let o = cloth(&["check", scene.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("cloth.mesh.pins[0]"), "{}", stderr(&o));
    // A body's layer thinned to the cloth's edges, whose length a mesh file does not say
    // before it is read, is refused naming the key.
    std::fs::write(
        &scene,
        format!(
            "{}[[bodies]]\nsphere = {{ radius = 0.1 }}\nposition = [0.2, 0.2, 0.5]\nmin_thickness = 0.001\n",
            std::fs::read_to_string(&scene)
                .unwrap()
                .replace("pins = [500,", "pins = [0,")
        ),
    )
    .unwrap();
    let o = cloth(&["check", scene.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("bodies[0].min_thickness"), "{}", stderr(&o));
}

#[test]
fn bench_prints_json_for_the_standard_scenes() {
    let o = cloth(&["bench", "--quick", "--steps", "3", "--scaling"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let scenes = json["scenes"].as_array().unwrap();
    let names: Vec<&str> = scenes.iter().map(|s| s["name"].as_str().unwrap()).collect();
    assert_eq!(
        names,
        [
            "hanging_sheet",
            "sheet_on_sphere",
            "sphere_drop_35x35",
            "dress_drape",
            "dress_drape_without_self_collision"
        ]
    );
    for s in scenes {
        assert_eq!(s["steps"], 3);
        assert!(s["particles"].as_u64().unwrap() > 100);
        assert!(s["median_ms_per_step"].as_f64().unwrap() > 0.0);
    }
    // The main job from placed panels to rest: both stages ran and took time.
    let to_rest = &json["to_rest"][0];
    assert_eq!(to_rest["name"], "dress_to_rest");
    for stage in ["sewing", "drape"] {
        assert!(to_rest[format!("{stage}_steps")].as_u64().unwrap() > 0);
        assert!(to_rest[format!("{stage}_seconds")].as_f64().unwrap() > 0.0);
    }
    // The quick scaling runs the sheet at 12, 24 and 48 a side, and the dress sewn at 14
    // and 7 cm, the finer with more particles.
    let particles = |list: &serde_json::Value| -> Vec<u64> {
        let list = list.as_array().unwrap().iter();
        list.map(|s| s["particles"].as_u64().unwrap()).collect()
    };
    assert_eq!(particles(&json["scaling"]["sheet"]), [144, 576, 2304]);
    let dress = json["scaling"]["dress"].as_array().unwrap();
    let edges: Vec<f64> = dress.iter().map(|d| d["edge_length"].as_f64().unwrap()).collect();
    assert_eq!(edges, [0.14, 0.07]);
    let drapes: Vec<_> = dress.iter().map(|d| d["drape"].clone()).collect();
    let drape_particles = particles(&serde_json::Value::Array(drapes));
    assert!(drape_particles[1] > 2 * drape_particles[0], "{drape_particles:?}");
    for d in dress {
        assert!(d["sewing_steps"].as_u64().unwrap() > 0);
        assert_eq!(d["drape"]["steps"], 3);
    }
    assert!(json["threads"].as_u64().unwrap() >= 1);
}

#[test]
fn drape_runs_many_patterns_into_folders_with_one_summary() {
    let dir = scratch("drape");
    let out = dir.join("out");
    // A GarmentCode waistband (two panels, a few hundred particles) and a pattern whose
    // JSON is cut short: one finishes, one is refused, and the batch goes on.
    let band = assets().join("garmentcode/patterns/rand_1_001.json");
    let broken = dir.join("broken.json");
    std::fs::write(&broken, "{\"pattern\": {\"panels\": ").unwrap();
    let body = assets().join("garmentcode/bodies/mean_all.obj");
    let args = |extra: &[&str]| {
        let mut a = vec![
            "drape",
            band.to_str().unwrap(),
            broken.to_str().unwrap(),
            "--body",
            body.to_str().unwrap(),
            "--body-up-axis",
            "y",
            "--edge-length",
            "0.03",
            "--out",
            out.to_str().unwrap(),
            "--jobs",
            "2",
            "--up-axis",
            "y",
        ];
        a.extend_from_slice(extra);
        a.into_iter().map(String::from).collect::<Vec<_>>()
    };
    let run = |extra: &[&str]| {
        let a = args(extra);
        cloth(&a.iter().map(String::as_str).collect::<Vec<_>>())
    };
    let o = run(&[]);
    assert_eq!(o.status.code(), Some(1), "one pattern failed: {}", stderr(&o));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let entries = summary.as_array().unwrap();
    assert_eq!(entries.len(), 2);
    let band_entry = &entries[0];
    assert_eq!(band_entry["name"], "rand_1_001");
    assert_eq!(band_entry["outcome"], "finished", "{band_entry}");
    assert!(band_entry["particles"].as_u64().unwrap() > 50);
    assert!(band_entry["sewing_steps"].as_u64().unwrap() > 0);
    assert!(band_entry["draping_steps"].as_u64().unwrap() > 0);
    for key in [
        "max_warp",
        "p99_weft",
        "deepest_penetration",
        "self_intersections",
        "body_intersections",
    ] {
        assert!(band_entry[key].is_number(), "{key}: {band_entry}");
    }
    // The verdict agrees with the figures: "clean" exactly when they say so.
    let under = |key: &str| band_entry[key].as_f64().unwrap() < 5.0;
    let clean = band_entry["self_intersections"] == 0
        && band_entry["body_intersections"] == 0
        && under("p99_warp")
        && under("p99_weft")
        && band_entry["drape_ended"] == "at_rest";
    assert_eq!(
        band_entry["verdict"].as_str() == Some("clean"),
        clean,
        "{band_entry}"
    );
    // Its report gives the figures panel by panel: every triangle in one of its panels.
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("rand_1_001/report.json")).unwrap()).unwrap();
    let panels = report["panels"].as_array().unwrap();
    assert!(panels.len() >= 2, "{panels:?}");
    let triangles: u64 = panels.iter().map(|p| p["triangles"].as_u64().unwrap()).sum();
    assert_eq!(triangles, report["triangles"].as_u64().unwrap());
    let worst = panels
        .iter()
        .map(|p| p["p99_weft"].as_f64().unwrap())
        .fold(f64::MIN, f64::max);
    assert!(
        worst >= band_entry["p99_weft"].as_f64().unwrap() - 1e-9,
        "{panels:?}"
    );
    let broken_entry = &entries[1];
    assert_eq!(broken_entry["outcome"], "failed");
    assert!(broken_entry["verdict"].is_null(), "{broken_entry}");
    assert!(
        broken_entry["failure"].as_str().unwrap().contains("broken.json"),
        "{broken_entry}"
    );
    for file in [
        "cloth.obj",
        "report.json",
        "render.png",
        "scene.toml",
        "finished.json",
    ] {
        assert!(out.join("rand_1_001").join(file).is_file(), "{file}");
    }
    // Asked y up, as the body came: the OBJ says so and its waistband is at the body's
    // waist in the body file's own frame; its panels are groups, named as in the pattern.
    let obj = std::fs::read_to_string(out.join("rand_1_001/cloth.obj")).unwrap();
    assert!(
        obj.lines().take(2).any(|l| l.starts_with("# y up")),
        "{}",
        &obj[..200]
    );
    let band_mesh = tobj::load_obj(out.join("rand_1_001/cloth.obj"), &tobj::GPU_LOAD_OPTIONS)
        .unwrap()
        .0;
    let body_mesh = tobj::load_obj(&body, &tobj::GPU_LOAD_OPTIONS).unwrap().0;
    let heights = |models: &[tobj::Model]| {
        let y: Vec<f64> = models
            .iter()
            .flat_map(|m| m.mesh.positions.chunks(3).map(|p| p[1]))
            .collect();
        (
            y.iter().copied().fold(f64::MAX, f64::min),
            y.iter().copied().fold(f64::MIN, f64::max),
        )
    };
    let (band_low, band_high) = heights(&band_mesh);
    let (feet, head) = heights(&body_mesh);
    assert!(
        band_low > feet + 0.4 * (head - feet) && band_high < head,
        "waistband y {band_low}..{band_high}, body {feet}..{head}"
    );
    let groups: std::collections::BTreeSet<&str> = obj.lines().filter_map(|l| l.strip_prefix("g ")).collect();
    let names: std::collections::BTreeSet<&str> =
        panels.iter().map(|p| p["panel"].as_str().unwrap()).collect();
    assert_eq!(groups, names);
    // The segmentation has a line per vertex, each naming its panel or a seam's panels;
    // the PLY has each vertex's panel.
    let vertices = obj.lines().filter(|l| l.starts_with("v ")).count();
    let segmentation = std::fs::read_to_string(out.join("rand_1_001/segmentation.txt")).unwrap();
    assert_eq!(segmentation.lines().count(), vertices);
    assert!(segmentation.lines().any(|l| l.contains(',')), "no seam vertex");
    for line in segmentation.lines() {
        assert!(line.split(',').all(|p| names.contains(p)), "{line}");
    }
    let ply = std::fs::read_to_string(out.join("rand_1_001/cloth.ply")).unwrap();
    assert!(
        ply.contains("property int panel") && ply.contains("comment y up"),
        "{}",
        &ply[..400]
    );
    let table = std::fs::read_to_string(out.join("summary.md")).unwrap();
    assert!(
        table.contains("1 of 2 patterns finished") && table.contains("| rand_1_001 | finished"),
        "{table}"
    );
    // The body's contact layer is thinned where it is flat, by default.
    let scene = std::fs::read_to_string(out.join("rand_1_001/scene.toml")).unwrap();
    assert!(scene.contains("min_thickness = 0.001"), "{scene}");
    // The scene written beside the outputs runs the same drape again.
    let again = cloth(&["check", out.join("rand_1_001/scene.toml").to_str().unwrap()]);
    assert!(again.status.success(), "{}", stderr(&again));
    // Run again with frames: each frame's OBJ has the panels as groups, in both stages
    // (the sewn garment's triangles keep their panels through welding).
    let framed = dir.join("framed.toml");
    std::fs::write(
        &framed,
        scene.replace("[output]\n", "[output]\nframes_every = 10\n"),
    )
    .unwrap();
    let o = run_quietly(&framed, &dir.join("framed"));
    assert!(o.status.success(), "{}", stderr(&o));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("framed/report.json")).unwrap()).unwrap();
    let frames = report["frames"].as_array().unwrap();
    let stages: std::collections::BTreeSet<&str> =
        frames.iter().map(|f| f["stage"].as_str().unwrap()).collect();
    assert_eq!(stages, ["draping", "sewing"].into_iter().collect(), "{frames:?}");
    for f in frames {
        let text = std::fs::read_to_string(dir.join("framed").join(f["file"].as_str().unwrap())).unwrap();
        let groups: std::collections::BTreeSet<&str> =
            text.lines().filter_map(|l| l.strip_prefix("g ")).collect();
        assert_eq!(groups, names, "{}", f["file"]);
    }

    // Again: the finished pattern is skipped, the broken one tried and refused again.
    let o = run(&[]);
    assert_eq!(o.status.code(), Some(1));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary[0]["skipped"], true);
    assert_eq!(summary[0]["outcome"], "finished");

    // A time limit passed before the first step ends: counted failed, with its report.
    let o = run(&["--force", "--time-limit", "0.01"]);
    assert_eq!(o.status.code(), Some(1));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary[0]["outcome"], "failed", "{}", summary[0]);
    assert!(
        summary[0]["failure"]
            .as_str()
            .unwrap()
            .contains("stopped by the time limit of 0.01 s"),
        "{}",
        summary[0]
    );
    assert!(!out.join("rand_1_001/finished.json").exists());
    assert!(out.join("rand_1_001/report.json").is_file());

    // Bad input to the batch itself: exit 2 before anything runs.
    let missing = dir.join("missing.obj");
    let bad_body = cloth(&[
        "drape",
        band.to_str().unwrap(),
        "--body",
        missing.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(bad_body.status.code(), Some(2), "{}", stderr(&bad_body));
    assert!(stderr(&bad_body).contains("missing.obj"));
    let bad_fabric = run(&["--fabric", "tweed"]);
    assert_eq!(bad_fabric.status.code(), Some(2));
    for layer in ["0", "0.004"] {
        let bad_layer = run(&["--min-thickness", layer]);
        assert_eq!(bad_layer.status.code(), Some(2), "{}", stderr(&bad_layer));
        assert!(
            stderr(&bad_layer).contains("--min-thickness"),
            "{}",
            stderr(&bad_layer)
        );
    }
    let empty = dir.join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    let o = cloth(&[
        "drape",
        empty.to_str().unwrap(),
        "--body",
        body.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("holds no pattern"), "{}", stderr(&o));
}
