//! The `cloth` command: a thin layer over the library. Exit status 0 on success, 2 when the
//! input is at fault (a bad scene, pattern, body or fabric), 1 when a valid run fails.

mod failure;
mod progress;
mod commands;
mod drape;
mod render;

use clap::{Args, Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "cloth",
    version,
    about = "Cloth simulation: drape fabric and garments on bodies"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Simulate a scene and write its outputs.
    Run {
        scene: PathBuf,
        /// Output folder (default: the scene's name beside it, with `.out`).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Write into an existing output folder.
        #[arg(long)]
        force: bool,
        /// Print nothing but errors.
        #[arg(long, conflicts_with = "verbose")]
        quiet: bool,
        /// Print every step's statistics.
        #[arg(long)]
        verbose: bool,
    },
    /// Parse and validate a scene, its patterns, bodies and fabrics, without simulating.
    Check { scene: PathBuf },
    /// List the fabric presets, or show one in SI units.
    Fabrics { name: Option<String> },
    /// Run the standard benchmark scenes and print JSON (time per step, CG iterations,
    /// particles), to track speed over time.
    Bench {
        /// Steps timed per scene.
        #[arg(long, default_value_t = 60)]
        steps: usize,
        /// About a tenth of the particles: a smoke test, not a measurement.
        #[arg(long)]
        quick: bool,
        /// Also the hanging sheet from 3,025 to 199,809 particles (55 to 447 a side) and the
        /// dress sewn at 2, 1, 1/2 and 1/4 times its edge length (about 3,000 to 190,000),
        /// for how a step's cost grows (with --quick, 12 to 48 a side and the dress at 14
        /// and 7 cm).
        #[arg(long)]
        scaling: bool,
    },
    /// Drape many patterns on one body, each into OUT/<pattern name>/ with the outputs of
    /// `run`, and write OUT/summary.json and summary.md. Patterns finished by an earlier
    /// batch with the same body, fabric and edge length are skipped. Exit status 0 when
    /// every pattern finished, 1 when some failed, 2 for bad input.
    Drape(drape::DrapeArgs),
    /// Write a generated mannequin as OBJ.
    Mannequin(MannequinArgs),
    /// Render meshes (OBJ, PLY) to a PNG picture.
    Render(render::RenderArgs),
}

/// The mannequin's measurements, m (the defaults are the shipped average body).
#[derive(Args)]
struct MannequinArgs {
    #[arg(long, default_value_t = 1.68)]
    height: f64,
    #[arg(long, default_value_t = 0.92)]
    bust: f64,
    #[arg(long, default_value_t = 0.76)]
    waist: f64,
    #[arg(long, default_value_t = 0.98)]
    hip: f64,
    #[arg(long, default_value_t = 0.40)]
    shoulder_width: f64,
    #[arg(long, default_value_t = 0.36)]
    neck_girth: f64,
    /// With arms (average proportions).
    #[arg(long)]
    arms: bool,
    #[arg(short, long)]
    output: PathBuf,
}

impl MannequinArgs {
    fn measurements(&self) -> cloth::garment::mannequin::Measurements {
        let m = cloth::garment::mannequin::Measurements {
            height: self.height,
            bust: self.bust,
            waist: self.waist,
            hip: self.hip,
            shoulder_width: self.shoulder_width,
            neck_girth: self.neck_girth,
            arms: None,
        };
        if self.arms {
            m.with_arms()
        } else {
            m
        }
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run {
            scene,
            out,
            force,
            quiet,
            verbose,
        } => {
            let verbosity = match (quiet, verbose) {
                (true, _) => progress::Verbosity::Quiet,
                (_, true) => progress::Verbosity::Verbose,
                _ => progress::Verbosity::Normal,
            };
            commands::run(&scene, out, force, verbosity)
        }
        Command::Check { scene } => commands::check(&scene),
        Command::Fabrics { name } => commands::fabrics(name.as_deref()),
        Command::Bench {
            steps,
            quick,
            scaling,
        } => commands::bench(steps, quick, scaling),
        Command::Mannequin(args) => commands::mannequin(args.measurements(), &args.output),
        Command::Render(args) => render::render(&args),
        Command::Drape(args) => drape::drape(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(f) => {
            eprintln!("error: {}", f.message);
            ExitCode::from(f.status)
        }
    }
}
