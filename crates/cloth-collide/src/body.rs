//! A rigid body: a surface, the contact surfaces over it (all of it the cloth can reach,
//! and its thick parts alone), how it moves, and its contact properties.

use crate::contact_mesh::{ContactMesh, LocalPoint};
use crate::layer::thinned_layer;
use crate::surface::{SharpFeature as SurfaceFeature, TriSurface};
use crate::thin_parts::{thin_triangles, THIN_PART};
use crate::Motion;
use cloth_core::{math::Vec3, ParticlePath};
use nalgebra::{Isometry3, Point3};

/// Default contact thickness, m: a few millimetres, about a fabric's thickness.
pub const DEFAULT_THICKNESS: f64 = 0.003;
/// Default fold angle above which an edge counts as sharp, rad (30 degrees).
pub const DEFAULT_SHARP_ANGLE: f64 = std::f64::consts::PI / 6.0;

fn finite<'a>(values: impl IntoIterator<Item = &'a f64>) -> bool {
    values.into_iter().all(|c| c.is_finite())
}

/// A body parameter out of range.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("body `{body}`: `{name}` = {value} is invalid: {expected}")]
pub struct BodyError {
    pub body: String,
    pub name: &'static str,
    pub value: f64,
    pub expected: &'static str,
}

/// A rigid body the cloth collides with. Build with [`Body::new`] and the `with_` methods.
#[derive(Debug, Clone)]
pub struct Body {
    name: String,
    surface: TriSurface,
    /// The surface's triangles the cloth can reach (those inside other parts left out).
    full: ContactMesh,
    /// The body's chord under each of them, up to [`THIN_PART`].
    chords: Vec<f64>,
    /// The world's up in the body's frame as placed, which tells arms from feet.
    up: Vec3,
    /// Those of them over the body's thick parts, for cloth passing through its thin parts.
    thick: Thick,
    sharp: Vec<SurfaceFeature>,
    sharp_angle: f64,
    motion: Motion,
    /// The contact thickness, m: everywhere, or the most anywhere when `layer` thins it.
    thickness: f64,
    /// The contact layer thinned where the surface is flat (see [`crate::layer`]): the
    /// cloth's edge length and the floor it was made for, m, and its thickness at each of
    /// the surface's vertices.
    layer: Option<Layer>,
    /// `None`: the fabric's own coefficient applies.
    friction: Option<f64>,
    /// Largest distance of a surface vertex from the local origin.
    radius: f64,
}

/// The body as cloth passing through its thin parts meets it.
#[derive(Debug, Clone)]
enum Thick {
    /// It has no thin part.
    Whole,
    /// Its thick parts (boxed: a body without thin parts carries no second mesh).
    Parts(Box<ContactMesh>),
    /// It is thin all over (a plate).
    Nothing,
}

/// The body's thick parts, `up` being the world's up in its frame.
fn thick_parts(
    surface: &TriSurface,
    full: &ContactMesh,
    chords: &[f64],
    up: &Vec3,
    sharp: &[SurfaceFeature],
    angle: f64,
) -> Thick {
    let thin = thin_triangles(surface.vertices(), full.triangles(), chords, up);
    let thick_triangles: Vec<[u32; 3]> = full
        .triangles()
        .iter()
        .zip(&thin)
        .filter(|(_, &thin)| !thin)
        .map(|(t, _)| *t)
        .collect();
    if thick_triangles.len() == full.triangles().len() {
        Thick::Whole
    } else if thick_triangles.is_empty() {
        Thick::Nothing
    } else {
        // Open where the thin parts were: its winding number tells inside from outside.
        Thick::Parts(Box::new(ContactMesh::new(
            surface.vertices(),
            thick_triangles,
            false,
            sharp,
            angle,
        )))
    }
}

/// A contact layer thinned where the surface is flat.
#[derive(Debug, Clone)]
struct Layer {
    edge_length: f64,
    floor: f64,
    at_vertex: Vec<f64>,
}

