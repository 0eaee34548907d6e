//! The scene file's records, as serde reads them.

use super::frame::UpAxis;
use cloth_core::{Fabric, KesMeasurement, RestCriteria, SelfCollision, SolverSettings};
use cloth_garment::mannequin::Measurements;
use cloth_garment::pattern::EdgeRef;
use cloth_garment::sewing::{DrapeSettings, SewingSettings};
use serde::Deserialize;
use std::path::PathBuf;

/// A whole run.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// The run's name, in the report and the picture.
    #[serde(default)]
    pub name: String,
    /// What the cloth is: exactly one of the tables below.
    pub cloth: ClothSpec,
    /// The fabric: `preset = "..."`, `[fabric.si]` or `[fabric.kes]`.
    pub fabric: FabricSpec,
    /// The rigid bodies the cloth meets, each a `[[bodies]]` entry.
    #[serde(default)]
    pub bodies: Vec<BodySpec>,
    /// The integrator of a sheet's run (a garment's stages have their own).
    #[serde(default)]
    pub solver: SolverSettings,
    /// When a sheet's run stops.
    #[serde(default)]
    pub rest: RestCriteria,
    /// A garment's sewing stage (gravity off, the seams pulled shut).
    #[serde(default)]
    pub sewing: SewingSettings,
    /// A garment's draping stage (gravity on, until at rest).
    #[serde(default)]
    pub drape: DrapeSettings,
    /// The cloth's collision with itself, in every stage (on unless `enabled = false`).
    #[serde(default)]
    pub self_collision: SelfCollision,
    /// What the run writes.
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
    /// `pins` hold outline edges or whole panels, by name, where the sewing leaves them,
    /// for the whole drape (a garment on a hanger, a waistband held up).
    Garment {
        /// The pattern file, from the scene's folder.
        pattern: PathBuf,
        /// The target length of the mesh's edges, m (15 mm by default).
        #[serde(default = "default_edge_length")]
        edge_length: f64,
        /// Edges or panels held where the sewing leaves them (see below).
        #[serde(default)]
        pins: Vec<GarmentPin>,
    },
    /// A rectangular sheet of `nx` by `ny` particles, `size` m, its corner at `origin`,
    /// its warp along `u_axis` and weft along `v_axis`, the particles `pins` (as [i, j])
    /// held where they start.
    Grid {
        /// Particles along the warp.
        nx: usize,
        /// Particles along the weft.
        ny: usize,
        /// Width (warp) and height (weft), m.
        size: [f64; 2],
        /// The corner of particle [0, 0], m.
        #[serde(default)]
        origin: [f64; 3],
        /// The warp's direction ([1, 0, 0] by default).
        #[serde(default = "x_axis")]
        u_axis: [f64; 3],
        /// The weft's direction ([0, 1, 0] by default).
        #[serde(default = "y_axis")]
        v_axis: [f64; 3],
        /// Particles held where they start, as [i, j].
        #[serde(default)]
        pins: Vec<[usize; 2]>,
    },
    /// A sheet from a triangle mesh file (OBJ). Its texture coordinates (`vt`, times
    /// `uv_scale` to metres) are the material coordinates, the warp along u; a file without
    /// them must be flat, and is its own rest shape with the warp along x. `pins` are vertex
    /// numbers (from 0) held where they start; the cloth is turned from `up_axis` to z up,
    /// then by `rotation`, then moved by `position` (as a body's file is).
    Mesh {
        /// The OBJ file, from the scene's folder.
        file: PathBuf,
        /// Scale of the file's coordinates (0.01 for centimetres).
        #[serde(default = "one")]
        scale: f64,
        /// Scale of its texture coordinates to metres.
        #[serde(default = "one")]
        uv_scale: f64,
        /// The file's up axis, turned to z.
        #[serde(default = "z_up")]
        up_axis: UpAxis,
        /// Degrees about x, then y, then z.
        #[serde(default)]
        rotation: [f64; 3],
        /// Where the file's origin goes, m.
        #[serde(default)]
        position: [f64; 3],
        /// Vertex numbers (from 0) held where they start.
        #[serde(default)]
        pins: Vec<usize>,
    },
    /// The Cusick drape test (BS 5058): a 30 cm disk of the fabric, its central 18 cm
    /// clamped, drapes from flat; the report gives the drape coefficient and the folds.
    Cusick {
        /// The disk's mesh edge length, m.
        #[serde(default = "cusick_edge_length")]
        edge_length: f64,
        /// Rayleigh damping added to the fabric's while it settles, s.
        #[serde(default = "cusick_damping")]
        damping: f64,
    },
    /// The cantilever bending test (ASTM D1388): a 2.5 cm strip along the warp, `overhang`
    /// m of it beyond the platform's edge in `cells` cells, bends under its own weight; the
    /// report compares its tip with the inextensible elastica's.
    Cantilever {
        /// The strip's length beyond the edge, m.
        overhang: f64,
        /// Cells along that length.
        cells: usize,
    },
}

