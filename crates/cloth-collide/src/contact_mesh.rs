//! One surface the cloth meets, in the body's own frame: its parry mesh and BVH, its
//! inside and outside, and the smooth normals over it. A body has one over all it can
//! reach, and one over its thick parts only, for the cloth passing through its thin ones.

use crate::convert::{from_parry, to_parry};
use crate::surface::{SharpFeature as SurfaceFeature, WindingTree};
use cloth_core::math::predicates::segment_crosses_triangle;
use cloth_core::math::Vec3;
use parry3d_f64::bounding_volume::Aabb;
use parry3d_f64::query::{PointQuery, PointQueryWithLocation, Ray, RayCast};
use parry3d_f64::shape::{TriMesh, TriMeshFlags, TrianglePointLocation};
use std::collections::HashSet;

/// Where a path or a point stands relative to the surface, in the body's frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LocalPoint {
    pub point: Vec3,
    pub normal: Vec3,
    pub distance: f64,
    pub crossed: bool,
    /// Fraction of the path at the entry (1 for a plain proximity).
    pub entry: f64,
    /// The surface's vertices round `point` and their weights in it, for what the body
    /// keeps per vertex (its contact layer).
    pub corners: [u32; 3],
    pub weights: [f64; 3],
}

#[derive(Debug, Clone)]
pub(crate) struct ContactMesh {
    mesh: TriMesh,
    /// Inside/outside for a surface that is not closed; `None`: the pseudonormals of
    /// `mesh` answer it.
    winding: Option<WindingTree>,
    shading: Shading,
}

impl ContactMesh {
    /// The surface of `triangles` over `vertices`. `closed`: a watertight surface, whose
    /// pseudonormals answer inside and outside soundly; any other asks its winding number.
    pub fn new(
        vertices: &[Vec3],
        triangles: Vec<[u32; 3]>,
        closed: bool,
        sharp: &[SurfaceFeature],
        angle: f64,
    ) -> Self {
        let (flags, winding) = if closed {
            (TriMeshFlags::ORIENTED, None)
        } else {
            (
                TriMeshFlags::empty(),
                Some(WindingTree::new(vertices, &triangles)),
            )
        };
        let shading = Shading::new(vertices, &triangles, sharp, angle);
        let mesh = TriMesh::with_flags(vertices.iter().map(to_parry).collect(), triangles, flags)
            .expect("a contact surface has triangles");
        Self {
            mesh,
            winding,
            shading,
        }
    }

    pub fn triangles(&self) -> &[[u32; 3]] {
        self.mesh.indices()
    }

    /// New smooth normals for a new sharp angle.
    pub fn reshade(&mut self, vertices: &[Vec3], sharp: &[SurfaceFeature], angle: f64) {
        self.shading = Shading::new(vertices, self.mesh.indices(), sharp, angle);
    }

    /// Whether the point `p` is inside: the winding number's answer, or else the
    /// pseudonormals' (`pseudo`, from the projection onto the mesh).
    fn inside(&self, p: &Vec3, pseudo: bool) -> bool {
        match &self.winding {
            Some(tree) => tree.winding_number(p) >= 0.5,
            None => pseudo,
        }
    }

    /// Signed distance of `p` from the surface (negative inside), with no limit.
    pub fn signed_distance(&self, p: &Vec3) -> f64 {
        let proj = self.mesh.project_local_point(to_parry(p), false);
        let distance = (p - from_parry(proj.point)).norm();
        if self.inside(p, proj.is_inside) {
            -distance
        } else {
            distance
        }
    }

    /// How many triangles the segment from `p` to `q` passes through.
    pub fn segment_crossings(&self, p: &Vec3, q: &Vec3) -> usize {
        let bounds = Aabb::new(to_parry(&p.inf(q)), to_parry(&p.sup(q)));
        self.mesh
            .bvh()
            .intersect_aabb(&bounds)
            .filter(|&k| {
                let tri = self.mesh.triangle(k);
                segment_crosses_triangle(p, q, &[tri.a, tri.b, tri.c].map(from_parry))
            })
            .count()
    }