/// Which of a body a query meets.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Parts {
    All,
    /// Its thick parts only (see [`crate::thin_parts`]).
    Thick,
}

/// Where a path or a point stands relative to one body, in the world frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct BodyPoint {
    pub point: Vec3,
    pub normal: Vec3,
    pub distance: f64,
    pub crossed: bool,
    /// Fraction of the path at the entry (1 for a plain proximity).
    pub entry: f64,
    /// The contact thickness there, m.
    pub thickness: f64,
}

impl Body {
    /// A static body at the identity pose with the default contact properties.
    pub fn new(name: impl Into<String>, surface: TriSurface) -> Self {
        let mut reachable: Vec<[u32; 3]> = (0..surface.triangles().len())
            .filter(|&t| !surface.is_buried(t))
            .map(|t| surface.triangles()[t])
            .collect();
        // The outermost points of a surface lie inside no part, so some triangle is always
        // reachable; should rounding say otherwise, contact uses them all.
        if reachable.is_empty() {
            reachable = surface.triangles().to_vec();
        }
        let radius = surface.vertices().iter().map(|v| v.norm()).fold(0.0, f64::max);
        let angle = DEFAULT_SHARP_ANGLE;
        let sharp = reachable_features(&surface, &reachable, angle);
        let full = ContactMesh::new(
            surface.vertices(),
            reachable,
            surface.is_watertight(),
            &sharp,
            angle,
        );
        let chords = full.chords(THIN_PART);
        let up = Vec3::z();
        let thick = thick_parts(&surface, &full, &chords, &up, &sharp, angle);
        Self {
            name: name.into(),
            surface,
            full,
            chords,
            up,
            thick,
            sharp,
            sharp_angle: angle,
            motion: Motion::default(),
            thickness: DEFAULT_THICKNESS,
            layer: None,
            friction: None,
            radius,
        }
    }

    fn check(
        &self,
        ok: bool,
        name: &'static str,
        value: f64,
        expected: &'static str,
    ) -> Result<(), BodyError> {
        if ok {
            Ok(())
        } else {
            Err(BodyError {
                body: self.name.clone(),
                name,
                value,
                expected,
            })
        }
    }

