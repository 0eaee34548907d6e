//! The scene file's records, as serde reads them.

use crate::collide::SurfaceOptions;
use crate::garment::mannequin::Measurements;
use crate::garment::sewing::{DrapeSettings, SewingSettings};
use cloth_core::{Fabric, KesMeasurement, RestCriteria, SolverSettings};
use serde::Deserialize;
use std::path::PathBuf;

/// A whole run.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    #[serde(default)]
    pub name: String,
    pub cloth: ClothSpec,
    pub fabric: FabricSpec,
    #[serde(default)]
    pub bodies: Vec<BodySpec>,
    /// The integrator of a sheet's run (a garment's stages have their own).
    #[serde(default)]
    pub solver: SolverSettings,
    /// When a sheet's run stops.
    #[serde(default)]
    pub rest: RestCriteria,
    #[serde(default)]
    pub sewing: SewingSettings,
    #[serde(default)]
    pub drape: DrapeSettings,
    #[serde(default)]
    pub output: OutputSpec,
}

/// What the cloth is.
#[derive(Debug, Clone, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum ClothSpec {
    /// A garment from a pattern: our TOML (`.toml`) or GarmentCode's JSON (`.json`).
    Garment {
        pattern: PathBuf,
        #[serde(default = "default_edge_length")]
        edge_length: f64,
    },
    /// A rectangular sheet of `nx` by `ny` particles, `size` m, its corner at `origin`,
    /// its warp along `u_axis` and weft along `v_axis`, the particles `pins` (as [i, j])
    /// held where they start.
    Grid {
        nx: usize,
        ny: usize,
        size: [f64; 2],
        #[serde(default)]
        origin: [f64; 3],
        #[serde(default = "x_axis")]
        u_axis: [f64; 3],
        #[serde(default = "y_axis")]
        v_axis: [f64; 3],
        #[serde(default)]
        pins: Vec<[usize; 2]>,
    },
}

fn default_edge_length() -> f64 {
    crate::garment::garment::DEFAULT_EDGE_LENGTH
}
fn x_axis() -> [f64; 3] {
    [1.0, 0.0, 0.0]
}
fn y_axis() -> [f64; 3] {
    [0.0, 1.0, 0.0]
}

/// The fabric: a preset by name, or SI values, or a Kawabata record (exactly one).
/// A garment's panels that name a preset get it instead.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FabricSpec {
    pub preset: Option<String>,
    pub si: Option<Fabric>,
    pub kes: Option<KesMeasurement>,
}

/// A rigid body: a generated mannequin, a mesh file, or a primitive (exactly one), placed
/// at `position`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    pub name: Option<String>,
    pub mannequin: Option<Measurements>,
    /// An OBJ or STL file.
    pub file: Option<PathBuf>,
    /// Scale applied to the file's coordinates (0.01 for centimetres).
    pub scale: Option<f64>,
    pub sphere: Option<SphereSpec>,
    #[serde(rename = "box")]
    pub cuboid: Option<BoxSpec>,
    #[serde(default)]
    pub position: [f64; 3],
    /// Contact thickness, m.
    pub thickness: Option<f64>,
    /// Coulomb coefficient (the fabric's when not given).
    pub friction: Option<f64>,
}

#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SphereSpec {
    pub radius: f64,
}

#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxSpec {
    pub size: [f64; 3],
}

/// What a run writes.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OutputSpec {
    /// The final cloth as OBJ with its material coordinates.
    pub obj: bool,
    /// The final cloth as PLY with per-vertex strain colours.
    pub ply: bool,
    /// The bodies as OBJ, to view with the cloth.
    pub bodies: bool,
}

impl Default for OutputSpec {
    fn default() -> Self {
        Self {
            obj: true,
            ply: true,
            bodies: true,
        }
    }
}

impl BodySpec {
    pub(crate) fn surface_options(&self) -> SurfaceOptions {
        SurfaceOptions {
            scale: self.scale.unwrap_or(1.0),
            ..SurfaceOptions::default()
        }
    }
}
