//! What a garment's cut asks of the fabric where it is most stretched. The stretched
//! thread (weft or warp) is followed from there through the cloth, across the seams into
//! the next panel's thread of the same kind, and goes round the body or does not. If it
//! does, its length at rest (from the panels' material coordinates) is set against the
//! girth of the body inside it: the perimeter of the convex hull of the body's slice by
//! the plane the thread lies nearest, which the thread, projected on that plane and round
//! it, is at least as long as. A thread cut shorter than that girth is stretched on average
//! by at least their ratio however the garment is draped there: "stretched" because it
//! is cut smaller than the body, not because the drape pulled it so (GarmentCode's
//! rand_1_061 on `mean_all`: its waistband's weft, 84.3 cm at rest, goes round 91.1 cm of
//! waist, asking 8.0 %; it rests at p99 weft 8.7 %).

use cloth_collide::TriSurface;
use cloth_core::{math::Vec3, ClothMesh, StrainReport};
use cloth_garment::meshing::encloses;
use nalgebra::{Matrix3, Vector2};
use serde::Serialize;
use std::collections::HashMap;

/// How close, m, the triangles strained past the garment's 99th percentile must lie to
/// count as one stretched place: about a hand's width, the size of a waistband's or a
/// cuff's stretched band.
const PLACE_RADIUS: f64 = 0.05;

/// The most triangles weighed for the most stretched place (the most strained first).
const MOST_WEIGHED: usize = 2000;

/// The most of the most strained triangles whose threads are followed round, the most
/// stretched place's first, until one goes round the body.
const THREADS_TRIED: usize = 48;

/// The cut against the body where a garment is most stretched.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Fit {
    /// The panel most stretched there.
    pub panel: String,
    /// The thread stretched most ("warp" or "weft"), across which the cloth is sliced.
    pub thread: &'static str,
    /// The middle of the most stretched place, m (the output's frame).
    pub at: [f64; 3],
    /// The length round the slice of the cloth at rest and as worn, m.
    pub cloth_at_rest: f64,
    pub cloth_worn: f64,
    /// The girth of the body inside the slice (its convex hull's perimeter), m.
    pub body_girth: f64,
    /// How much longer than the cloth at rest the body's girth is, %: the least average
    /// stretch round the slice the cut asks (negative: the ease the cut gives).
    pub asks: f64,
}

impl Fit {
    /// What the cut asks round the body, or the ease it gives: "the cut asks 4.8 %", "the
    /// cut gives 12.0 % to spare".
    pub fn asks_said(&self) -> String {
        if self.asks > 0.0 {
            format!("the cut asks {:.1} %", self.asks)
        } else {
            format!("the cut gives {:.1} % to spare", -self.asks)
        }
    }

    /// What a verdict says of it, e.g. "where most stretched ('wb_back'), 91.6 cm of cloth
    /// at rest goes round 96.0 cm of body: the cut asks 4.8 %".
    pub fn said(&self) -> String {
        format!(
            "where most stretched ('{}'), {:.1} cm of cloth at rest goes round {:.1} cm of body: {}",
            self.panel,
            100.0 * self.cloth_at_rest,
            100.0 * self.body_girth,
            self.asks_said()
        )
    }
}