/// A garment's pin: an outline edge of a panel (by its name, or its index from 0 as
/// GarmentCode's unnamed edges are), or the whole panel when no edge is given.
#[derive(Debug, Clone, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GarmentPin {
    /// The panel's name.
    pub panel: String,
    /// One of its outline edges, by name or index; the whole panel when not given.
    #[serde(default)]
    pub edge: Option<EdgeRef>,
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

/// The fabric: a preset by name, SI values, or a Kawabata record. A garment's panels that
/// name a preset get it instead. In the file, exactly one of `preset = "..."`,
/// `[fabric.si]` or `[fabric.kes]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(try_from = "FabricTable")]
pub enum FabricSpec {
    Preset(String),
    Si(Fabric),
    Kes(KesMeasurement),
}

/// `[fabric]` as written, before it is known to say one thing.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FabricTable {
    preset: Option<String>,
    si: Option<Fabric>,
    kes: Option<KesMeasurement>,
}

impl TryFrom<FabricTable> for FabricSpec {
    type Error = String;
    fn try_from(t: FabricTable) -> Result<Self, String> {
        match (t.preset, t.si, t.kes) {
            (Some(name), None, None) => Ok(Self::Preset(name)),
            (None, Some(si), None) => Ok(Self::Si(si)),
            (None, None, Some(kes)) => Ok(Self::Kes(kes)),
            _ => Err("fabric: give exactly one of preset, [fabric.si] or [fabric.kes]".into()),
        }
    }
}

/// A rigid body: a shape, placed, with its contact layer. In the file, one `[[bodies]]`
/// entry with exactly one shape key (`mannequin`, `file`, `sphere`, `box`, `cylinder`,
/// `table`) beside the placement and contact keys.
#[derive(Debug, Clone, Deserialize)]
#[serde(try_from = "BodyTable")]
pub struct BodySpec {
    pub name: Option<String>,
    pub shape: BodyShape,
    pub placement: Placement,
    pub contact: ContactSpec,
}

/// What a body is.
#[derive(Debug, Clone)]
pub enum BodyShape {
    Mannequin(Measurements),
    File(FileSpec),
    Sphere(SphereSpec),
    Box(BoxSpec),
    /// Along z, centred on the body's position.
    Cylinder(CylinderSpec),
    /// A table standing on z = 0 below the body's position (its top's upper face at
    /// `height`).
    Table(TableSpec),
    /// A triangle mesh given in memory (Python's `Body.from_arrays`), loaded as a file's
    /// is; scene files name files instead.
    Mesh(MeshSpec),
}

/// A body's triangle mesh given in memory.
#[derive(Debug, Clone)]
pub struct MeshSpec {
    pub vertices: Vec<cloth_core::math::Vec3>,
    pub triangles: Vec<[u32; 3]>,
    /// Scale applied to the coordinates (0.01 for centimetres).
    pub scale: f64,
}

/// A body read from a mesh file.
#[derive(Debug, Clone)]
pub struct FileSpec {
    /// An OBJ, STL, PLY, glTF or GLB file.
    pub path: PathBuf,
    /// Scale applied to the file's coordinates (0.01 for centimetres).
    pub scale: f64,
}

/// Where a body stands: turned from its `up_axis` to z, then by `rotation`, then moved to
/// `position`.
#[derive(Debug, Clone, Copy, Default)]
pub struct Placement {
    /// The file's up axis, turned to our z (y: (x, y, z) -> (x, -z, y)); glTF files are
    /// y-up unless this says otherwise, other formats and shapes z-up.
    pub up_axis: Option<UpAxis>,
    /// Degrees about x, then y, then z (after the up axis is turned to z).
    pub rotation: [f64; 3],
    pub position: [f64; 3],
}

