//! The fabric validation report: simulated against reference, as tables.
//!
//!     cargo run --release --example fabric_validation
//!
//! Prints the presets, the cantilever against the elastica, the fixed-angle bending
//! length, the Cusick drape of every preset against the measured ranges, and the hanging
//! strip with a J-shaped law. Writes each draped Cusick specimen as an OBJ and its shadow
//! as an SVG to `target/validation/`.

use cloth::formats::obj::write_cloth_obj;
use cloth::presets::FabricLibrary;
use cloth::validation::cantilever::bending_length;
use cloth::validation::cusick::{SPECIMEN_RADIUS, SUPPORT_RADIUS};
use cloth::validation::{fixed_angle, Cantilever, CusickResult, CusickTest, HangingStrip};
use std::error::Error;
use std::path::Path;

/// The measured drape ranges of fabrics.md, by preset.
const RANGES: [(&str, f64, f64); 4] = [
    ("silk", 20.0, 40.0),
    ("cotton_poplin", 60.0, 76.0),
    ("denim", 70.0, 90.0),
    ("wang_black_denim", 70.0, 90.0),
];

fn main() -> Result<(), Box<dyn Error>> {
    let library = FabricLibrary::builtin();
    let out = Path::new("target/validation");
    std::fs::create_dir_all(out)?;

    println!("## Presets (assets/fabrics.toml)\n");
    println!("| preset | form | g/m^2 | bending length warp / weft, cm | shear G, N/m | tension at 1% warp / weft, N/m | friction |");
    println!("|---|---|---|---|---|---|---|");
    for p in library.presets() {
        let f = &p.fabric;
        let c = |b: f64| 100.0 * (b / (f.area_density * 9.81)).cbrt();
        println!(
            "| {} | {:?} | {:.0} | {:.2} / {:.2} | {:.1} | {:.2} / {:.2} | {:.2} |",
            p.name,
            p.form,
            1000.0 * f.area_density,
            c(f.bending.warp),
            c(f.bending.weft),
            f.shear_modulus,
            f.warp.extension(0.01).tension,
            f.weft.extension(0.01).tension,
            f.friction
        );
    }

    let fabric = library.fabric("cotton_poplin")?;
    println!("\n## Cantilever, 2.5 cm strip of cotton_poplin (warp), against the elastica\n");
    println!("| Gamma | overhang, cm | cells | tip drop / L | elastica | error |");
    println!("|---|---|---|---|---|---|");
    for gamma in [0.5, 1.0, 2.0, 4.0, 8.0, 20.0] {
        for cells in [20, 40] {
            let test = Cantilever::at_gamma(fabric.clone(), gamma, cells);
            let rest = test.run()?;
            let (sim, reference) = (rest.drop / test.overhang, test.reference_drop());
            println!(
                "| {gamma} | {:.2} | {cells} | {sim:.4} | {reference:.4} | {:+.2}% |",
                100.0 * test.overhang,
                100.0 * (sim / reference - 1.0)
            );
        }
    }

    println!("\n## Fixed-angle test (41.5 degrees), bending length\n");
    println!("| preset | simulated c = l/2, cm | (B/w)^(1/3), cm | error |");
    println!("|---|---|---|---|");
    for name in ["silk", "cotton_poplin", "wool_suiting", "wang_black_denim"] {
        let fabric = library.fabric(name)?;
        let c = bending_length(&fabric);
        let result = fixed_angle(&fabric, c / 16.0)?;
        println!(
            "| {name} | {:.3} | {:.3} | {:+.2}% |",
            100.0 * result.bending_length,
            100.0 * c,
            100.0 * (result.bending_length / c - 1.0)
        );
    }

    println!("\n## Cusick drape, 30 cm specimen on an 18 cm support\n");
    println!("| preset | drape coefficient | measured range | folds | steps |");
    println!("|---|---|---|---|---|");
    for p in library.presets() {
        let result = CusickTest::new(p.fabric.clone()).run()?;
        let range = RANGES
            .iter()
            .find(|r| r.0 == p.name)
            .map_or("".to_string(), |r| format!("{}-{}%", r.1, r.2));
        println!(
            "| {} | {:.1}% | {range} | {} | {} |",
            p.name, result.drape_coefficient, result.folds, result.steps
        );
        let obj = out.join(format!("cusick_{}.obj", p.name));
        write_cloth_obj(&obj, &result.positions, &result.triangles)?;
        write_svg(&out.join(format!("cusick_{}.svg", p.name)), &p.name, &result)?;
    }

    println!("\n## Hanging strip, 1 m x 5 cm, with a J-shaped law (knit_jersey, along the course)\n");
    let rest = HangingStrip {
        fabric: library.fabric("knit_jersey")?,
        length: 1.0,
        width: 0.05,
        rows: 101,
    }
    .run()?;
    println!("| tension at the top, N/m | strain at the top | inverse of the law | error |");
    println!("|---|---|---|---|");
    println!(
        "| {:.3} | {:.5} | {:.5} | {:+.3}% |",
        rest.top_tension,
        rest.top_strain,
        rest.expected_strain,
        100.0 * (rest.top_strain / rest.expected_strain - 1.0)
    );
    println!("\nDraped specimens: {}/cusick_*.obj and .svg", out.display());
    Ok(())
}

/// The shadow's outline from above, with the specimen and support circles.
fn write_svg(path: &Path, name: &str, result: &CusickResult) -> std::io::Result<()> {
    let scale = 1000.0; // 1 px per mm
    let c = SPECIMEN_RADIUS * scale + 20.0;
    let points: Vec<String> = result
        .outline
        .iter()
        .enumerate()
        .map(|(k, r)| {
            let a = std::f64::consts::TAU * k as f64 / result.outline.len() as f64;
            format!("{:.1},{:.1}", c + r * scale * a.cos(), c - r * scale * a.sin())
        })
        .collect();
    let svg = format!(
        r##"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">
<rect width="100%" height="100%" fill="white"/>
<circle cx="{c}" cy="{c}" r="{rs}" fill="none" stroke="#999" stroke-dasharray="4 4"/>
<polygon points="{pts}" fill="#4a7fb5" fill-opacity="0.6" stroke="#1f4e79"/>
<circle cx="{c}" cy="{c}" r="{rd}" fill="#ddd" stroke="#555"/>
<text x="10" y="{ty}" font-family="sans-serif" font-size="14">{name}: DC {dc:.1}%, {folds} folds</text>
</svg>
"##,
        w = 2.0 * c,
        h = 2.0 * c + 24.0,
        rs = SPECIMEN_RADIUS * scale,
        rd = SUPPORT_RADIUS * scale,
        pts = points.join(" "),
        ty = 2.0 * c + 16.0,
        dc = result.drape_coefficient,
        folds = result.folds,
    );
    std::fs::write(path, svg)
}