/// The fit where `mesh` at `x` is most stretched along the thread whose 99th percentile
/// of `strain` is higher, against `bodies`; the panel of each triangle is
/// `panel_names[triangle_panel[t]]`; `crosses(a, b)` says whether the segment from `a` to
/// `b` passes through a body. A thread worn through the body (a cuff zipped through the
/// forearm) does not say what the cut asks, so it is passed over for the next. `None` if
/// no thread near the most stretched places goes round a body outside it (an open
/// skirt's hem, a flat sheet), or the cloth is not stretched at all.
pub fn fit_where_stretched(
    mesh: &ClothMesh,
    x: &[Vec3],
    strain: &StrainReport,
    bodies: &[TriSurface],
    triangle_panel: &[usize],
    panel_names: &[String],
    crosses: &dyn Fn(&Vec3, &Vec3) -> bool,
) -> Option<Fit> {
    let (strains, p99, thread) = if strain.p99_weft >= strain.p99_warp {
        (&strain.weft, strain.p99_weft, "weft")
    } else {
        (&strain.warp, strain.p99_warp, "warp")
    };
    if p99 <= 0.0 {
        return None;
    }
    // The thread through the middle of the place may leave the cloth (at a hem it runs
    // beside, or along a seam); then one through the next nearest of its triangles.
    // A triangle a thread tried has passed through gives the same thread again.
    let threads = Threads::new(mesh, x, thread == "weft");
    let mut passed = vec![false; mesh.triangles().len()];
    let mut found = None;
    let mut tried = 0;
    for seed in most_stretched_place(mesh, x, strains, p99) {
        if strains[seed] <= 0.0 || tried == THREADS_TRIED {
            break;
        }
        if passed[seed] {
            continue;
        }
        tried += 1;
        let Some(ring) = threads.round(seed, &mut passed) else {
            continue;
        };
        let n = ring.points.len();
        if (0..n).any(|k| crosses(&ring.points[k], &ring.points[(k + 1) % n])) {
            continue;
        }
        let girth = Plane::fitted(&ring.points).and_then(|plane| girth_inside(bodies, &plane, &ring.points));
        if let Some(girth) = girth {
            found = Some((seed, ring, girth));
            break;
        }
    }
    let (seed, ring, body_girth) = found?;
    let centre = mesh.triangles()[seed].iter().map(|&i| x[i]).sum::<Vec3>() / 3.0;
    Some(Fit {
        panel: panel_names.get(*triangle_panel.get(seed)?)?.clone(),
        thread,
        at: [centre.x, centre.y, centre.z],
        cloth_at_rest: ring.at_rest,
        cloth_worn: ring.worn,
        body_girth,
        asks: 100.0 * (body_girth / ring.at_rest - 1.0),
    })
}

/// The triangles of the most stretched place, its middle first: of the triangles strained
/// at least `p99`, the one with the most others within [`PLACE_RADIUS`] (the more strained
/// of two with as many), so that one stray triangle at a seam's corner does not pass for
/// the place, then those others, nearest first, then all the rest, most strained first.
fn most_stretched_place(mesh: &ClothMesh, x: &[Vec3], strains: &[f64], p99: f64) -> Vec<usize> {
    let mut over: Vec<usize> = (0..strains.len()).filter(|&t| strains[t] >= p99).collect();
    over.sort_by(|&a, &b| strains[b].total_cmp(&strains[a]));
    over.truncate(MOST_WEIGHED);
    let centre = |t: usize| mesh.triangles()[t].iter().map(|&i| x[i]).sum::<Vec3>() / 3.0;
    let centres: Vec<Vec3> = over.iter().map(|&t| centre(t)).collect();
    let near = |c: &Vec3| centres.iter().filter(|d| (*d - c).norm() < PLACE_RADIUS).count();
    // The most strained first, so a tie keeps the more strained.
    let mut best: Option<(usize, usize)> = None;
    for (k, c) in centres.iter().enumerate() {
        let n = near(c);
        if best.is_none_or(|(_, m)| n > m) {
            best = Some((k, n));
        }
    }
    let Some((middle, _)) = best else {
        return Vec::new();
    };
    let mut place: Vec<(f64, usize)> = centres
        .iter()
        .zip(&over)
        .map(|(c, &t)| ((c - centres[middle]).norm(), t))
        .filter(|&(d, _)| d < PLACE_RADIUS)
        .collect();
    place.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut order: Vec<usize> = place.into_iter().map(|(_, t)| t).collect();
    // Then the rest, most strained first: where the place itself is not gone round (a
    // skirt stretched most at its slit), the next place that is.
    let mut in_place = vec![false; strains.len()];
    for &t in &order {
        in_place[t] = true;
    }
    let mut elsewhere: Vec<usize> = (0..strains.len()).filter(|&t| !in_place[t]).collect();
    elsewhere.sort_by(|&a, &b| strains[b].total_cmp(&strains[a]));
    order.extend(elsewhere);
    order
}

/// The plane the body is sliced by.
struct Plane {
    point: Vec3,
    normal: Vec3,
}

impl Plane {
    /// The plane `points` lie nearest (through their mean, across their least spread).
    fn fitted(points: &[Vec3]) -> Option<Self> {
        if points.len() < 3 {
            return None;
        }
        let point = points.iter().sum::<Vec3>() / points.len() as f64;
        let spread = points
            .iter()
            .map(|p| (p - point) * (p - point).transpose())
            .sum::<Matrix3<f64>>();
        let eigen = spread.symmetric_eigen();
        let least = eigen.eigenvalues.imin();
        let normal = eigen
            .eigenvectors
            .column(least)
            .into_owned()
            .try_normalize(1e-12)?;
        Some(Self { point, normal })
    }