    /// The first entry into the surface along the straight path from `p0` to `p1`; else
    /// the nearest surface point to `p1` within `max_distance`. The path test is skipped
    /// when the path is shorter than `min_start_distance`, a lower bound on the distance
    /// of `p0`. `scale`: the body's size, below a billionth of which a distance is zero.
    pub fn sweep(
        &self,
        p0: &Vec3,
        p1: &Vec3,
        min_start_distance: f64,
        max_distance: f64,
        scale: f64,
    ) -> Option<LocalPoint> {
        let path = p1 - p0;
        let length = path.norm();
        if length > 0.0 && length >= min_start_distance {
            let ray = Ray::new(to_parry(p0), to_parry(&path));
            if let Some(hit) = self.mesh.cast_local_ray_and_get_normal(&ray, 1.0, false) {
                let n = from_parry(hit.normal).normalize();
                // A hit from inside is the particle leaving (it started inside): not an entry.
                if n.dot(&path) < 0.0 {
                    let entry = p0 + hit.time_of_impact * path;
                    let (_, (triangle, location)) = self
                        .mesh
                        .project_local_point_and_get_location(to_parry(&entry), false);
                    let n = self.shading.normal(&self.mesh, triangle, &location).unwrap_or(n);
                    let (corners, weights) = self.corners(triangle, &location);
                    return Some(LocalPoint {
                        point: entry,
                        normal: n,
                        distance: n.dot(&(p1 - entry)),
                        crossed: true,
                        entry: hit.time_of_impact,
                        corners,
                        weights,
                    });
                }
            }
        }
        let (proj, (triangle, location)) = self.mesh.project_local_point_and_get_location_with_max_dist(
            to_parry(p1),
            false,
            max_distance,
        )?;
        let q = from_parry(proj.point);
        let offset = p1 - q;
        let distance = offset.norm();
        let sign = if self.inside(p1, proj.is_inside) {
            -1.0
        } else {
            1.0
        };
        let normal = match self.shading.normal(&self.mesh, triangle, &location) {
            Some(smooth) => smooth,
            None if distance > 1e-9 * scale.max(1e-3) => sign * offset / distance,
            None => from_parry(self.mesh.triangle(triangle).scaled_normal()).normalize(),
        };
        let (corners, weights) = self.corners(triangle, &location);
        Some(LocalPoint {
            point: q,
            normal,
            distance: sign * distance,
            crossed: false,
            entry: 1.0,
            corners,
            weights,
        })
    }

    /// The vertices of `triangle` and the weights of `location` in them.
    fn corners(&self, triangle: u32, location: &TrianglePointLocation) -> ([u32; 3], [f64; 3]) {
        let w = location.barycentric_coordinates().unwrap_or([1.0 / 3.0; 3]);
        (self.mesh.indices()[triangle as usize], w)
    }

    /// The chord through the body from each triangle's centre along its inward normal, as
    /// far as `limit` (the body's thickness under each triangle), m.
    pub fn chords(&self, limit: f64) -> Vec<f64> {
        self.mesh
            .triangles()
            .map(|tri| {
                let (a, b, c) = (from_parry(tri.a), from_parry(tri.b), from_parry(tri.c));
                let Some(n) = (b - a).cross(&(c - a)).try_normalize(1e-18) else {
                    return limit;
                };
                let centre = (a + b + c) / 3.0;
                // From just inside, the first crossing is the far side.
                let start = centre - 1e-7 * n;
                let ray = Ray::new(to_parry(&start), to_parry(&(-n)));
                self.mesh
                    .cast_local_ray(&ray, limit, false)
                    .map_or(limit, |toi| toi + 1e-7)
            })
            .collect()
    }
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
