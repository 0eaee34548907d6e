//! From a scene file to what runs: the cloth (a garment to sew or a sheet), its fabrics,
//! and the bodies. Everything a run needs is checked here, so `cloth check` finds what
//! `cloth run` would trip on.

use super::cloth_file::read_cloth_obj;
use super::error::{SceneErrorKind, SceneFileError};
use super::frame::{placement, UpAxis};
use super::records::{BodyShape, BodySpec, ClothSpec, FabricSpec, Placement, SceneFile};
use super::warning::SceneWarning;
use crate::presets::FabricLibrary;
use crate::validation::{Cantilever, CusickTest};
use cloth_collide::{Bodies, Body, SurfaceOptions, TriSurface};
use cloth_core::{math::Vec3, Fabric, GridBuilder, GridShape, Pin, SimulationBuilder};
use cloth_garment::mannequin::Mannequin;
use cloth_garment::{garmentcode, Garment, GarmentBuilder, Pattern};
use std::path::Path;
use std::sync::Arc;

/// How far apart panels overlapping in one plane are layered, m: several times the
/// contact distance of any fabric's layers, a fraction of a cell.
const LAYER_GAP: f64 = 0.002;

/// A scene ready to run.
pub struct Prepared {
    pub name: String,
    pub cloth: PreparedCloth,
    pub bodies: Arc<Bodies>,
    /// What the scene loads with that the user should know (imperfect body meshes,
    /// gathered seams, panels starting inside a body): the run goes on.
    pub warnings: Vec<SceneWarning>,
}

pub enum PreparedCloth {
    /// A garment to sew and drape, each panel with its fabric.
    Garment {
        garment: Box<Garment>,
        fabrics: Vec<Fabric>,
    },
    /// A sheet to run to rest, and the test that measures it at rest, if it is one.
    Sheet {
        builder: Box<SimulationBuilder>,
        test: Option<SheetTest>,
    },
}

/// A fabric test a sheet's run is: what to read from the cloth at rest.
pub enum SheetTest {
    Cusick,
    Cantilever { test: Box<Cantilever>, grid: GridShape },
}

