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

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("cloth-cli-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
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
    assert!(String::from_utf8_lossy(&o.stdout).contains("area_density"));
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
    for scene in ["dress.toml", "skirt.toml", "tshirt.toml", "sheet_on_sphere.toml"] {
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
}

#[test]
fn a_run_writes_outputs_that_read_back() {
    let dir = scratch("run");
    let scene = dir.join("sheet.toml");
    std::fs::write(&scene, SHEET).unwrap();
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
    assert!(report["max_warp"].as_f64().unwrap().is_finite());
    assert_eq!(report["stages"][0]["steps"], 60);
    let ply = std::fs::read_to_string(out.join("cloth.ply")).unwrap();
    assert!(
        ply.starts_with("ply\n") && ply.contains("element vertex 144") && ply.contains("property uchar red")
    );
    assert!(out.join("report.md").exists() && out.join("bodies.obj").exists());
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
    assert_eq!(report["failed"], true);
    assert!(report["error"].as_str().unwrap().contains("step 1"), "{report}");
}

#[test]
fn bench_prints_json_for_the_standard_scenes() {
    let o = cloth(&["bench", "--quick", "--steps", "3"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let scenes = json["scenes"].as_array().unwrap();
    let names: Vec<&str> = scenes.iter().map(|s| s["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["hanging_sheet", "sheet_on_sphere", "dress_drape"]);
    for s in scenes {
        assert_eq!(s["steps"], 3);
        assert!(s["particles"].as_u64().unwrap() > 100);
        assert!(s["median_ms_per_step"].as_f64().unwrap() > 0.0);
    }
    assert!(json["threads"].as_u64().unwrap() >= 1);
}
