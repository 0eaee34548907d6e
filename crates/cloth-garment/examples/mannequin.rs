//! Writes the shipped dress forms, `assets/bodies/mannequin.obj` (default measurements, no
//! arms) and `assets/bodies/mannequin_arms.obj` (the same with default arms), and prints
//! their landmarks and girths. The tests check the files still match the generator, so run
//! this after changing it:
//!
//!     cargo run --release -p cloth-garment --example mannequin

use std::path::Path;

use cloth_garment::mannequin::{Mannequin, Measurements};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/bodies"));
    std::fs::create_dir_all(dir)?;
    let plain = Measurements::default();
    for (file, m) in [
        ("mannequin.obj", plain),
        ("mannequin_arms.obj", plain.with_arms()),
    ] {
        let mannequin = Mannequin::new(&m)?;
        let path = dir.join(file);
        mannequin.write_obj(&path)?;
        println!("{}:", path.display());
        summary(&mannequin);
    }
    Ok(())
}

fn summary(mannequin: &Mannequin) {
    let lm = mannequin.landmarks();
    println!("  landmarks: {lm:#?}");
    for (name, z, target) in mannequin.measured_girths() {
        let girth = mannequin.girth_at(z);
        println!(
            "  {name} girth at z = {z:.4}: {girth:.6} m (measurement {target} m, {:+.2e} relative)",
            girth / target - 1.0
        );
    }
    for (name, surface) in mannequin.surfaces() {
        let (lo, hi) = surface.bounding_box();
        println!(
            "  {name}: {} vertices, {} triangles, volume {:.6} m^3, area {:.4} m^2, box {:.4?} to {:.4?}",
            surface.vertices().len(),
            surface.triangles().len(),
            surface.volume(),
            surface.area(),
            lo.as_slice(),
            hi.as_slice()
        );
    }
    for (name, axis) in ["left_arm", "right_arm"].iter().zip(mannequin.arm_axes()) {
        println!("  {name} axis: {axis:.4?}");
    }
}
