//! `cloth render` as a user runs it: files in, a PNG out, errors named.

use std::path::PathBuf;
use std::process::Command;

fn cloth() -> Command {
    Command::new(env!("CARGO_BIN_EXE_cloth"))
}

/// A fresh folder for one test.
fn folder(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("render")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A tetrahedron as OBJ, and a strained square sheet as PLY (as `cloth run` writes).
fn write_inputs(dir: &std::path::Path) -> (PathBuf, PathBuf) {
    let obj = dir.join("a.obj");
    std::fs::write(
        &obj,
        "v 0 0 0\nv 0.5 0 0\nv 0 0.5 0\nv 0 0 0.5\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    )
    .unwrap();
    let ply = dir.join("b.ply");
    let mut text = String::from(
        "ply\nformat ascii 1.0\nelement vertex 9\nproperty double x\nproperty double y\n\
         property double z\nproperty float strain\nelement face 4\n\
         property list uchar int vertex_indices\nend_header\n",
    );
    for j in 0..3 {
        for i in 0..3 {
            text += &format!("{} -0.3 {} {}\n", 0.3 * i as f64, 0.3 * j as f64, 2.0 * i as f64);
        }
    }
    for [a, b, c, d] in [[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6], [4, 5, 8, 7]] {
        text += &format!("4 {a} {b} {c} {d}\n");
    }
    std::fs::write(&ply, text).unwrap();
    (obj, ply)
}

#[test]
fn renders_an_obj_and_a_ply_to_a_png_of_the_requested_size() {
    let dir = folder("ok");
    let (obj, ply) = write_inputs(&dir);
    let png_path = dir.join("x.png");
    let out = cloth()
        .arg("render")
        .args([&obj, &ply])
        .arg("-o")
        .arg(&png_path)
        .args(["--width", "640", "--height", "400"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));

    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&png_path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut pixels = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut pixels).unwrap();
    assert_eq!((info.width, info.height), (640, 400));
    assert_eq!(info.color_type, png::ColorType::Rgb);
    let pixels = &pixels[..info.buffer_size()];
    // Not a blank picture: many pixels differ from the top left corner's background, and
    // some are strongly coloured (the strain scale), not just shades of grey.
    let corner = &pixels[..3];
    let differing = pixels.chunks_exact(3).filter(|p| p != &corner).count();
    assert!(
        differing > 640 * 400 / 10,
        "only {differing} pixels differ from the background"
    );
    let saturated = pixels
        .chunks_exact(3)
        .filter(|p| p.iter().max().unwrap() - p.iter().min().unwrap() > 120)
        .count();
    assert!(saturated > 1000, "only {saturated} coloured pixels");
    // No temporary file is left beside the picture.
    let names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names.len(), 3, "{names:?}");
}

/// The RGB pixels of the PNG at `path`.
fn pixels(path: &std::path::Path) -> Vec<u8> {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut pixels = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut pixels).unwrap();
    pixels.truncate(info.buffer_size());
    pixels
}

/// A y-up file drawn with `--up-axis y` is the picture of the same mesh z-up.
#[test]
fn a_y_up_file_draws_upright_when_told() {
    let dir = folder("y_up");
    let (z_up, _) = write_inputs(&dir);
    // The tetrahedron turned (x, y, z) -> (x, z, -y), as `[output] up_axis = "y"` writes.
    let y_up = dir.join("y.obj");
    std::fs::write(
        &y_up,
        "v 0 0 0\nv 0.5 0 0\nv 0 0 -0.5\nv 0 0.5 0\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    )
    .unwrap();
    let draw = |file: &PathBuf, png: &str, extra: &[&str]| {
        let out = cloth()
            .arg("render")
            .arg(file)
            .arg("-o")
            .arg(dir.join(png))
            .args(["--width", "320", "--height", "200"])
            .args(extra)
            .output()
            .unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        pixels(&dir.join(png))
    };
    let upright = draw(&z_up, "z.png", &[]);
    let turned = draw(&y_up, "y.png", &["--up-axis", "y"]);
    let lying = draw(&y_up, "lying.png", &[]);
    // The same file with the header cloth writes draws upright by itself, unless told
    // otherwise (same name, so the same title).
    let headed_dir = dir.join("headed");
    std::fs::create_dir_all(&headed_dir).unwrap();
    let headed = headed_dir.join("y.obj");
    let header = "# the cloth, written by cloth 0.1.0\n# y up, metres: turned from the engine's z up, (x, y, z) -> (x, z, -y)\n";
    std::fs::write(
        &headed,
        format!("{header}{}", std::fs::read_to_string(&y_up).unwrap()),
    )
    .unwrap();
    assert_eq!(draw(&headed, "headed.png", &[]), turned, "read from its header");
    assert_eq!(
        draw(&headed, "told.png", &["--up-axis", "z"]),
        lying,
        "the flag wins"
    );
    let differ = |a: &[u8], b: &[u8]| {
        a.chunks_exact(3)
            .zip(b.chunks_exact(3))
            .filter(|(p, q)| p != q)
            .count()
    };
    // The title names the file, so a few pixels differ; the mesh does not.
    let turned_off = differ(&upright, &turned);
    let lying_off = differ(&upright, &lying);
    assert!(
        10 * turned_off < lying_off,
        "turned: {turned_off} pixels differ, lying down: {lying_off}"
    );
}

#[test]
fn a_missing_file_is_an_input_error_that_names_it() {
    let dir = folder("missing");
    let (obj, _) = write_inputs(&dir);
    let missing = dir.join("no-such-mesh.ply");
    let out = cloth()
        .arg("render")
        .args([&obj, &missing])
        .arg("-o")
        .arg(dir.join("x.png"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("no-such-mesh.ply"), "{stderr}");
    assert!(!dir.join("x.png").exists());
}

#[test]
fn a_malformed_file_is_an_input_error_and_an_unwritable_output_a_run_error() {
    let dir = folder("bad");
    let bad = dir.join("bad.ply");
    std::fs::write(
        &bad,
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n1\n",
    )
    .unwrap();
    let out = cloth()
        .arg("render")
        .arg(&bad)
        .arg("-o")
        .arg(dir.join("x.png"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("bad.ply"));

    let (obj, _) = write_inputs(&dir);
    let out = cloth()
        .arg("render")
        .arg(&obj)
        .arg("-o")
        .arg(dir.join("no-such-folder").join("x.png"))
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}
