//! Panels placed over one another in one plane. GarmentCode lays the tiers of a tiered
//! skirt, the flared cuffs of both trouser legs and the two fronts of a wrap top flat in
//! the same plane where they overlap: the cloth then starts through itself wherever they
//! do, with no side of the other for either to be on. They are set apart into layers
//! along their normal, so each starts on one side of the other and the seams draw them
//! into place with the cloth's collision with itself on from the first step.

use super::Garment;
use cloth_core::math::union_find::{find, union};
use cloth_core::math::Vec3;
use nalgebra::Vector2;

/// Panels whose normals are within this of each other (cosine) are parallel.
const PARALLEL: f64 = 0.9998; // 1 degree
/// Parallel panels this near each other's plane, m, lie in one plane.
const COPLANAR: f64 = 1e-3;

/// Panels set apart into layers, the first outermost.
#[derive(Debug, Clone, PartialEq)]
pub struct Layers {
    pub panels: Vec<String>,
    /// How far apart the layers were set, m.
    pub gap: f64,
}

impl std::fmt::Display for Layers {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let names: Vec<String> = self.panels.iter().map(|p| format!("'{p}'")).collect();
        write!(
            f,
            "panels {} overlap in one plane: layered {:.1} mm apart before sewing, the first outermost",
            names.join(", "),
            1e3 * self.gap
        )
    }
}

/// A flat panel: its particles, unit normal (out of the garment), a point of its plane and
/// its triangles in the plane's coordinates.
struct Flat {
    members: Vec<usize>,
    normal: Vec3,
    origin: Vec3,
    triangles: Vec<[Vector2<f64>; 3]>,
    height: f64,
}

impl Garment {
    /// Sets panels that overlap in one plane apart into layers `gap` apart along their
    /// normal, the higher panel outermost (a tier over the one below it; panels level
    /// with each other in their order); returns each group so layered.
    pub fn layer_overlapping(&mut self, gap: f64) -> Vec<Layers> {
        let members = self.panel_members();
        let facing = self.panel_facing();
        let x = self.mesh.positions();
        let flats: Vec<Option<Flat>> = (0..self.panel_names.len())
            .map(|p| self.flat(p, &members[p], facing[p], x))
            .collect();
        // Overlapping pairs in one plane, joined into groups.
        let mut group: Vec<usize> = (0..flats.len()).collect();
        let mut any = false;
        for a in 0..flats.len() {
            for b in a + 1..flats.len() {
                let (Some(fa), Some(fb)) = (&flats[a], &flats[b]) else {
                    continue;
                };
                if fa.normal.dot(&fb.normal) < PARALLEL
                    || fa.normal.dot(&(fb.origin - fa.origin)).abs() > COPLANAR
                {
                    continue;
                }
                if overlap(fa, fb, x) || overlap(fb, fa, x) {
                    union(&mut group, a, b);
                    any = true;
                }
            }
        }
        if !any {
            return Vec::new();
        }
        let mut groups: Vec<Vec<usize>> = vec![Vec::new(); flats.len()];
        for p in 0..flats.len() {
            let r = find(&mut group, p);
            groups[r].push(p);
        }
        groups.retain(|g| g.len() > 1);
        let mut layered = Vec::new();
        for mut panels in groups {
            let height = |p: usize| flats[p].as_ref().map_or(0.0, |f| f.height);
            panels.sort_by(|&a, &b| height(b).total_cmp(&height(a)).then(a.cmp(&b)));
            for (rank, &p) in panels.iter().enumerate() {
                let flat = flats[p].as_ref().expect("grouped panels are flat");
                self.mesh
                    .translate_vertices(&flat.members, -(rank as f64 * gap) * flat.normal);
            }
            layered.push(Layers {
                panels: panels.iter().map(|&p| self.panel_names[p].clone()).collect(),
                gap,
            });
        }
        layered
    }