    /// Which side `p` is on, a point on the plane counted above it so that every edge
    /// has its ends on one side or across.
    fn above(&self, p: &Vec3) -> bool {
        self.normal.dot(&(p - self.point)) >= 0.0
    }

    /// Where the plane cuts the segment from `a` to `b`, as the fraction of the way.
    fn cut(&self, a: &Vec3, b: &Vec3) -> f64 {
        let (da, db) = (
            self.normal.dot(&(a - self.point)),
            self.normal.dot(&(b - self.point)),
        );
        if da == db {
            0.5
        } else {
            (da / (da - db)).clamp(0.0, 1.0)
        }
    }

    /// Coordinates of `p`'s projection on the plane.
    fn in_plane(&self, p: &Vec3) -> Vector2<f64> {
        let helper = if self.normal.x.abs() < 0.9 {
            Vec3::x()
        } else {
            Vec3::y()
        };
        let e1 = self.normal.cross(&helper).normalize();
        let e2 = self.normal.cross(&e1);
        let d = p - self.point;
        Vector2::new(d.dot(&e1), d.dot(&e2))
    }
}

/// A thread followed round the garment: its length at rest and worn, and the points
/// where it crosses the triangles' edges.
struct Ring {
    at_rest: f64,
    worn: f64,
    points: Vec<Vec3>,
}

/// The threads of a garment's cloth, to follow round it.
struct Threads<'a> {
    mesh: &'a ClothMesh,
    x: &'a [Vec3],
    /// The two triangles across each inner edge, by its ends (lower first): the mesh has
    /// no edge of more than two.
    across: HashMap<[usize; 2], [usize; 2]>,
    /// The thread's direction in the panels' material coordinates.
    axis: Vector2<f64>,
}

impl<'a> Threads<'a> {
    /// The weft threads of `mesh` at `x` (`weft`), else the warp threads.
    fn new(mesh: &'a ClothMesh, x: &'a [Vec3], weft: bool) -> Self {
        let across = mesh.hinges().iter().map(|h| (h.edge, h.triangles)).collect();
        let axis = if weft {
            Vector2::new(0.0, 1.0)
        } else {
            Vector2::new(1.0, 0.0)
        };
        Self {
            mesh,
            x,
            across,
            axis,
        }
    }