impl SceneFile {
    /// Builds the cloth, fabrics and bodies. `file` names the scene in errors and `dir`
    /// is where its relative paths start.
    pub fn prepare(&self, file: &str, dir: &Path) -> Result<Prepared, SceneFileError> {
        let invalid = |key: &str, reason: String| SceneFileError::invalid(file, key, reason);
        let param = |source| SceneFileError::new(file, None, SceneErrorKind::Param(source));
        self.solver_settings().validate().map_err(param)?;
        self.rest.validate().map_err(param)?;
        self.sewing.validate().map_err(param)?;
        self.drape.validate().map_err(param)?;
        self.output
            .check()
            .map_err(|(key, reason)| invalid(key, reason))?;
        let library = FabricLibrary::builtin();
        let fabric = self.fabric.resolve(library).map_err(|e| match e {
            Ok(source) => SceneFileError::new(file, Some("fabric"), SceneErrorKind::Preset(source)),
            Err(reason) => invalid("fabric", reason),
        })?;
        fabric.validate().map_err(param)?;

        if let Some(triangles) = self.cloth.estimated_triangles() {
            // A NaN estimate (an edge length of NaN) is refused too.
            if triangles.is_nan() || triangles > self.max_triangles as f64 {
                return Err(invalid(
                    "cloth",
                    format!(
                        "the cloth would have about {triangles:.2e} triangles, over the limit of {} \
                         (max_triangles): make it coarser, or raise the limit",
                        self.max_triangles
                    ),
                ));
            }
        }
        let mut bodies = Vec::with_capacity(self.bodies.len());
        let mut warnings = Vec::new();
        for (k, spec) in self.bodies.iter().enumerate() {
            let built = spec.build(file, dir, &format!("bodies[{k}]"), self.cloth.longest_edge())?;
            for body in &built {
                warnings.extend(body.surface().defects().iter().map(|d| SceneWarning::Body {
                    body: format!("bodies[{k}] '{}'", body.name()),
                    defect: d.clone(),
                }));
            }
            bodies.extend(built);
        }
        let bodies = Arc::new(Bodies::new(bodies));

        let cloth = match &self.cloth {
            ClothSpec::Garment {
                pattern,
                edge_length,
                pins,
            } => {
                let path = dir.join(pattern);
                let is_json = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("json"));
                let pattern = if is_json {
                    garmentcode::from_path(&path, &garmentcode::ImportOptions::default())
                } else {
                    Pattern::from_toml_path(&path)
                }
                .map_err(|e| {
                    SceneFileError::new(file, Some("cloth.garment.pattern"), SceneErrorKind::Pattern(e))
                })?;
                warnings.extend(pattern.gathers().into_iter().map(SceneWarning::Gather));
                let pinned = pins
                    .iter()
                    .enumerate()
                    .map(|(k, pin)| {
                        let found = match &pin.edge {
                            Some(edge) => pattern
                                .find_edge(&pin.panel, edge)
                                .map(|s| (s.panel, Some(s.edge))),
                            None => pattern.find_panel(&pin.panel).map(|p| (p, None)),
                        };
                        found.map_err(|reason| {
                            invalid(
                                &format!("cloth.garment.pins[{k}]"),
                                format!("in '{}': {reason}", path.display()),
                            )
                        })
                    })
                    .collect::<Result<Vec<_>, _>>()?;
                let mut garment = GarmentBuilder::new(pattern)
                    .edge_length(*edge_length)
                    .max_triangles(self.max_triangles)
                    .file(path.display().to_string())
                    .build()
                    .map_err(|e| {
                        SceneFileError::new(file, Some("cloth.garment"), SceneErrorKind::Garment(e))
                    })?;
                for (panel, edge) in pinned {
                    garment.pin(panel, edge);
                }
                let fabrics = library.panel_fabrics(&garment, &fabric).map_err(|source| {
                    SceneFileError::new(
                        &path.display().to_string(),
                        Some("fabric"),
                        SceneErrorKind::Preset(source),
                    )
                })?;
                warnings.extend(
                    garment
                        .layer_overlapping(LAYER_GAP)
                        .into_iter()
                        .map(SceneWarning::Layers),
                );
                warnings.extend(garment.find_touching().into_iter().map(SceneWarning::Touching));
                warnings.extend(
                    garment
                        .move_out_of(&bodies)
                        .into_iter()
                        .map(SceneWarning::Placement),
                );
                PreparedCloth::Garment {
                    garment: Box::new(garment),
                    fabrics,
                }
            }
            ClothSpec::Grid {
                nx,
                ny,
                size,
                origin,
                u_axis,
                v_axis,
                pins,
            } => {
                let mesh = GridBuilder::new(*nx, *ny)
                    .size(size[0], size[1])
                    .origin(Vec3::from(*origin))
                    .axes(Vec3::from(*u_axis), Vec3::from(*v_axis))
                    .build()
                    .map_err(|source| {
                        SceneFileError::new(file, Some("cloth"), SceneErrorKind::Mesh(source))
                    })?;
                let g = mesh.grid().expect("a grid builder makes a grid");
                let mut builder = SimulationBuilder::new(mesh, fabric.clone());
                for (k, &[i, j]) in pins.iter().enumerate() {
                    if i >= *nx || j >= *ny {
                        return Err(invalid(
                            &format!("cloth.grid.pins[{k}]"),
                            format!("[{i}, {j}] is outside the {nx} x {ny} grid"),
                        ));
                    }
                    builder = builder.pin(Pin::fixed(g.index(i, j)));
                }
                sheet(builder, self, &bodies, None)
            }
            ClothSpec::Mesh {
                file: mesh_file,
                scale,
                uv_scale,
                up_axis,
                rotation,
                position,
                pins,
            } => {
                let path = dir.join(mesh_file);
                let placed = placement(*up_axis, *rotation, *position)
                    .map_err(|reason| invalid("cloth.mesh.rotation", reason))?;
                let mesh = read_cloth_obj(&path, *scale, *uv_scale, &placed).map_err(|reason| {
                    invalid("cloth.mesh.file", format!("'{}': {reason}", path.display()))
                })?;
                let n = mesh.vertex_count();
                if let Some((k, i)) = pins.iter().enumerate().find(|(_, &i)| i >= n) {
                    return Err(invalid(
                        &format!("cloth.mesh.pins[{k}]"),
                        format!("vertex {i}, but the mesh has {n} (numbered from 0)"),
                    ));
                }
                let builder = SimulationBuilder::new(mesh, fabric).pins(pins.iter().map(|&i| Pin::fixed(i)));
                sheet(builder, self, &bodies, None)
            }
            ClothSpec::Cusick { edge_length, damping } => {
                let mut test = CusickTest::new(fabric);
                test.edge_length = *edge_length;
                test.damping = *damping;
                let builder = test
                    .simulation_builder()
                    .map_err(|e| invalid("cloth.cusick", e.to_string()))?;
                sheet(builder, self, &bodies, Some(SheetTest::Cusick))
            }
            ClothSpec::Cantilever { overhang, cells } => {
                if !(overhang.is_finite() && *overhang > 0.0) || *cells < 2 {
                    return Err(invalid(
                        "cloth.cantilever",
                        format!("overhang {overhang} m in {cells} cells: give an overhang > 0 and at least 2 cells"),
                    ));
                }
                let test = Cantilever {
                    fabric,
                    overhang: *overhang,
                    cells: *cells,
                };
                let (builder, grid) = test
                    .simulation_builder()
                    .map_err(|e| invalid("cloth.cantilever", e.to_string()))?;
                sheet(
                    builder,
                    self,
                    &bodies,
                    Some(SheetTest::Cantilever {
                        test: Box::new(test),
                        grid,
                    }),
                )
            }
        };
        Ok(Prepared {
            name: self.name.clone(),
            cloth,
            bodies,
            warnings,
        })
    }
}