/// A body's contact layer: each `None` takes the default (the fabric's friction).
#[derive(Debug, Clone, Copy, Default)]
pub struct ContactSpec {
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

/// A `[[bodies]]` entry as written, before it is known to have one shape.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct BodyTable {
    /// The body's name in the report and the outputs.
    name: Option<String>,
    /// The parametric mannequin (see below); one shape key of mannequin, file, sphere,
    /// box, cylinder, table.
    mannequin: Option<Measurements>,
    /// A mesh file: OBJ, STL, PLY, glTF or GLB, from the scene's folder.
    file: Option<PathBuf>,
    /// Scale of a file's coordinates (0.01 for centimetres).
    scale: Option<f64>,
    /// A file's up axis, turned to z (glTF's is y unless given, the others' z).
    up_axis: Option<UpAxis>,
    /// Degrees about x, then y, then z, after the up axis is turned.
    #[serde(default)]
    rotation: [f64; 3],
    /// `{ radius = r }`, m, centred on `position`.
    sphere: Option<SphereSpec>,
    /// `{ size = [x, y, z] }`, m, centred on `position`.
    #[serde(rename = "box")]
    cuboid: Option<BoxSpec>,
    /// `{ radius = r, height = h }`, along z, centred on `position`.
    cylinder: Option<CylinderSpec>,
    /// `{ size = [w, d, t], height = h }` (and `leg_width`, `leg_inset`): a table on z = 0.
    table: Option<TableSpec>,
    /// Where the body goes, m.
    #[serde(default)]
    position: [f64; 3],
    /// The contact layer's thickness, m (3 mm by default).
    thickness: Option<f64>,
    /// The layer thinned where the body is flat, down to this, m.
    min_thickness: Option<f64>,
    /// The friction coefficient with the cloth (the fabric's by default).
    friction: Option<f64>,
}

impl TryFrom<BodyTable> for BodySpec {
    type Error = String;
    fn try_from(t: BodyTable) -> Result<Self, String> {
        let mut shapes = Vec::new();
        if let Some(m) = t.mannequin {
            shapes.push(BodyShape::Mannequin(m));
        }
        if let Some(path) = t.file {
            shapes.push(BodyShape::File(FileSpec {
                path,
                scale: t.scale.unwrap_or(1.0),
            }));
        }
        shapes.extend(t.sphere.map(BodyShape::Sphere));
        shapes.extend(t.cuboid.map(BodyShape::Box));
        shapes.extend(t.cylinder.map(BodyShape::Cylinder));
        shapes.extend(t.table.map(BodyShape::Table));
        let [shape] = <[BodyShape; 1]>::try_from(shapes).map_err(|_| {
            "a body: give exactly one of mannequin, file, sphere, box, cylinder or table".to_string()
        })?;
        if t.scale.is_some() && !matches!(shape, BodyShape::File(_)) {
            return Err("a body: `scale` applies to a body read from a file".into());
        }
        Ok(Self {
            name: t.name,
            shape,
            placement: Placement {
                up_axis: t.up_axis,
                rotation: t.rotation,
                position: t.position,
            },
            contact: ContactSpec {
                thickness: t.thickness,
                min_thickness: t.min_thickness,
                friction: t.friction,
            },
        })
    }
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

/// An animation file's format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum AnimationFormat {
    /// A point cache, `frames/<stage>.pc2`, which Blender's Mesh Cache modifier plays on
    /// the stage's mesh, `frames/<stage>.obj` (the same vertices in the same order).
    Pc2,
    /// A glTF binary, `frames/<stage>.glb`: the first frame's mesh, each later frame a
    /// morph target, and an animation of their weights over the simulated time, which
    /// Blender's glTF importer and three.js play; at most 150 frames, evenly chosen.
    Gltf,
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
    /// Record the cloth every this many steps of each stage (into `frames/`): as an OBJ
    /// per frame, or into one animation file per stage (`animation`). With an animation
    /// and no cadence, every step.
    pub frames_every: Option<u64>,
    /// The frames as one animation file per stage rather than an OBJ each.
    pub animation: Option<AnimationFormat>,
    /// Steps of each stage after which to record the largest warp and weft stretch (the
    /// source's table of stretch after N iterations).
    pub checkpoints: Vec<u64>,
    /// The up axis of the OBJ and PLY files (the cloth, its frames, the bodies), said in
    /// each file's header: z, the engine's own, or y, as Blender's, Maya's, Houdini's and
    /// Marvelous Designer's importers expect, turned `(x, y, z) -> (x, z, -y)`. glTF is
    /// always y up, as its specification says.
    pub up_axis: UpAxis,
    /// A garment's segmentation file (`segmentation.txt`): a line per vertex of the OBJ
    /// and PLY naming its panel, or the panels a seam vertex joins.
    pub segmentation: bool,
    /// Every step of every stage as a row of `history.csv`: the solver's iterations and
    /// residual, the energies, the fastest particle, the contacts, the step's time.
    pub history: bool,
    /// Plots for the report: the final strain's histogram (`strain.png`) and the residual
    /// and kinetic energy over the steps (`convergence.png`).
    pub plots: bool,
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
            animation: None,
            checkpoints: Vec::new(),
            up_axis: UpAxis::Z,
            segmentation: true,
            history: true,
            plots: true,
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

#[cfg(test)]
mod tests {
    use super::*;