    /// The thread through the middle of triangle `seed`, followed from triangle to
    /// triangle across their edges and across the seams into the next panel's thread of
    /// the same kind, if it comes back round to where it began (through `seed`, or within
    /// [`CLOSING`] of its size). `None` if it leaves the cloth at an edge, runs along a
    /// seam, or does not come back. Every triangle it passes is marked in `passed`.
    fn round(&self, seed: usize, passed: &mut [bool]) -> Option<Ring> {
        let (mesh, x, axis) = (self.mesh, self.x, self.axis);
        let triangles = mesh.triangles();
        let seed_uv = mesh.corner_uv(seed);
        let start_uv = (seed_uv[0] + seed_uv[1] + seed_uv[2]) / 3.0;
        let start = triangles[seed].iter().map(|&i| x[i]).sum::<Vec3>() / 3.0;
        let size = (0..3)
            .map(|k| (x[triangles[seed][k]] - x[triangles[seed][(k + 1) % 3]]).norm())
            .fold(0.0, f64::max);
        let (mut t, mut at_uv, mut at, mut along, mut from) =
            (seed, start_uv, start, axis, None::<[usize; 2]>);
        let (mut at_rest, mut worn, mut points) = (0.0, 0.0, Vec::new());
        let mut nearest: Option<(f64, f64, f64, usize)> = None;
        for _ in 0..2 * triangles.len() {
            passed[t] = true;
            let c = triangles[t];
            let uv = mesh.corner_uv(t);
            // Where the thread leaves this triangle: the nearest edge ahead but the one it came in by.
            let (k, reach, share) = (0..3)
                .filter(|&k| from != Some(key(c[k], c[(k + 1) % 3])))
                .filter_map(|k| {
                    let (a, b) = (uv[k], uv[(k + 1) % 3]);
                    let edge = b - a;
                    let across = along.perp(&edge);
                    if across.abs() < 1e-12 {
                        return None;
                    }
                    let reach = (a - at_uv).perp(&edge) / across;
                    let share = (a - at_uv).perp(&along) / across;
                    (reach > 0.0 && (-1e-9..=1.0 + 1e-9).contains(&share)).then_some((
                        k,
                        reach,
                        share.clamp(0.0, 1.0),
                    ))
                })
                .min_by(|p, q| p.1.total_cmp(&q.1))?;
            let (i, j) = (c[k], c[(k + 1) % 3]);
            let next = x[i].lerp(&x[j], share);
            at_rest += reach;
            worn += (next - at).norm();
            points.push(next);
            // Come back beside where it began, not through its own triangle (a thread a
            // seam has shifted): closed where it passed nearest, the rest of the way taken at
            // the stretch so far.
            let gap = (next - start).norm();
            if worn > CLOSING_RUN * size && gap < CLOSING * size {
                match nearest {
                    Some((g, ..)) if gap >= g => {
                        let (g, rest_then, worn_then, n) = nearest?;
                        points.truncate(n);
                        let ring = Ring {
                            at_rest: rest_then + g * rest_then / worn_then,
                            worn: worn_then + g,
                            points,
                        };
                        return Some(ring);
                    }
                    _ => nearest = Some((gap, at_rest, worn, points.len())),
                }
            }
            // On into the triangle across that edge, along its own thread, pointing into it.
            let edge_key = key(i, j);
            let pair = self.across.get(&edge_key)?;
            let u = if pair[0] == t { pair[1] } else { pair[0] };
            let cu = triangles[u];
            let uv_u = mesh.corner_uv(u);
            let (ki, kj) = (cu.iter().position(|&v| v == i)?, cu.iter().position(|&v| v == j)?);
            let kk = 3 - ki - kj;
            at_uv = uv_u[ki].lerp(&uv_u[kj], share);
            if u == seed {
                // Back in the triangle it began in: on to where it began.
                at_rest += (start_uv - at_uv).norm();
                worn += (start - next).norm();
                return Some(Ring {
                    at_rest,
                    worn,
                    points,
                });
            }
            let edge = uv_u[kj] - uv_u[ki];
            let inward = edge.perp(&(uv_u[kk] - uv_u[ki]));
            let across = edge.perp(&axis);
            if across.abs() < THREAD_ALONG_SEAM * edge.norm() {
                return None;
            }
            along = if across * inward > 0.0 { axis } else { -axis };
            at = next;
            from = Some(edge_key);
            t = u;
        }
        None
    }
}

/// A thread that has run at least this many times its first triangle's size and comes
/// back within [`CLOSING`] of them to where it began has gone round.
const CLOSING_RUN: f64 = 10.0;
const CLOSING: f64 = 1.5;

/// A thread meeting an edge at a sine less than this runs along it (a seam along the
/// thread): where it goes on is undefined.
const THREAD_ALONG_SEAM: f64 = 0.05;

fn key(a: usize, b: usize) -> [usize; 2] {
    [a.min(b), a.max(b)]
}

/// The perimeter of the convex hull of `bodies`' slice by `plane` inside the loop through
/// `points` (in the plane), or `None` if no body lies inside it.
fn girth_inside(bodies: &[TriSurface], plane: &Plane, points: &[Vec3]) -> Option<f64> {
    let ring: Vec<Vector2<f64>> = points.iter().map(|p| plane.in_plane(p)).collect();
    let mut inside = Vec::new();
    for body in bodies {
        let v = body.vertices();
        for tri in body.triangles() {
            let c = tri.map(|i| v[i as usize]);
            for k in 0..3 {
                let (a, b) = (&c[k], &c[(k + 1) % 3]);
                if plane.above(a) != plane.above(b) {
                    let p = plane.in_plane(&a.lerp(b, plane.cut(a, b)));
                    if encloses(&ring, p) {
                        inside.push(p);
                    }
                }
            }
        }
    }
    let hull = convex_hull(inside);
    (hull.len() >= 3).then(|| perimeter(&hull))
}

