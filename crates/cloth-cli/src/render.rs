//! `cloth render`: meshes to a PNG picture, all in one panel, framed together. A PLY with
//! strain (as `cloth run` writes) keeps its colours and gets the legend; meshes without
//! colours are told apart by neutral tints.

use crate::drape::Axis;
use crate::failure::Failure;
use cloth::render::{
    check_image_size, figure, read_render_mesh, Colouring, Legend, MeshColours, Panel, View, NEUTRAL_GREY,
};
use std::path::PathBuf;

/// Tints for meshes without colours, in order of the files: grey first (the body, as a
/// rule), then soft hues that read as different materials without shouting.
const TINTS: [[u8; 3]; 6] = [
    NEUTRAL_GREY,
    [150, 178, 214],
    [222, 196, 150],
    [160, 200, 160],
    [214, 160, 168],
    [186, 168, 214],
];

#[derive(clap::Args)]
pub struct RenderArgs {
    /// Meshes to draw together (OBJ, PLY).
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// The PNG file to write.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Picture width, pixels.
    #[arg(long, default_value_t = 1600)]
    pub width: u32,
    /// Picture height, pixels.
    #[arg(long, default_value_t = 1000)]
    pub height: u32,
    /// Degrees around the vertical from the front (-y); positive turns towards +x.
    #[arg(long, default_value_t = View::default().azimuth_deg, allow_negative_numbers = true)]
    pub azimuth: f64,
    /// Degrees above the horizon (-89 to 89).
    #[arg(long, default_value_t = View::default().elevation_deg, allow_negative_numbers = true)]
    pub elevation: f64,
    /// The files' up axis: y for most avatar assets, turned to z up as a scene reads them.
    /// By default each file's own header says (cloth's OBJ and PLY outputs name their
    /// frame, `[output] up_axis = "y"` or not); z, the engine's, where it does not.
    #[arg(long, value_enum)]
    pub up_axis: Option<Axis>,
}

/// The up axis a file's header declares, as cloth writes it in its OBJ and PLY outputs
/// (a comment line starting "y up" or "z up"); `None` when its first lines say nothing.
fn declared_up_axis(path: &std::path::Path) -> Option<Axis> {
    use std::io::Read;
    let mut head = Vec::new();
    std::fs::File::open(path)
        .ok()?
        .take(4096)
        .read_to_end(&mut head)
        .ok()?;
    String::from_utf8_lossy(&head).lines().take(40).find_map(|line| {
        let comment = line
            .strip_prefix('#')
            .or_else(|| line.strip_prefix("comment"))?
            .trim_start();
        if comment.starts_with("y up") {
            Some(Axis::Y)
        } else if comment.starts_with("z up") {
            Some(Axis::Z)
        } else {
            None
        }
    })
}

pub fn render(args: &RenderArgs) -> Result<(), Failure> {
    check_image_size(args.width, args.height)
        .map_err(|e| Failure::input(format!("--width, --height: {e}")))?;
    for (name, value) in [("--azimuth", args.azimuth), ("--elevation", args.elevation)] {
        if !value.is_finite() {
            return Err(Failure::input(format!(
                "{name} must be a number of degrees, not {value}"
            )));
        }
    }
    let mut meshes = Vec::with_capacity(args.files.len());
    let mut plain = 0;
    for path in &args.files {
        let mut loaded = read_render_mesh(path).map_err(Failure::input)?;
        if let Some(Axis::Y) = args.up_axis.or_else(|| declared_up_axis(path)) {
            let turn = cloth::scene_file::UpAxis::Y.to_z_up();
            for p in &mut loaded.mesh.positions {
                *p = turn * *p;
            }
        }
        if loaded.colouring == Colouring::Plain {
            loaded.mesh.colours = MeshColours::Uniform(TINTS[plain % TINTS.len()]);
            plain += 1;
        }
        meshes.push(loaded);
    }
    let legend = meshes.iter().any(|m| m.wants_legend()).then(|| Legend {
        caption: "strain".to_string(),
    });
    let names: Vec<String> = args
        .files
        .iter()
        .map(|p| {
            p.file_name()
                .unwrap_or(p.as_os_str())
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    let panel = Panel {
        title: names.join(", "),
        meshes: meshes.iter().map(|m| &m.mesh).collect(),
    };
    let view = View {
        azimuth_deg: args.azimuth,
        elevation_deg: args.elevation,
    };
    let image = figure(&[panel], legend.as_ref(), &view, args.width, args.height);
    image
        .write_png(&args.output)
        .map_err(|e| Failure::run(format!("cannot write '{}': {e}", args.output.display())))?;
    println!(
        "wrote {} ({} x {})",
        args.output.display(),
        args.width,
        args.height
    );
    Ok(())
}