    /// Places the body (static).
    pub fn with_pose(self, pose: Isometry3<f64>) -> Result<Self, BodyError> {
        self.with_motion(Motion::Static(pose))
    }
    /// Makes the body move. A path's poses are checked as the simulation asks for them.
    pub fn with_motion(mut self, motion: Motion) -> Result<Self, BodyError> {
        let pose_ok =
            |p: &Isometry3<f64>| finite(p.translation.vector.iter().chain(p.rotation.coords.iter()));
        match &motion {
            Motion::Static(pose) => {
                self.check(pose_ok(pose), "pose", f64::NAN, "finite translation and rotation")?
            }
            Motion::Spin {
                pose,
                center,
                axis,
                rate,
            } => {
                self.check(pose_ok(pose), "pose", f64::NAN, "finite translation and rotation")?;
                self.check(finite(center.iter()), "center", f64::NAN, "a finite point")?;
                self.check(finite(axis.iter()), "axis", f64::NAN, "a finite unit vector")?;
                self.check(rate.is_finite(), "rate", *rate, "a finite rate in rad/s")?;
            }
            Motion::Linear { pose, velocity } => {
                self.check(pose_ok(pose), "pose", f64::NAN, "finite translation and rotation")?;
                self.check(
                    finite(velocity.iter()),
                    "velocity",
                    f64::NAN,
                    "a finite velocity in m/s",
                )?;
            }
            Motion::Path(_) => {}
        }
        self.motion = motion;
        let up = self.pose(0.0).inverse_transform_vector(&Vec3::z());
        if (up - self.up).norm() > 1e-9 {
            self.up = up;
            self.thick = thick_parts(
                &self.surface,
                &self.full,
                &self.chords,
                &up,
                &self.sharp,
                self.sharp_angle,
            );
        }
        Ok(self)
    }
    /// Contact thickness, m: the cloth is kept this far from the surface.
    pub fn with_thickness(mut self, thickness: f64) -> Result<Self, BodyError> {
        self.check(
            thickness > 0.0 && thickness.is_finite(),
            "thickness",
            thickness,
            "a positive thickness in m (a few millimetres)",
        )?;
        self.thickness = thickness;
        if let Some(layer) = self.layer.take() {
            return self.with_thinned_layer(layer.edge_length, layer.floor);
        }
        Ok(self)
    }
    /// Thins the contact layer where the surface is flat (see [`crate::layer`]): at each
    /// point, `floor` plus the dip of a straight edge of the cloth, `edge_length` long, over
    /// the surface's convex curvature there, up to the body's thickness (m).
    pub fn with_thinned_layer(mut self, edge_length: f64, floor: f64) -> Result<Self, BodyError> {
        self.check(
            edge_length > 0.0 && edge_length.is_finite(),
            "edge_length",
            edge_length,
            "the cloth's edge length, a positive length in m",
        )?;
        self.check(
            floor > 0.0 && floor <= self.thickness,
            "min_thickness",
            floor,
            "a positive thickness in m, at most the body's thickness",
        )?;
        let at_vertex = thinned_layer(
            self.surface.vertices(),
            self.full.triangles(),
            edge_length,
            floor,
            self.thickness,
        );
        self.layer = Some(Layer {
            edge_length,
            floor,
            at_vertex,
        });
        Ok(self)
    }
    /// Coulomb friction coefficient of cloth on this body, in place of the fabric's own;
    /// `f64::INFINITY` is the source's no-slip condition.
    pub fn with_friction(mut self, friction: f64) -> Result<Self, BodyError> {
        self.check(
            friction >= 0.0,
            "friction",
            friction,
            "a non-negative coefficient (infinity for no slip)",
        )?;
        self.friction = Some(friction);
        Ok(self)
    }
    /// Fold angle (rad) above which an edge counts as sharp and is kept out of cloth
    /// triangles; pi or more turns the feature pass off for this body.
    pub fn with_sharp_angle(mut self, angle: f64) -> Result<Self, BodyError> {
        self.check(angle > 0.0, "sharp_angle", angle, "a positive angle in radians")?;
        self.sharp_angle = angle;
        self.sharp = reachable_features(&self.surface, self.full.triangles(), angle);
        self.full.reshade(self.surface.vertices(), &self.sharp, angle);
        if let Thick::Parts(thick) = &mut self.thick {
            thick.reshade(self.surface.vertices(), &self.sharp, angle);
        }
        Ok(self)
    }

    pub fn name(&self) -> &str {
        &self.name
    }
    pub fn surface(&self) -> &TriSurface {
        &self.surface
    }
    pub fn motion(&self) -> &Motion {
        &self.motion
    }
    /// The contact thickness, m: the most anywhere, if the layer is thinned where the
    /// surface is flat.
    pub fn thickness(&self) -> f64 {
        self.thickness
    }
    /// The thinnest the contact layer is anywhere, m.
    pub fn min_thickness(&self) -> f64 {
        self.layer.as_ref().map_or(self.thickness, |l| {
            l.at_vertex.iter().copied().fold(self.thickness, f64::min)
        })
    }
    /// The body's own coefficient, if it sets one (otherwise the fabric's applies).
    pub fn friction(&self) -> Option<f64> {
        self.friction
    }
    /// The sharp edges and corners, in the body's own frame.
    pub fn sharp_features(&self) -> &[SurfaceFeature] {
        &self.sharp
    }
    pub fn pose(&self, t: f64) -> Isometry3<f64> {
        self.motion.pose(t)
    }
    pub(crate) fn radius(&self) -> f64 {
        self.radius
    }

    /// The surface in the world frame at time `t`.
    pub fn surface_at(&self, t: f64) -> TriSurface {
        self.surface.transformed(&self.pose(t))
    }