    /// Panel `p` as a flat piece, if every particle of it is within [`COPLANAR`] of its
    /// plane (a panel wrapped round the body is not).
    fn flat(&self, p: usize, members: &[usize], normal: Vec3, x: &[Vec3]) -> Option<Flat> {
        let origin = members.iter().map(|&i| x[i]).sum::<Vec3>() / members.len().max(1) as f64;
        if members
            .iter()
            .any(|&i| normal.dot(&(x[i] - origin)).abs() > COPLANAR)
        {
            return None;
        }
        let (u, v) = plane_axes(&normal);
        let to_plane = |q: &Vec3| Vector2::new(u.dot(&(q - origin)), v.dot(&(q - origin)));
        let triangles = self
            .mesh
            .triangles()
            .iter()
            .zip(&self.triangle_panel)
            .filter(|(_, &q)| q == p)
            .map(|(t, _)| t.map(|i| to_plane(&x[i])))
            .collect();
        Some(Flat {
            members: members.to_vec(),
            normal,
            origin,
            triangles,
            height: origin.z,
        })
    }
}

/// Whether a particle of `a` lies inside `b`, in `b`'s plane (clear of its outline by a
/// millimetre, so panels that merely touch along an edge do not count).
fn overlap(a: &Flat, b: &Flat, x: &[Vec3]) -> bool {
    let (u, v) = plane_axes(&b.normal);
    let in_plane = |i: usize| Vector2::new(u.dot(&(x[i] - b.origin)), v.dot(&(x[i] - b.origin)));
    // b's triangles binned in a grid of cells as large as its largest triangle's box.
    let boxes: Vec<(Vector2<f64>, Vector2<f64>)> = b
        .triangles
        .iter()
        .map(|t| (t[0].inf(&t[1]).inf(&t[2]), t[0].sup(&t[1]).sup(&t[2])))
        .collect();
    let Some(lo) = boxes.iter().map(|b| b.0).reduce(|a, c| a.inf(&c)) else {
        return false;
    };
    let hi = boxes.iter().map(|b| b.1).fold(lo, |a, c| a.sup(&c));
    let cell = boxes.iter().map(|(l, h)| (h - l).max()).fold(1e-3, f64::max);
    let dims = ((hi - lo) / cell).map(|d| d.floor() as usize + 1);
    let cell_of = |q: &Vector2<f64>| {
        let c = (q - lo) / cell;
        (
            c.x.floor().clamp(0.0, (dims.x - 1) as f64) as usize,
            c.y.floor().clamp(0.0, (dims.y - 1) as f64) as usize,
        )
    };
    let mut grid: Vec<Vec<usize>> = vec![Vec::new(); dims.x * dims.y];
    for (k, (l, h)) in boxes.iter().enumerate() {
        let ((x0, y0), (x1, y1)) = (cell_of(l), cell_of(h));
        for gy in y0..=y1 {
            for gx in x0..=x1 {
                grid[gy * dims.x + gx].push(k);
            }
        }
    }
    a.members.iter().any(|&i| {
        let q = in_plane(i);
        if q.x < lo.x || q.y < lo.y || q.x > hi.x || q.y > hi.y {
            return false;
        }
        let (gx, gy) = cell_of(&q);
        grid[gy * dims.x + gx]
            .iter()
            .any(|&k| inside(&q, &b.triangles[k], 1e-3))
    })
}

/// Two unit axes of the plane with normal `n`.
fn plane_axes(n: &Vec3) -> (Vec3, Vec3) {
    let u = n
        .cross(&Vec3::z())
        .try_normalize(1e-9)
        .unwrap_or_else(|| n.cross(&Vec3::x()).normalize());
    (u, n.cross(&u))
}

/// Whether `q` is inside triangle `t` by at least `margin` from each of its edges.
fn inside(q: &Vector2<f64>, t: &[Vector2<f64>; 3], margin: f64) -> bool {
    let area2 = (t[1] - t[0]).perp(&(t[2] - t[0]));
    if area2.abs() < 1e-18 {
        return false;
    }
    (0..3).all(|k| {
        let (a, b) = (t[k], t[(k + 1) % 3]);
        let edge = b - a;
        // Signed distance of q from the edge, positive inside.
        area2.signum() * edge.perp(&(q - a)) / edge.norm() > margin
    })
}