/// The longest edges of a garment's mesh over its target edge length: GarmentCode's
/// rand_1_002 at 1.5 cm has its 99th percentile at 1.24 times it, its longest at 1.39.
const GARMENT_LONG_EDGE: f64 = 1.4;

impl ClothSpec {
    /// The cloth's longest edges, m, known before it is built; `None` for a mesh read from
    /// a file and for the cantilever test's strip.
    fn longest_edge(&self) -> Option<f64> {
        match *self {
            ClothSpec::Garment { edge_length, .. } | ClothSpec::Cusick { edge_length, .. } => {
                Some(GARMENT_LONG_EDGE * edge_length)
            }
            // A grid's cells are cut along a diagonal.
            ClothSpec::Grid { nx, ny, size, .. } => {
                Some((size[0] / (nx.max(2) - 1) as f64).hypot(size[1] / (ny.max(2) - 1) as f64))
            }
            ClothSpec::Mesh { .. } | ClothSpec::Cantilever { .. } => None,
        }
    }

    /// The triangles a generated cloth would have, known before it is built; `None` for
    /// what is sized by its file (a mesh, whose size the file bounds, or a pattern, which
    /// the garment builder sizes itself).
    fn estimated_triangles(&self) -> Option<f64> {
        match *self {
            ClothSpec::Grid { nx, ny, .. } => Some(2.0 * (nx as f64 - 1.0) * (ny as f64 - 1.0)),
            ClothSpec::Cusick { edge_length, .. } => {
                let disk = std::f64::consts::PI * crate::validation::cusick::SPECIMEN_RADIUS.powi(2);
                Some(cloth_garment::garment::triangles_in(disk, edge_length))
            }
            ClothSpec::Cantilever { overhang, cells } => {
                let across = crate::validation::cantilever::STRIP_WIDTH * cells as f64 / overhang;
                Some(2.0 * (cells as f64 + 1.0) * across.max(2.0))
            }
            ClothSpec::Garment { .. } | ClothSpec::Mesh { .. } => None,
        }
    }
}

/// A sheet's run with the scene's solver settings, on the bodies if there are any.
fn sheet(
    builder: SimulationBuilder,
    scene: &SceneFile,
    bodies: &Arc<Bodies>,
    test: Option<SheetTest>,
) -> PreparedCloth {
    let builder = builder.settings(scene.solver_settings());
    let builder = if bodies.bodies().is_empty() {
        builder
    } else {
        builder.collider(bodies.clone())
    };
    PreparedCloth::Sheet {
        builder: Box::new(builder),
        test,
    }
}

impl FabricSpec {
    /// The fabric: `Ok(Err(_))` carries a preset lookup error, `Err(_)` a form error.
    fn resolve(
        &self,
        library: &FabricLibrary,
    ) -> Result<Fabric, Result<crate::presets::PresetError, String>> {
        match self {
            FabricSpec::Preset(name) => library.fabric(name).map_err(Ok),
            FabricSpec::Si(si) => Ok(si.clone()),
            FabricSpec::Kes(kes) => kes.to_fabric().map(|c| c.fabric).map_err(|e| Err(e.to_string())),
        }
    }
}