    /// How many of the body's triangles the segment from `a` to `b` passes through at
    /// time `t` (see [`cloth_core::Collider::segment_crossings`]).
    pub fn segment_crossings(&self, t: f64, a: &Vec3, b: &Vec3) -> usize {
        self.segment_crossings_of(Parts::All, t, a, b)
    }

    /// As [`Body::segment_crossings`], of the body's `parts`.
    pub(crate) fn segment_crossings_of(&self, parts: Parts, t: f64, a: &Vec3, b: &Vec3) -> usize {
        let Some(surface) = self.contact_mesh(parts) else {
            return 0;
        };
        let pose = self.pose(t);
        let (p, q) = (
            pose.inverse_transform_point(&Point3::from(*a)).coords,
            pose.inverse_transform_point(&Point3::from(*b)).coords,
        );
        surface.segment_crossings(&p, &q)
    }

    /// The contact surface of the body's `parts`, if it has any.
    fn contact_mesh(&self, parts: Parts) -> Option<&ContactMesh> {
        match (parts, &self.thick) {
            (Parts::All, _) | (Parts::Thick, Thick::Whole) => Some(&self.full),
            (Parts::Thick, Thick::Parts(thick)) => Some(thick),
            (Parts::Thick, Thick::Nothing) => None,
        }
    }

    /// Signed distance of `x` from the surface at time `t` (negative inside), with no
    /// distance limit.
    pub fn signed_distance(&self, t: f64, x: &Vec3) -> f64 {
        let p = self.pose(t).inverse_transform_point(&Point3::from(*x)).coords;
        self.full.signed_distance(&p)
    }

    /// The fraction of the body's reachable surface over thin parts (see [`crate::thin_parts`]).
    pub fn thin_fraction(&self) -> f64 {
        match &self.thick {
            Thick::Whole => 0.0,
            Thick::Nothing => 1.0,
            Thick::Parts(thick) => 1.0 - thick.triangles().len() as f64 / self.full.triangles().len() as f64,
        }
    }

    /// The first entry into the body (its `parts`) along the straight `path`, relative
    /// to the body; else the nearest surface point to its end within `max_distance`. The
    /// path test is skipped when the path is shorter than `min_start_distance`, a lower
    /// bound on the distance of its start.
    pub(crate) fn sweep(
        &self,
        parts: Parts,
        path: &ParticlePath,
        min_start_distance: f64,
        max_distance: f64,
    ) -> Option<BodyPoint> {
        let &ParticlePath { t0, x0, t1, x1 } = path;
        let surface = self.contact_mesh(parts)?;
        let pose1 = self.pose(t1);
        let p1 = pose1.inverse_transform_point(&Point3::from(x1)).coords;
        let p0 = if t0 == t1 {
            pose1.inverse_transform_point(&Point3::from(x0)).coords
        } else {
            self.pose(t0).inverse_transform_point(&Point3::from(x0)).coords
        };
        let LocalPoint {
            point,
            normal,
            distance,
            crossed,
            entry,
            corners,
            weights,
        } = surface.sweep(&p0, &p1, min_start_distance, max_distance, self.radius)?;
        let thickness = self.layer.as_ref().map_or(self.thickness, |l| {
            (0..3)
                .map(|k| weights[k] * l.at_vertex[corners[k] as usize])
                .sum()
        });
        Some(BodyPoint {
            point: (pose1 * Point3::from(point)).coords,
            normal: pose1.rotation * normal,
            distance,
            crossed,
            entry,
            thickness,
        })
    }
}

/// The sharp edges and corners of `surface` on its `reachable` triangles: those of parts
/// buried inside others are out of the cloth's reach.
fn reachable_features(surface: &TriSurface, reachable: &[[u32; 3]], angle: f64) -> Vec<SurfaceFeature> {
    let mut used = vec![false; surface.vertices().len()];
    reachable.iter().flatten().for_each(|&i| used[i as usize] = true);
    let mut features = surface.sharp_features(angle);
    features.retain(|f| used[f.a as usize] && used[f.b as usize]);
    features
}