    fn scene(rest: &str) -> Result<SceneFile, String> {
        let text = format!("[cloth.grid]\nnx = 3\nny = 3\nsize = [1.0, 1.0]\n{rest}");
        toml::from_str::<SceneFile>(&text).map_err(|e| e.to_string())
    }

    #[test]
    fn the_fabric_is_exactly_one_of_a_preset_si_values_or_a_kes_record() {
        let s = scene("[fabric]\npreset = \"silk\"\n").unwrap();
        assert!(matches!(&s.fabric, FabricSpec::Preset(name) if name == "silk"));
        for bad in [
            "[fabric]\n",
            "[fabric]\npreset = \"silk\"\n[fabric.si]\narea_density = 0.15\n\
             warp = { law = \"linear\", stiffness = 500.0 }\nweft = { law = \"linear\", stiffness = 500.0 }\n\
             compression_warp = 100.0\ncompression_weft = 100.0\nshear_modulus = 20.0\n\
             bending = { warp = 1e-5, weft = 1e-5 }\n",
        ] {
            let e = scene(bad).unwrap_err();
            assert!(e.contains("exactly one of preset"), "{e}");
        }
        let e = scene("[fabric]\npreset = \"silk\"\ncolour = \"red\"\n").unwrap_err();
        assert!(e.contains("colour"), "{e}");
    }

    #[test]
    fn a_body_is_one_shape_with_its_placement_and_contact() {
        let s = scene(
            "[fabric]\npreset = \"silk\"\n[[bodies]]\nfile = \"body.obj\"\nscale = 0.01\nup_axis = \"y\"\n\
             position = [0.0, 0.0, 1.0]\nfriction = 0.3\n[[bodies]]\nsphere = { radius = 0.2 }\n",
        )
        .unwrap();
        let [file, sphere] = &s.bodies[..] else {
            panic!("two bodies")
        };
        assert!(matches!(&file.shape, BodyShape::File(f) if f.scale == 0.01 && f.path.ends_with("body.obj")));
        assert_eq!(file.placement.up_axis, Some(UpAxis::Y));
        let with =
            scene("[fabric]\npreset = \"silk\"\n[output]\nanimation = \"pc2\"\nup_axis = \"y\"\n").unwrap();
        assert_eq!(with.output.animation, Some(AnimationFormat::Pc2));
        assert_eq!(with.output.up_axis, UpAxis::Y);
        let gltf = scene("[fabric]\npreset = \"silk\"\n[output]\nanimation = \"gltf\"\n").unwrap();
        assert_eq!(gltf.output.animation, Some(AnimationFormat::Gltf));
        let e = scene("[fabric]\npreset = \"silk\"\n[output]\nanimation = \"avi\"\n").unwrap_err();
        assert!(e.contains("pc2") && e.contains("gltf"), "{e}");
        assert_eq!(file.placement.position, [0.0, 0.0, 1.0]);
        assert_eq!(file.contact.friction, Some(0.3));
        assert!(matches!(&sphere.shape, BodyShape::Sphere(s) if s.radius == 0.2));
        assert_eq!(sphere.contact.thickness, None);
        for (bad, says) in [
            (
                "sphere = { radius = 0.2 }\nbox = { size = [1.0, 1.0, 1.0] }\n",
                "exactly one of mannequin",
            ),
            ("position = [0.0, 0.0, 1.0]\n", "exactly one of mannequin"),
            (
                "sphere = { radius = 0.2 }\nscale = 2.0\n",
                "`scale` applies to a body read from a file",
            ),
        ] {
            let e = scene(&format!("[fabric]\npreset = \"silk\"\n[[bodies]]\n{bad}")).unwrap_err();
            assert!(e.contains(says), "{bad}: {e}");
        }
    }
}