impl BodySpec {
    /// The bodies this entry makes (a mannequin with arms makes three). `file` and `key`
    /// name the entry in errors; relative paths start at `dir`; `cloth_edge` is the
    /// cloth's longest edge, m, if known, which a thinned contact layer needs.
    pub fn build(
        &self,
        file: &str,
        dir: &Path,
        key: &str,
        cloth_edge: Option<f64>,
    ) -> Result<Vec<Body>, SceneFileError> {
        let key = key.to_string();
        let surface_error =
            |source| SceneFileError::new(file, Some(&key), SceneErrorKind::Surface(Box::new(source)));
        let named = |default: &str| self.name.clone().unwrap_or_else(|| default.to_string());
        let surfaces: Vec<(String, TriSurface)> = match &self.shape {
            BodyShape::Mannequin(m) => {
                let mannequin = Mannequin::new(m).map_err(|source| {
                    SceneFileError::new(
                        file,
                        Some(&format!("{key}.mannequin")),
                        SceneErrorKind::Mannequin(Box::new(source)),
                    )
                })?;
                mannequin
                    .surfaces()
                    .into_iter()
                    .map(|(part, s)| (format!("{} {part}", named("mannequin")), s.clone()))
                    .collect()
            }
            BodyShape::File(f) => {
                let path = dir.join(&f.path);
                let options = SurfaceOptions {
                    scale: f.scale,
                    ..SurfaceOptions::default()
                };
                let surface = TriSurface::read(&path, &options).map_err(surface_error)?;
                vec![(named(&path.display().to_string()), surface)]
            }
            BodyShape::Mesh(m) => {
                let options = SurfaceOptions {
                    scale: m.scale,
                    ..SurfaceOptions::default()
                };
                let surface = TriSurface::new(m.vertices.clone(), m.triangles.clone(), &options)
                    .map_err(surface_error)?;
                vec![(named("mesh"), surface)]
            }
            BodyShape::Sphere(sphere) => vec![(
                named("sphere"),
                TriSurface::icosphere(sphere.radius, 4).map_err(surface_error)?,
            )],
            BodyShape::Box(b) => {
                let half = Vec3::from(b.size) / 2.0;
                vec![(named("box"), TriSurface::cuboid(half).map_err(surface_error)?)]
            }
            BodyShape::Cylinder(c) => {
                let surface = TriSurface::cylinder(c.radius, 0.5 * c.height, 64).map_err(surface_error)?;
                vec![(named("cylinder"), surface)]
            }
            BodyShape::Table(t) => {
                let half = Vec3::from(t.size) / 2.0;
                let surface = TriSurface::table(half, t.height, 0.5 * t.leg_width, t.leg_inset)
                    .map_err(surface_error)?;
                vec![(named("table"), surface)]
            }
        };
        let Placement {
            up_axis,
            rotation,
            position,
        } = self.placement;
        let up = match (up_axis, &self.shape) {
            (Some(up), _) => up,
            (None, BodyShape::File(f)) => UpAxis::of_file(&f.path),
            (None, _) => UpAxis::Z,
        };
        let pose = placement(up, rotation, position)
            .map_err(|reason| SceneFileError::invalid(file, &format!("{key}.rotation"), reason))?;
        let body_error = |source| SceneFileError::new(file, Some(&key), SceneErrorKind::Body(source));
        surfaces
            .into_iter()
            .map(|(name, surface)| {
                let mut body = Body::new(name, surface).with_pose(pose).map_err(body_error)?;
                if let Some(t) = self.contact.thickness {
                    body = body.with_thickness(t).map_err(body_error)?;
                }
                if let Some(floor) = self.contact.min_thickness {
                    let Some(edge) = cloth_edge else {
                        return Err(SceneFileError::invalid(
                            file,
                            &format!("{key}.min_thickness"),
                            "a layer thinned to the cloth's edges needs a cloth whose edge length \
                             is known before it is built (a garment, a grid, a Cusick test)"
                                .into(),
                        ));
                    };
                    body = body.with_thinned_layer(edge, floor).map_err(body_error)?;
                }
                if let Some(mu) = self.contact.friction {
                    body = body.with_friction(mu).map_err(body_error)?;
                }
                Ok(body)
            })
            .collect()
    }
}
