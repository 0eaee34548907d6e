//! A rigid body: a surface, its parry mesh and BVH (and its winding numbers when it is not
//! watertight), how it moves, and its contact properties.

use crate::convert::{from_parry, to_parry};
use crate::surface::{SharpFeature as SurfaceFeature, TriSurface, WindingTree};
use crate::Motion;
use cloth_core::self_contact::geometry::segment_crosses_triangle;
use cloth_core::Vec3;
use nalgebra::{Isometry3, Point3};
use parry3d_f64::bounding_volume::Aabb;
use parry3d_f64::query::{PointQuery, PointQueryWithLocation, Ray, RayCast};
use parry3d_f64::shape::{TriMesh, TriMeshFlags, TrianglePointLocation};
use std::collections::HashSet;

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
    mesh: TriMesh,
    /// Inside/outside for a surface that is not watertight; `None`: the pseudonormals of
    /// `mesh` answer it.
    winding: Option<WindingTree>,
    sharp: Vec<SurfaceFeature>,
    sharp_angle: f64,
    shading: Shading,
    motion: Motion,
    thickness: f64,
    /// `None`: the fabric's own coefficient applies.
    friction: Option<f64>,
    /// Largest distance of a surface vertex from the local origin.
    radius: f64,
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
}

impl Body {
    /// A static body at the identity pose with the default contact properties.
    pub fn new(name: impl Into<String>, surface: TriSurface) -> Self {
        let vertices = surface.vertices().iter().map(to_parry).collect();
        let mut reachable: Vec<[u32; 3]> = (0..surface.triangles().len())
            .filter(|&t| !surface.is_buried(t))
            .map(|t| surface.triangles()[t])
            .collect();
        // The outermost points of a surface lie inside no part, so some triangle is always
        // reachable; should rounding say otherwise, contact uses them all.
        if reachable.is_empty() {
            reachable = surface.triangles().to_vec();
        }
        // A watertight surface's pseudonormals give a sound inside/outside answer; any other
        // asks its winding number.
        let (flags, winding) = if surface.is_watertight() {
            (TriMeshFlags::ORIENTED, None)
        } else {
            (
                TriMeshFlags::empty(),
                Some(WindingTree::new(surface.vertices(), surface.triangles())),
            )
        };
        let mesh =
            TriMesh::with_flags(vertices, reachable.clone(), flags).expect("a TriSurface has triangles");
        let radius = surface.vertices().iter().map(|v| v.norm()).fold(0.0, f64::max);
        let sharp = reachable_features(&surface, &reachable, DEFAULT_SHARP_ANGLE);
        let shading = Shading::new(surface.vertices(), &reachable, &sharp, DEFAULT_SHARP_ANGLE);
        Self {
            name: name.into(),
            surface,
            mesh,
            winding,
            sharp,
            sharp_angle: DEFAULT_SHARP_ANGLE,
            shading,
            motion: Motion::default(),
            thickness: DEFAULT_THICKNESS,
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
        let reachable: Vec<[u32; 3]> = self.mesh.indices().to_vec();
        self.sharp = reachable_features(&self.surface, &reachable, angle);
        self.shading = Shading::new(self.surface.vertices(), &reachable, &self.sharp, angle);
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
    pub fn thickness(&self) -> f64 {
        self.thickness
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
        let pose = self.pose(t);
        let (p, q) = (
            pose.inverse_transform_point(&Point3::from(*a)).coords,
            pose.inverse_transform_point(&Point3::from(*b)).coords,
        );
        let bounds = Aabb::new(to_parry(&p.inf(&q)), to_parry(&p.sup(&q)));
        self.mesh
            .bvh()
            .intersect_aabb(&bounds)
            .filter(|&k| {
                let tri = self.mesh.triangle(k);
                segment_crosses_triangle(&p, &q, &[tri.a, tri.b, tri.c].map(from_parry))
            })
            .count()
    }

    /// Signed distance of `x` from the surface at time `t` (negative inside), with no
    /// distance limit.
    pub fn signed_distance(&self, t: f64, x: &Vec3) -> f64 {
        let p = self.pose(t).inverse_transform_point(&Point3::from(*x)).coords;
        let proj = self.mesh.project_local_point(to_parry(&p), false);
        let distance = (p - from_parry(proj.point)).norm();
        if self.inside(&p, proj.is_inside) {
            -distance
        } else {
            distance
        }
    }

    /// Whether the local point `p` is inside: the winding number's answer, or else the
    /// pseudonormals' (`pseudo`, from the projection onto the mesh).
    fn inside(&self, p: &Vec3, pseudo: bool) -> bool {
        match &self.winding {
            Some(tree) => tree.winding_number(p) >= 0.5,
            None => pseudo,
        }
    }

    /// The first entry into the body along the straight path from `x0` (at `t0`) to `x1`
    /// (at `t1`), relative to the body; else the nearest surface point to `x1` within
    /// `max_distance`. The path test is skipped when the path is shorter than
    /// `min_start_distance`, a lower bound on the distance of `x0`.
    pub(crate) fn sweep(
        &self,
        t0: f64,
        x0: &Vec3,
        t1: f64,
        x1: &Vec3,
        min_start_distance: f64,
        max_distance: f64,
    ) -> Option<BodyPoint> {
        let pose1 = self.pose(t1);
        let p1 = pose1.inverse_transform_point(&Point3::from(*x1)).coords;
        let p0 = if t0 == t1 {
            pose1.inverse_transform_point(&Point3::from(*x0)).coords
        } else {
            self.pose(t0).inverse_transform_point(&Point3::from(*x0)).coords
        };
        let path = p1 - p0;
        let length = path.norm();
        if length > 0.0 && length >= min_start_distance {
            let ray = Ray::new(to_parry(&p0), to_parry(&path));
            if let Some(hit) = self.mesh.cast_local_ray_and_get_normal(&ray, 1.0, false) {
                let n = from_parry(hit.normal).normalize();
                // A hit from inside is the particle leaving (it started inside): not an entry.
                if n.dot(&path) < 0.0 {
                    let entry = p0 + hit.time_of_impact * path;
                    let (_, (triangle, location)) = self
                        .mesh
                        .project_local_point_and_get_location(to_parry(&entry), false);
                    let n = self.shading.normal(&self.mesh, triangle, &location).unwrap_or(n);
                    return Some(BodyPoint {
                        point: (pose1 * Point3::from(entry)).coords,
                        normal: pose1.rotation * n,
                        distance: n.dot(&(p1 - entry)),
                        crossed: true,
                        entry: hit.time_of_impact,
                    });
                }
            }
        }
        let (proj, (triangle, location)) = self.mesh.project_local_point_and_get_location_with_max_dist(
            to_parry(&p1),
            false,
            max_distance,
        )?;
        let q = from_parry(proj.point);
        let offset = p1 - q;
        let distance = offset.norm();
        let sign = if self.inside(&p1, proj.is_inside) {
            -1.0
        } else {
            1.0
        };
        let normal = match self.shading.normal(&self.mesh, triangle, &location) {
            Some(smooth) => smooth,
            None if distance > 1e-9 * self.radius.max(1e-3) => sign * offset / distance,
            None => from_parry(self.mesh.triangle(triangle).scaled_normal()).normalize(),
        };
        Some(BodyPoint {
            point: (pose1 * Point3::from(q)).coords,
            normal: pose1.rotation * normal,
            distance: sign * distance,
            crossed: false,
            entry: 1.0,
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

/// The contact normal over a tessellated smooth surface. The distance field's own gradient
/// points away from the nearest vertex or edge of the tessellation, and turns at a rate of
/// one over the distance around each: a particle near a facet vertex of a sphere would be
/// pushed off radially from that vertex, breaking the body's symmetry. Over the smooth part
/// the normal is instead interpolated from per-corner normals that average only the faces
/// meeting smoothly; on a sharp edge or corner the gradient is the right normal and is kept.
#[derive(Debug, Clone)]
struct Shading {
    /// Per triangle, the normal at each corner.
    corners: Vec<[Vec3; 3]>,
    sharp_edges: HashSet<(u32, u32)>,
    sharp_vertices: Vec<bool>,
}

impl Shading {
    fn new(v: &[Vec3], t: &[[u32; 3]], sharp: &[SurfaceFeature], angle: f64) -> Self {
        let face_normal = |tri: &[u32; 3]| {
            let [a, b, c] = tri.map(|i| v[i as usize]);
            (b - a).cross(&(c - a)).normalize()
        };
        let corner_angle = |tri: &[u32; 3], k: usize| {
            let p = tri.map(|i| v[i as usize]);
            let (e1, e2) = (p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]);
            e1.angle(&e2)
        };
        let normals: Vec<Vec3> = t.iter().map(face_normal).collect();
        let mut around = vec![Vec::new(); v.len()];
        for (f, tri) in t.iter().enumerate() {
            for (k, &i) in tri.iter().enumerate() {
                around[i as usize].push((f, k));
            }
        }
        let cos_limit = angle.cos();
        let corners = t
            .iter()
            .enumerate()
            .map(|(f, tri)| {
                [0, 1, 2].map(|k| {
                    let sum: Vec3 = around[tri[k] as usize]
                        .iter()
                        .filter(|(g, _)| normals[*g].dot(&normals[f]) >= cos_limit)
                        .map(|&(g, kg)| corner_angle(&t[g], kg) * normals[g])
                        .sum();
                    sum.try_normalize(1e-12).unwrap_or(normals[f])
                })
            })
            .collect();
        let mut sharp_vertices = vec![false; v.len()];
        let mut sharp_edges = HashSet::new();
        for f in sharp {
            sharp_vertices[f.a as usize] = true;
            sharp_vertices[f.b as usize] = true;
            if f.a != f.b {
                sharp_edges.insert((f.a.min(f.b), f.a.max(f.b)));
            }
        }
        Self {
            corners,
            sharp_edges,
            sharp_vertices,
        }
    }

    /// The interpolated normal at a projection, or `None` on a sharp edge or corner.
    fn normal(&self, mesh: &TriMesh, triangle: u32, location: &TrianglePointLocation) -> Option<Vec3> {
        let idx = mesh.indices()[triangle as usize];
        match *location {
            TrianglePointLocation::OnVertex(i) if self.sharp_vertices[idx[i as usize] as usize] => {
                return None
            }
            TrianglePointLocation::OnEdge(i, _) => {
                let (a, b) = match i {
                    0 => (idx[0], idx[1]),
                    1 => (idx[1], idx[2]),
                    _ => (idx[0], idx[2]),
                };
                if self.sharp_edges.contains(&(a.min(b), a.max(b))) {
                    return None;
                }
            }
            _ => {}
        }
        let w = location.barycentric_coordinates()?;
        let c = &self.corners[triangle as usize];
        (w[0] * c[0] + w[1] * c[1] + w[2] * c[2]).try_normalize(1e-12)
    }
}