/// The convex hull of `points`, anticlockwise (Andrew's monotone chain).
fn convex_hull(mut points: Vec<Vector2<f64>>) -> Vec<Vector2<f64>> {
    points.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    points.dedup();
    if points.len() < 3 {
        return points;
    }
    let turn = |o: &Vector2<f64>, a: &Vector2<f64>, b: &Vector2<f64>| (a - o).perp(&(b - o));
    let mut hull: Vec<Vector2<f64>> = Vec::with_capacity(2 * points.len());
    for pass in [points.clone(), points.into_iter().rev().collect()] {
        let floor = hull.len();
        for p in pass {
            while hull.len() >= floor + 2 && turn(&hull[hull.len() - 2], &hull[hull.len() - 1], &p) <= 0.0 {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

/// The length round the closed polygon `ring`.
fn perimeter(ring: &[Vector2<f64>]) -> f64 {
    (0..ring.len())
        .map(|k| (ring[(k + 1) % ring.len()] - ring[k]).norm())
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// A tube of `around` x `rows` cells along z, from z = 0 to 0.1, its rest length
    /// round `rest` along the warp (u) and worn at radius `radius` round the z axis; its
    /// last column of cells left out in the lowest `slit` rows (all of them: a sheet
    /// wrapped nearly round).
    fn tube(rest: f64, radius: f64, around: usize, rows: usize, slit: usize) -> (ClothMesh, Vec<Vec3>) {
        flared(rest, &vec![radius; rows + 1], around, slit)
    }

    /// The same, worn at `radii[j]` at the `j`th row of vertices from the bottom.
    fn flared(rest: f64, radii: &[f64], around: usize, slit: usize) -> (ClothMesh, Vec<Vec3>) {
        let (height, rows) = (0.1, radii.len() - 1);
        let mut x = Vec::new();
        for (j, radius) in radii.iter().enumerate() {
            for i in 0..around {
                let a = 2.0 * PI * i as f64 / around as f64;
                x.push(Vec3::new(
                    radius * a.cos(),
                    radius * a.sin(),
                    height * j as f64 / rows as f64,
                ));
            }
        }
        let index = |i: usize, j: usize| j * around + i % around;
        let uv = |i: usize, j: usize| {
            Vector2::new(rest * i as f64 / around as f64, height * j as f64 / rows as f64)
        };
        let (mut triangles, mut corner_uv) = (Vec::new(), Vec::new());
        for j in 0..rows {
            let columns = if j < slit { around - 1 } else { around };
            for i in 0..columns {
                triangles.push([index(i, j), index(i + 1, j), index(i + 1, j + 1)]);
                corner_uv.push([uv(i, j), uv(i + 1, j), uv(i + 1, j + 1)]);
                triangles.push([index(i, j), index(i + 1, j + 1), index(i, j + 1)]);
                corner_uv.push([uv(i, j), uv(i + 1, j + 1), uv(i, j + 1)]);
            }
        }
        (
            ClothMesh::with_corner_uv(x.clone(), triangles, corner_uv).unwrap(),
            x,
        )
    }

    fn post(radius: f64, segments: usize) -> TriSurface {
        TriSurface::cylinder(radius, 0.5, segments).unwrap()
    }

    fn fit_of(mesh: &ClothMesh, x: &[Vec3], bodies: &[TriSurface]) -> Option<Fit> {
        let strain = StrainReport::new(mesh, x);
        let panels = vec![0; mesh.triangles().len()];
        // The posts are round the z axis: a segment with one end inside one and the other
        // outside passes through it.
        let radius = |p: &Vec3| p.x.hypot(p.y);
        let post_radius = bodies
            .first()
            .map_or(0.0, |b| b.vertices().iter().map(radius).fold(0.0, f64::max));
        let inside = |p: &Vec3| radius(p) < post_radius * (PI / 64.0).cos();
        let crosses = |a: &Vec3, b: &Vec3| inside(a) != inside(b);
        fit_where_stretched(mesh, x, &strain, bodies, &panels, &["cuff".to_string()], &crosses)
    }

    /// The perimeter of a regular polygon of `sides` round a circle of `radius`'s.
    fn polygon(radius: f64, sides: usize) -> f64 {
        2.0 * radius * sides as f64 * (PI / sides as f64).sin()
    }

    #[test]
    fn a_tube_cut_shorter_than_the_post_it_is_worn_round_asks_their_ratio() {
        // 30 cm of cloth worn at a 5.1 cm radius round a post 5 cm in radius.
        let (mesh, x) = tube(0.30, 0.051, 48, 6, 0);
        let fit = fit_of(&mesh, &x, &[post(0.05, 64)]).expect("the tube goes round the post");
        assert_eq!((fit.panel.as_str(), fit.thread), ("cuff", "warp"));
        assert!((fit.cloth_at_rest - 0.30).abs() < 1e-9, "{fit:?}");
        assert!((fit.cloth_worn - polygon(0.051, 48)).abs() < 1e-9, "{fit:?}");
        assert!((fit.body_girth - polygon(0.05, 64)).abs() < 1e-9, "{fit:?}");
        let asks = 100.0 * (polygon(0.05, 64) / 0.30 - 1.0);
        assert!((fit.asks - asks).abs() < 1e-6 && asks > 4.0, "{fit:?}");
        // Sliced across the stretched thread: level, at the middle of a row of cells.
        assert!(fit.at[2] > 0.0 && fit.at[2] < 0.1, "{fit:?}");
    }

    #[test]
    fn a_tube_cut_longer_than_the_post_gives_its_ease() {
        // Worn stretched at a 6 cm radius round a post 4 cm in radius: the drape, not the
        // cut, stretched it.
        let (mesh, x) = tube(0.34, 0.06, 40, 4, 0);
        let fit = fit_of(&mesh, &x, &[post(0.04, 64)]).unwrap();
        assert!(fit.asks < -20.0, "{fit:?}");
        assert!(fit.said().contains("the cut gives"), "{}", fit.said());
    }

    #[test]
    fn cloth_that_does_not_go_round_or_holds_no_body_has_no_fit() {
        let (open, x) = tube(0.30, 0.051, 48, 6, 6);
        assert_eq!(fit_of(&open, &x, &[post(0.05, 64)]), None);
        let (mesh, x) = tube(0.30, 0.051, 48, 6, 0);
        let far: Vec<Vec3> = x.iter().map(|p| p + Vec3::new(1.0, 0.0, 0.0)).collect();
        assert_eq!(fit_of(&mesh, &far, &[post(0.05, 64)]), None);
    }

    #[test]
    fn of_two_layers_round_the_post_the_stretched_one_is_followed() {
        // A stretched cuff under a loose sleeve: the slice follows the cuff round.
        let (cuff, x_cuff) = tube(0.30, 0.051, 48, 6, 0);
        let (sleeve, x_sleeve) = tube(0.50, 0.07, 60, 6, 0);
        let mesh = ClothMesh::join(&[cuff, sleeve]).unwrap();
        let x: Vec<Vec3> = x_cuff.iter().chain(&x_sleeve).copied().collect();
        let fit = fit_of(&mesh, &x, &[post(0.05, 64)]).unwrap();
        assert!((fit.cloth_at_rest - 0.30).abs() < 1e-9, "{fit:?}");
    }

    #[test]
    fn where_the_most_stretched_place_is_open_the_next_that_goes_round_is_measured() {
        // Flared wider at the bottom, where a slit leaves it open: the thread there leaves
        // the cloth, so the one higher up, narrower but closed, is followed round.
        let radii = [0.056, 0.055, 0.054, 0.052, 0.051, 0.051, 0.051];
        let (mesh, x) = flared(0.30, &radii, 48, 2);
        let fit = fit_of(&mesh, &x, &[post(0.05, 64)]).expect("the closed rows go round");
        assert!((fit.cloth_at_rest - 0.30).abs() < 1e-9, "{fit:?}");
        assert!(fit.at[2] > 0.2 * 0.1 - 1e-9, "{fit:?}");
        // Measured where the cloth goes round: no wider there than the rows above the slit.
        assert!(fit.cloth_worn <= polygon(0.054, 48) + 1e-9, "{fit:?}");
    }

    #[test]
    fn a_thread_worn_through_the_body_is_passed_over() {
        // A cuff with one column of particles pushed into the post: every thread round it
        // passes through the post, and says nothing of the fit.
        let (mesh, mut x) = tube(0.30, 0.051, 48, 6, 0);
        for p in x.iter_mut().step_by(48) {
            *p *= 0.5;
        }
        assert_eq!(fit_of(&mesh, &x, &[post(0.05, 64)]), None);
    }
}
