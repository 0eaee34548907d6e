//! Every reader of user input, driven with random mutations of real inputs: scene files,
//! patterns (our TOML and GarmentCode's JSON), cloth OBJ files and body meshes (OBJ, STL,
//! PLY, glTF). Whatever the bytes, a reader answers with a value or an error: it does not
//! panic, it answers within a bounded time, and it does not take more than a bounded
//! amount of memory on the way.
//!
//! The mutations are seeded, so a failure repeats; the input that failed is written to
//! the target's scratch folder and named in the message.

use cloth::collide::{Body, SurfaceOptions, TriSurface};
use cloth::garment::{garmentcode, GarmentBuilder, Pattern};
use cloth::scene_file::{read_cloth_obj, SceneFile};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use std::alloc::{GlobalAlloc, Layout, System};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

/// Counts the bytes held and the most held since the last reset.
struct Tracking;
static HELD: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

fn held(delta: isize) {
    let now = if delta >= 0 {
        HELD.fetch_add(delta as usize, Ordering::Relaxed) + delta as usize
    } else {
        HELD.fetch_sub(delta.unsigned_abs(), Ordering::Relaxed) - delta.unsigned_abs()
    };
    PEAK.fetch_max(now, Ordering::Relaxed);
}

unsafe impl GlobalAlloc for Tracking {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        held(layout.size() as isize);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        held(-(layout.size() as isize));
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        held(new_size as isize - layout.size() as isize);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Tracking = Tracking;

/// The most one input may take on top of what was held before it. The largest valid
/// input here (the T-shirt scene with its mannequin) takes under 100 MB.
const MEMORY_LIMIT: usize = 1 << 30;
/// The longest one input may take: a guard against hangs, not a speed target (valid ones
/// take well under a second in an optimised build).
const TIME_LIMIT: Duration = Duration::from_secs(60);
/// Cloth meshes larger than this are refused in these runs, to keep them short; the limit
/// itself is tested with its default in tests/input_errors.rs.
const MAX_TRIANGLES: usize = 100_000;

fn asset(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

/// What a reader is given: the file's bytes, named with its extension.
type Reader = fn(&Path) -> Result<(), String>;

fn read_scene(path: &Path) -> Result<(), String> {
    let text = std::fs::read_to_string(path).map_err(|e| e.to_string())?;
    let mut scene = SceneFile::from_toml_str(&text, "fuzz").map_err(|e| e.to_string())?;
    scene.max_triangles = scene.max_triangles.min(MAX_TRIANGLES);
    scene
        .prepare("fuzz", &asset("assets/scenes"))
        .map(|_| ())
        .map_err(|e| e.to_string())
}

fn build(pattern: Pattern) -> Result<(), String> {
    GarmentBuilder::new(pattern)
        .max_triangles(MAX_TRIANGLES)
        .build()
        .map(|_| ())
        .map_err(|e| e.to_string())
}

fn read_pattern_toml(path: &Path) -> Result<(), String> {
    build(Pattern::from_toml_path(path).map_err(|e| e.to_string())?)
}

fn read_pattern_json(path: &Path) -> Result<(), String> {
    let options = garmentcode::ImportOptions::default();
    build(garmentcode::from_path(path, &options).map_err(|e| e.to_string())?)
}

fn read_cloth(path: &Path) -> Result<(), String> {
    read_cloth_obj(path, 1.0, 1.0, &nalgebra::Isometry3::identity()).map(|_| ())
}

fn read_body(path: &Path) -> Result<(), String> {
    let surface = TriSurface::read(path, &SurfaceOptions::default()).map_err(|e| e.to_string())?;
    let body = Body::new("fuzz", surface);
    // The queries a run makes: a point in the middle of the body and one far off.
    let (lo, hi) = body.surface().bounding_box();
    for p in [0.5 * (lo + hi), 2.0 * hi - lo] {
        body.signed_distance(0.0, &p);
    }
    Ok(())
}

/// Numbers a typo, a unit mix-up or an attacker might write.
const EXTREMES: [&str; 12] = [
    "0",
    "-0",
    "1e308",
    "-1e308",
    "1e-308",
    "nan",
    "inf",
    "-1",
    "4294967296",
    "1e9",
    "0.0000001",
    "18446744073709551616",
];

/// One random change: a byte flipped, a run deleted, duplicated or inserted, the file cut
/// short, or a number replaced by an extreme one.
fn mutate(input: &[u8], rng: &mut StdRng) -> Vec<u8> {
    let mut out = input.to_vec();
    let len = out.len().max(1);
    match rng.random_range(0..6) {
        0 => {
            for _ in 0..rng.random_range(1..8) {
                let i = rng.random_range(0..len).min(out.len().saturating_sub(1));
                if let Some(b) = out.get_mut(i) {
                    *b ^= 1 << rng.random_range(0..8);
                }
            }
        }
        1 => {
            let a = rng.random_range(0..len).min(out.len());
            let b = (a + rng.random_range(0..64)).min(out.len());
            out.drain(a..b);
        }
        2 => {
            let a = rng.random_range(0..len).min(out.len());
            let b = (a + rng.random_range(0..256)).min(out.len());
            let copy = out[a..b].to_vec();
            for _ in 0..rng.random_range(1..4) {
                let at = rng.random_range(0..=out.len());
                out.splice(at..at, copy.iter().copied());
            }
        }
        3 => {
            let at = rng.random_range(0..=out.len());
            let junk: Vec<u8> = (0..rng.random_range(1..16)).map(|_| rng.random()).collect();
            out.splice(at..at, junk);
        }
        4 => out.truncate(rng.random_range(0..len)),
        _ => {
            // Replace a number-looking run of ASCII with an extreme value.
            let starts: Vec<usize> = (0..out.len())
                .filter(|&i| out[i].is_ascii_digit() && (i == 0 || !out[i - 1].is_ascii_digit()))
                .collect();
            if let Some(&a) = starts.get(rng.random_range(0..starts.len().max(1))) {
                let mut b = a;
                while b < out.len() && (out[b].is_ascii_digit() || b".eE-+".contains(&out[b])) {
                    b += 1;
                }
                let value = EXTREMES[rng.random_range(0..EXTREMES.len())];
                out.splice(a..b, value.bytes());
            }
        }
    }
    out
}

/// Runs `reader` on `cases` mutations of each seed file, one at a time in a thread of its
/// own, checking time, memory and panics.
fn fuzz(name: &str, seeds: &[&str], extension: &str, reader: Reader, cases: usize) {
    let seeds: Vec<(String, Vec<u8>)> = seeds
        .iter()
        .map(|s| (s.to_string(), std::fs::read(asset(s)).unwrap()))
        .collect();
    fuzz_bytes(name, &seeds, extension, reader, cases);
}

/// One input at a time: the memory measure is the whole process's.
static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());

fn fuzz_bytes(name: &str, seeds: &[(String, Vec<u8>)], extension: &str, reader: Reader, cases: usize) {
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let scratch = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("input_fuzz")
        .join(name);
    std::fs::create_dir_all(&scratch).unwrap();
    let mut rng = StdRng::seed_from_u64(0x5eed ^ name.len() as u64);
    let (mut accepted, mut refused) = (0, 0);
    for (seed, original) in seeds {
        let mut input = original.clone();
        for case in 0..cases {
            // Mostly one change to the seed; sometimes a change on top of the last input,
            // to wander further.
            input = mutate(if rng.random_bool(0.7) { original } else { &input }, &mut rng);
            let path = scratch.join(format!("case.{extension}"));
            std::fs::write(&path, &input).unwrap();
            let kept = scratch.join(format!("failed_{case}.{extension}"));
            let baseline = HELD.load(Ordering::Relaxed);
            PEAK.store(baseline, Ordering::Relaxed);
            let (tx, rx) = std::sync::mpsc::channel();
            let job = path.clone();
            std::thread::spawn(move || {
                let result = std::panic::catch_unwind(|| reader(&job));
                let _ = tx.send(result);
            });
            let fail = |what: String| {
                std::fs::write(&kept, &input).unwrap();
                panic!(
                    "{name} from {seed}, case {case}: {what}; the input is {}",
                    kept.display()
                );
            };
            match rx.recv_timeout(TIME_LIMIT) {
                Err(_) => fail(format!("no answer in {} s", TIME_LIMIT.as_secs())),
                Ok(Err(_)) => fail("the reader panicked".into()),
                Ok(Ok(Ok(()))) => accepted += 1,
                Ok(Ok(Err(message))) => {
                    if message.trim().is_empty() {
                        fail("an error with no message".into());
                    }
                    refused += 1;
                }
            }
            let peak = PEAK.load(Ordering::Relaxed).saturating_sub(baseline);
            if peak > MEMORY_LIMIT {
                fail(format!("took {} MB", peak >> 20));
            }
        }
    }
    eprintln!("{name}: {accepted} accepted, {refused} refused with an error");
    assert!(
        accepted > 0,
        "no mutation of {seeds:?} was valid: the seeds are not exercised"
    );
}

#[test]
fn scene_files() {
    let seeds = [
        "assets/scenes/skirt.toml",
        "assets/scenes/sheet_on_sphere.toml",
        "assets/scenes/cusick.toml",
    ];
    fuzz("scene", &seeds, "toml", read_scene, 200);
}

#[test]
fn toml_patterns() {
    fuzz(
        "pattern_toml",
        &["assets/patterns/dress.toml", "assets/patterns/tshirt.toml"],
        "toml",
        read_pattern_toml,
        500,
    );
}

#[test]
fn garmentcode_patterns() {
    let seeds = [
        "assets/garmentcode/patterns/rand_1_001.json",
        "assets/garmentcode/patterns/rand_1_057.json",
    ];
    fuzz("pattern_json", &seeds, "json", read_pattern_json, 500);
}

#[test]
fn cloth_obj_files() {
    // A 4 x 4 sheet with its texture coordinates, and the same flat without them.
    let (mut with_uv, mut flat) = (String::new(), String::new());
    for j in 0..4 {
        for i in 0..4 {
            with_uv += &format!(
                "v {} {} {}\nvt {} {}\n",
                0.1 * i as f64,
                0.0,
                0.1 * j as f64,
                0.1 * i as f64,
                0.1 * j as f64
            );
            flat += &format!("v {} {} 0\n", 0.1 * i as f64, 0.1 * j as f64);
        }
    }
    for j in 0..3 {
        for i in 0..3 {
            let k = 1 + i + 4 * j;
            with_uv += &format!(
                "f {k}/{k} {}/{} {}/{} {}/{}\n",
                k + 1,
                k + 1,
                k + 5,
                k + 5,
                k + 4,
                k + 4
            );
            flat += &format!("f {k} {} {} {}\n", k + 1, k + 5, k + 4);
        }
    }
    let seeds = [
        ("sheet with vt".to_string(), with_uv.into_bytes()),
        ("flat sheet".to_string(), flat.into_bytes()),
    ];
    fuzz_bytes("cloth_obj", &seeds, "obj", read_cloth, 600);
}

#[test]
fn body_meshes() {
    let data = "crates/cloth-collide/tests/data";
    for (file, extension) in [
        ("cube_quads.obj", "obj"),
        ("cube_ascii.stl", "stl"),
        ("cube_binary.stl", "stl"),
        ("cube.ply", "ply"),
        ("cube_binary.ply", "ply"),
        ("cube.gltf", "gltf"),
        ("cube.glb", "glb"),
    ] {
        let seed = format!("{data}/{file}");
        fuzz(&format!("body_{file}"), &[&seed], extension, read_body, 600);
    }
}
