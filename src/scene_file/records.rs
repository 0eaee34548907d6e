//! The scene file's records, as serde reads them.

use super::frame::UpAxis;
use cloth_collide::SurfaceOptions;
use cloth_core::{Fabric, KesMeasurement, RestCriteria, SelfCollision, SolverSettings};
use cloth_garment::mannequin::Measurements;
use cloth_garment::sewing::{DrapeSettings, SewingSettings};
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
    /// The cloth's collision with itself, in every stage (on unless `enabled = false`).
    #[serde(default)]
    pub self_collision: SelfCollision,
    #[serde(default)]
    pub output: OutputSpec,
    /// The largest cloth mesh the scene may make, in triangles: a pattern in the wrong
    /// units or a grid of a billion cells is refused before anything is built.
    #[serde(default = "default_max_triangles")]
    pub max_triangles: usize,
}

fn default_max_triangles() -> usize {
    cloth_garment::garment::DEFAULT_MAX_TRIANGLES
}

impl SceneFile {
    /// The settings of a sheet's run: `[solver]` with the scene's self-collision.
    pub fn solver_settings(&self) -> SolverSettings {
        SolverSettings {
            self_collision: self.self_collision,
            ..self.solver.clone()
        }
    }
    /// The sewing stage's settings: `[sewing]` with the scene's self-collision.
    pub fn sewing_settings(&self) -> SewingSettings {
        SewingSettings {
            self_collision: self.self_collision,
            ..self.sewing
        }
    }
    /// The draping stage's settings: `[drape]` with the scene's self-collision.
    pub fn drape_settings(&self) -> DrapeSettings {
        DrapeSettings {
            self_collision: self.self_collision,
            ..self.drape
        }
    }
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
    /// A sheet from a triangle mesh file (OBJ). Its texture coordinates (`vt`, times
    /// `uv_scale` to metres) are the material coordinates, the warp along u; a file without
    /// them must be flat, and is its own rest shape with the warp along x. `pins` are vertex
    /// numbers (from 0) held where they start; the cloth is turned from `up_axis` to z up,
    /// then by `rotation`, then moved by `position` (as a body's file is).
    Mesh {
        file: PathBuf,
        #[serde(default = "one")]
        scale: f64,
        #[serde(default = "one")]
        uv_scale: f64,
        #[serde(default = "z_up")]
        up_axis: UpAxis,
        #[serde(default)]
        rotation: [f64; 3],
        #[serde(default)]
        position: [f64; 3],
        #[serde(default)]
        pins: Vec<usize>,
    },
    /// The Cusick drape test (BS 5058): a 30 cm disk of the fabric, its central 18 cm
    /// clamped, drapes from flat; the report gives the drape coefficient and the folds.
    Cusick {
        #[serde(default = "cusick_edge_length")]
        edge_length: f64,
        /// Rayleigh damping added to the fabric's while it settles, s.
        #[serde(default = "cusick_damping")]
        damping: f64,
    },
    /// The cantilever bending test (ASTM D1388): a 2.5 cm strip along the warp, `overhang`
    /// m of it beyond the platform's edge in `cells` cells, bends under its own weight; the
    /// report compares its tip with the inextensible elastica's.
    Cantilever { overhang: f64, cells: usize },
}

fn one() -> f64 {
    1.0
}
fn z_up() -> UpAxis {
    UpAxis::Z
}
fn cusick_edge_length() -> f64 {
    0.0075
}
fn cusick_damping() -> f64 {
    0.01
}

fn default_edge_length() -> f64 {
    cloth_garment::garment::DEFAULT_EDGE_LENGTH
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

/// A rigid body: a generated mannequin, a mesh file, or a primitive (exactly one), turned
/// by `rotation` and placed at `position`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    pub name: Option<String>,
    pub mannequin: Option<Measurements>,
    /// An OBJ, STL, PLY, glTF or GLB file.
    pub file: Option<PathBuf>,
    /// Scale applied to the file's coordinates (0.01 for centimetres).
    pub scale: Option<f64>,
    /// The file's up axis, turned to our z (y: (x, y, z) -> (x, -z, y)); glTF files are y-up
    /// unless this says otherwise, other formats z-up.
    pub up_axis: Option<UpAxis>,
    /// Degrees about x, then y, then z (after the up axis is turned to z).
    #[serde(default)]
    pub rotation: [f64; 3],
    pub sphere: Option<SphereSpec>,
    #[serde(rename = "box")]
    pub cuboid: Option<BoxSpec>,
    /// Along z, centred on `position`.
    pub cylinder: Option<CylinderSpec>,
    /// A table standing on z = 0 below `position` (its top's upper face at `height`).
    pub table: Option<TableSpec>,
    #[serde(default)]
    pub position: [f64; 3],
    /// Contact thickness, m.
    pub thickness: Option<f64>,
    /// Thins the contact layer where the body is flat, down to this, m: at each point of
    /// the surface the layer is this plus the dip of the cloth's longest edges over the
    /// surface's convex curve there, up to `thickness` (see `cloth_collide::Body::with_thinned_layer`).
    /// For a cloth whose edge length is known before it is built (a garment, a grid, a
    /// Cusick test).
    pub min_thickness: Option<f64>,
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

#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CylinderSpec {
    pub radius: f64,
    pub height: f64,
}

/// A table: a top of `size` (width, depth, thickness) on four legs.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TableSpec {
    pub size: [f64; 3],
    pub height: f64,
    #[serde(default = "leg_width")]
    pub leg_width: f64,
    #[serde(default = "leg_inset")]
    pub leg_inset: f64,
}

fn leg_width() -> f64 {
    0.06
}
fn leg_inset() -> f64 {
    0.05
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
    /// The bodies and the cloth (with strain colours) as one glTF binary.
    pub glb: bool,
    /// A picture of the final state (bodies and cloth, coloured by warp and weft strain).
    pub png: bool,
    /// The picture's width and height, pixels.
    pub image_size: [u32; 2],
    /// Write the cloth as OBJ every this many steps of each stage (into `frames/`).
    pub frames_every: Option<u64>,
    /// Steps of each stage after which to record the largest warp and weft stretch (the
    /// source's table of stretch after N iterations).
    pub checkpoints: Vec<u64>,
}

impl Default for OutputSpec {
    fn default() -> Self {
        Self {
            obj: true,
            ply: true,
            bodies: true,
            glb: true,
            png: true,
            image_size: [1600, 1000],
            frames_every: None,
            checkpoints: Vec::new(),
        }
    }
}

impl OutputSpec {
    /// What cannot be written: the reason and the key.
    pub(crate) fn check(&self) -> Result<(), (&'static str, String)> {
        let [w, h] = self.image_size;
        cloth_render::check_image_size(w, h).map_err(|reason| ("output.image_size", reason))?;
        if self.frames_every == Some(0) {
            return Err(("output.frames_every", "must be at least 1 step".into()));
        }
        if self.checkpoints.contains(&0) {
            return Err(("output.checkpoints", "steps count from 1".into()));
        }
        Ok(())
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
