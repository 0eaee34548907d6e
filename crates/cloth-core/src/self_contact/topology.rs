//! The cloth's primitives for self-collision, which of their pairs are exempt, and which
//! triangle speaks for each edge and vertex so a particle near one gets one contact, not
//! one per triangle around it.
//!
//! A pair is exempt when its primitives share a particle or have neighbouring particles
//! (particles a seam will join counting as one), or when they lie within the rest radius
//! of each other in the flat cloth. Such pairs are near for good: neighbours' primitives
//! touch whenever a row of cells is pressed flat in its own plane (which is the membrane's
//! to resist, not a fold), and on a mesh finer than a few thicknesses, pairs within the
//! radius would be in contact unfolded. Cloth cannot fold through itself over less than
//! its own thickness, nor within one cell without folding its cells flat.

use crate::math::predicates::{closest_on_segments, closest_on_triangle, segment_crosses_triangle};
use crate::math::union_find::{find, union};
use crate::math::Vec3;
use crate::mesh::{within_rings, ClothMesh};
use nalgebra::Vector2;

/// Bit of [`Topology::owns`] for vertex `k` of a triangle.
const OWNS_VERTEX: u8 = 1;
/// Bit for the edge opposite vertex `k`.
const OWNS_EDGE: u8 = 8;

#[derive(Debug, Clone)]
pub(crate) struct Topology {
    pub triangles: Vec<[u32; 3]>,
    pub edges: Vec<[u32; 2]>,
    /// Each particle's representative: the particles a seam pulls together are one.
    rep: Vec<u32>,
    /// The representatives joined by an edge to each representative, sorted, in
    /// compressed rows.
    neighbours: (Vec<u32>, Vec<u32>),
    /// Per triangle, `OWNS_VERTEX << k` when it is the first triangle of vertex `k`, and
    /// `OWNS_EDGE << k` when it is the first of the edge opposite vertex `k`.
    owns: Vec<u8>,
    /// Per triangle, the edge opposite each corner, and the triangle across it (or
    /// `u32::MAX` on a border).
    pub triangle_edges: Vec<[u32; 3]>,
    pub across: Vec<[u32; 3]>,
    /// The triangles of each particle, in compressed rows.
    vertex_triangles: (Vec<u32>, Vec<u32>),
    /// Material coordinates of each triangle's corners, and its chart (numbered from 0):
    /// triangles joined across edges whose corners agree in material coordinates share one
    /// (a panel; a welded seam parts two).
    corner_uv: Vec<[Vector2<f64>; 3]>,
    chart: Vec<u32>,
    /// Pairs of charts (lower first, sorted) that passed through each other when the
    /// simulation began: exempt from each other until they have come apart (see
    /// [`Topology::set_tangled`]).
    tangled: Vec<(u32, u32)>,
    /// Per particle, the side of a layer pass it is on (`2 k` the layer of pass `k`,
    /// `2 k + 1` the side let through it), or `u32::MAX`; empty while there are none (see
    /// [`Topology::set_passes`]).
    pass_side: Vec<u32>,
    /// Per representative, whether it is where the cloth passes through itself, and the
    /// pairs of charts passing through each other there (lower first, sorted; a chart
    /// through itself paired with itself); empty while nowhere is (see
    /// [`Topology::set_loose`]).
    loose: Vec<bool>,
    loose_charts: Vec<(u32, u32)>,
    /// Scratch for [`Topology::set_loose`]: the representatives reached by the last ring
    /// and those the next one reaches.
    loose_frontier: Vec<u32>,
    loose_next: Vec<u32>,
    /// Pairs this near in the flat cloth are exempt, m.
    rest_radius: f64,
}

/// Compressed rows of `items` listed under each of their particles.
fn incidence<const N: usize>(n: usize, items: &[[u32; N]]) -> (Vec<u32>, Vec<u32>) {
    let mut start = vec![0u32; n + 1];
    for item in items {
        for &v in item {
            start[v as usize + 1] += 1;
        }
    }
    for i in 0..n {
        start[i + 1] += start[i];
    }
    let mut cursor = start.clone();
    let mut list = vec![0u32; start[n] as usize];
    for (k, item) in items.iter().enumerate() {
        for &v in item {
            list[cursor[v as usize] as usize] = k as u32;
            cursor[v as usize] += 1;
        }
    }
    (start, list)
}

fn row(csr: &(Vec<u32>, Vec<u32>), i: usize) -> &[u32] {
    &csr.1[csr.0[i] as usize..csr.0[i + 1] as usize]
}

impl Topology {
    /// The topology of `mesh`, with each pair of `seams` counting as one particle and
    /// pairs within `rest_radius` of each other in the flat cloth exempt.
    pub fn new(mesh: &ClothMesh, seams: &[[usize; 2]], rest_radius: f64) -> Self {
        let n = mesh.vertex_count();
        let mut parent: Vec<u32> = (0..n as u32).collect();
        for &[a, b] in seams {
            union(&mut parent, a as u32, b as u32);
        }
        let rep: Vec<u32> = (0..n as u32).map(|i| find(&mut parent, i)).collect();

        let triangles: Vec<[u32; 3]> = mesh.triangles().iter().map(|t| t.map(|i| i as u32)).collect();
        let edges: Vec<[u32; 2]> = mesh.edges().iter().map(|e| e.map(|i| i as u32)).collect();
        let rep_edges: Vec<[u32; 2]> = edges
            .iter()
            .map(|e| e.map(|i| rep[i as usize]))
            .filter(|[a, b]| a != b)
            .collect();
        let (start, mut list) = incidence(n, &rep_edges);
        // Each row lists the edges; turn them into the other ends, sorted.
        for r in 0..n {
            let row = &mut list[start[r] as usize..start[r + 1] as usize];
            for e in row.iter_mut() {
                let [a, b] = rep_edges[*e as usize];
                *e = if a as usize == r { b } else { a };
            }
            row.sort_unstable();
        }
        let neighbours = (start, list);
        let vertex_triangles = incidence(n, &triangles);
        let owns = triangles
            .iter()
            .enumerate()
            .map(|(t, tri)| {
                let mut bits = 0;
                for k in 0..3 {
                    if row(&vertex_triangles, tri[k] as usize)[0] as usize == t {
                        bits |= OWNS_VERTEX << k;
                    }
                    let (a, b) = (tri[(k + 1) % 3], tri[(k + 2) % 3]);
                    let first = row(&vertex_triangles, a as usize)
                        .iter()
                        .find(|&&s| triangles[s as usize].contains(&b));
                    if first == Some(&(t as u32)) {
                        bits |= OWNS_EDGE << k;
                    }
                }
                bits
            })
            .collect();
        let edge_index: std::collections::HashMap<[u32; 2], u32> =
            edges.iter().enumerate().map(|(k, &e)| (e, k as u32)).collect();
        let opposite = |tri: &[u32; 3], k: usize| {
            let (a, b) = (tri[(k + 1) % 3], tri[(k + 2) % 3]);
            [a.min(b), a.max(b)]
        };
        let triangle_edges: Vec<[u32; 3]> = triangles
            .iter()
            .map(|tri| std::array::from_fn(|k| edge_index[&opposite(tri, k)]))
            .collect();
        let mut across = vec![[u32::MAX; 3]; triangles.len()];
        for h in mesh.hinges() {
            let [s, t] = h.triangles;
            let key = [h.edge[0].min(h.edge[1]) as u32, h.edge[0].max(h.edge[1]) as u32];
            for (from, to) in [(s, t), (t, s)] {
                let k = (0..3)
                    .find(|&k| opposite(&triangles[from], k) == key)
                    .expect("the hinge's edge is the triangle's");
                across[from][k] = to as u32;
            }
        }
        let corner_uv: Vec<_> = (0..triangles.len()).map(|t| mesh.corner_uv(t)).collect();
        let mut chart: Vec<u32> = (0..triangles.len() as u32).collect();
        for h in mesh.hinges() {
            let [s, t] = h.triangles;
            let uv = |t: usize, i: usize| {
                let k = mesh.triangles()[t]
                    .iter()
                    .position(|&v| v == i)
                    .expect("on the edge");
                corner_uv[t][k]
            };
            if h.edge.iter().all(|&i| uv(s, i) == uv(t, i)) {
                union(&mut chart, s as u32, t as u32);
            }
        }
        let roots: Vec<u32> = (0..triangles.len() as u32).map(|t| find(&mut chart, t)).collect();
        // Number the charts from 0, in the order of their first triangles.
        let mut number = vec![u32::MAX; triangles.len()];
        let mut charts = 0;
        let chart = roots
            .iter()
            .map(|&r| {
                if number[r as usize] == u32::MAX {
                    number[r as usize] = charts;
                    charts += 1;
                }
                number[r as usize]
            })
            .collect();
        Self {
            triangles,
            edges,
            rep,
            neighbours,
            owns,
            triangle_edges,
            across,
            vertex_triangles,
            corner_uv,
            chart,
            tangled: Vec::new(),
            pass_side: Vec::new(),
            loose: Vec::new(),
            loose_charts: Vec::new(),
            loose_frontier: Vec::new(),
            loose_next: Vec::new(),
            rest_radius,
        }
    }

    /// The chart of triangle `t`.
    pub fn chart(&self, t: usize) -> u32 {
        self.chart[t]
    }

    /// The chart of edge `e`: that of its first triangle.
    pub fn edge_chart(&self, e: usize) -> u32 {
        self.edge_triangles(e).next().map_or(u32::MAX, |t| self.chart[t])
    }

    /// A triangle of each chart: its first.
    pub fn chart_triangles(&self) -> Vec<usize> {
        let mut first = Vec::new();
        for (t, &c) in self.chart.iter().enumerate() {
            if c as usize == first.len() {
                first.push(t);
            }
        }
        first
    }

    /// Makes the chart pairs in `pairs` exempt from each other (and no others).
    pub fn set_tangled(&mut self, pairs: impl IntoIterator<Item = (u32, u32)>) {
        self.tangled.clear();
        self.tangled.extend(
            pairs
                .into_iter()
                .filter(|(a, b)| a != b)
                .map(|(a, b)| (a.min(b), a.max(b))),
        );
        self.tangled.sort_unstable();
        self.tangled.dedup();
    }

    pub fn tangled(&self) -> &[(u32, u32)] {
        &self.tangled
    }

    /// Makes the two sides of each of `passes` (a layer and the cloth let through it)
    /// exempt from each other, and no others. A particle on the sides of several passes is
    /// on the first's.
    pub fn set_passes<'a>(&mut self, passes: impl IntoIterator<Item = [&'a [usize]; 2]>) {
        self.pass_side.clear();
        for (k, sides) in passes.into_iter().enumerate() {
            if self.pass_side.is_empty() {
                self.pass_side.resize(self.rep.len(), u32::MAX);
            }
            for (side, particles) in sides.iter().enumerate() {
                for &p in *particles {
                    if let Some(mark) = self.pass_side.get_mut(p).filter(|m| **m == u32::MAX) {
                        *mark = 2 * k as u32 + side as u32;
                    }
                }
            }
        }
    }

    /// Whether particles `p` and `q` are on the two sides of one layer pass.
    fn passing(&self, p: u32, q: u32) -> bool {
        match (self.pass_side.get(p as usize), self.pass_side.get(q as usize)) {
            (Some(&a), Some(&b)) => a != u32::MAX && b != u32::MAX && a ^ b == 1,
            _ => false,
        }
    }

    /// Whether edge `e` and triangle `t` are on the two sides of a layer pass, one let
    /// through the other.
    pub fn edge_triangle_passing(&self, e: usize, t: usize) -> bool {
        !self.pass_side.is_empty()
            && self.edges[e]
                .iter()
                .any(|&p| self.triangles[t].iter().any(|&q| self.passing(p, q)))
    }

    /// Makes the cloth within `rings` edges of the `crossings` (edge, triangle) loose, and
    /// no other: where it is, the two charts of each crossing are exempt from each other,
    /// as cloth passing through itself is, while other cloth there still collides with
    /// both.
    pub fn set_loose(&mut self, crossings: &[(usize, usize)], rings: usize) {
        self.loose.clear();
        self.loose_charts.clear();
        if crossings.is_empty() {
            return;
        }
        // Called every step while a drape pulls tangled cloth apart: the marks, the
        // frontiers and the chart pairs live in buffers kept from step to step.
        self.loose.resize(self.rep.len(), false);
        let mut frontier = std::mem::take(&mut self.loose_frontier);
        let mut next = std::mem::take(&mut self.loose_next);
        frontier.clear();
        for &(e, t) in crossings {
            for p in self.edges[e].into_iter().chain(self.triangles[t]) {
                let r = self.rep[p as usize];
                if !self.loose[r as usize] {
                    self.loose[r as usize] = true;
                    frontier.push(r);
                }
            }
        }
        for _ in 0..rings {
            next.clear();
            for &r in &frontier {
                for &s in row(&self.neighbours, r as usize) {
                    if !self.loose[s as usize] {
                        self.loose[s as usize] = true;
                        next.push(s);
                    }
                }
            }
            if next.is_empty() {
                break;
            }
            std::mem::swap(&mut frontier, &mut next);
        }
        self.loose_frontier = frontier;
        self.loose_next = next;
        let mut charts = std::mem::take(&mut self.loose_charts);
        for &(e, t) in crossings {
            let b = self.chart[t];
            charts.extend(self.edge_triangles(e).map(|s| {
                let a = self.chart[s];
                (a.min(b), a.max(b))
            }));
        }
        charts.sort_unstable();
        charts.dedup();
        self.loose_charts = charts;
    }

    /// Whether particle `p` is loose (see [`Topology::set_loose`]).
    fn is_loose(&self, p: u32) -> bool {
        !self.loose.is_empty() && self.loose[self.rep[p as usize] as usize]
    }

    /// Whether charts `a` and `b` pass through each other where the cloth is loose.
    fn charts_loose(&self, a: u32, b: u32) -> bool {
        self.loose_charts.binary_search(&(a.min(b), a.max(b))).is_ok()
    }

    /// Whether particle `p` and triangle `t` are loose and of charts passing through each
    /// other there.
    fn particle_loose_with(&self, p: usize, t: usize) -> bool {
        self.is_loose(p as u32)
            && self.triangles[t].iter().any(|&q| self.is_loose(q))
            && self
                .triangles_of(p)
                .iter()
                .any(|&s| self.charts_loose(self.chart[s as usize], self.chart[t]))
    }

    /// Whether edges `e` and `f` are loose and of charts passing through each other there.
    fn edges_loose(&self, e: usize, f: usize) -> bool {
        self.edges[e].iter().any(|&i| self.is_loose(i))
            && self.edges[f].iter().any(|&j| self.is_loose(j))
            && self.edge_triangles(e).any(|s| {
                self.edge_triangles(f)
                    .any(|t| self.charts_loose(self.chart[s], self.chart[t]))
            })
    }

    /// Whether charts `a` and `b` are exempt from each other, having begun tangled.
    fn charts_tangled(&self, a: u32, b: u32) -> bool {
        a != b && self.tangled.binary_search(&(a.min(b), a.max(b))).is_ok()
    }

    /// Whether some triangle of particle `p` is of a chart tangled with `chart`.
    fn particle_tangled_with(&self, p: usize, chart: u32) -> bool {
        !self.tangled.is_empty()
            && self
                .triangles_of(p)
                .iter()
                .any(|&s| self.charts_tangled(self.chart[s as usize], chart))
    }

    /// Whether some triangle of edge `e` is of a chart tangled with `chart`.
    fn edge_tangled_with(&self, e: usize, chart: u32) -> bool {
        !self.tangled.is_empty()
            && self
                .edge_triangles(e)
                .any(|s| self.charts_tangled(self.chart[s], chart))
    }

    /// The material coordinates of particle `i` in triangle `t` (one of its own), as a
    /// point of the plane z = 0.
    fn material(&self, t: usize, i: u32) -> Vec3 {
        let k = self.triangles[t].iter().position(|&v| v == i).unwrap_or(0);
        self.corner_uv[t][k].push(0.0)
    }

    fn material_triangle(&self, t: usize) -> [Vec3; 3] {
        self.corner_uv[t].map(|p| p.push(0.0))
    }

    /// The triangles of edge `e`.
    pub fn edge_triangles(&self, e: usize) -> impl Iterator<Item = usize> + '_ {
        let [a, b] = self.edges[e];
        self.triangles_of(a as usize)
            .iter()
            .map(|&t| t as usize)
            .filter(move |&t| self.triangles[t].contains(&b))
    }

    /// Edge `e`'s ends in the material coordinates of its triangle `t`.
    fn material_edge(&self, t: usize, e: usize) -> [Vec3; 2] {
        self.edges[e].map(|i| self.material(t, i))
    }

    pub fn particles(&self) -> usize {
        self.rep.len()
    }

    /// Whether particles `i` and `j` are one, or neighbours (seam partners counting as one).
    fn near_in_mesh(&self, i: u32, j: u32) -> bool {
        let (a, b) = (self.rep[i as usize], self.rep[j as usize]);
        a == b || row(&self.neighbours, a as usize).binary_search(&b).is_ok()
    }

    /// Particle `p` and triangle `t` are not in contact (see the module's introduction),
    /// nor while their charts are tangled, they are on the two sides of a layer pass, or
    /// both are loose.
    pub fn vertex_triangle_exempt(&self, p: usize, t: usize) -> bool {
        if self.particle_tangled_with(p, self.chart[t]) {
            return true;
        }
        if !self.pass_side.is_empty() && self.triangles[t].iter().any(|&q| self.passing(p as u32, q)) {
            return true;
        }
        if !self.loose.is_empty() && self.particle_loose_with(p, t) {
            return true;
        }
        self.near_for_good(p, t)
    }

    /// Particle `p` and triangle `t` are near in the mesh or in the flat cloth (see the
    /// module's introduction).
    fn near_for_good(&self, p: usize, t: usize) -> bool {
        if self.triangles[t].iter().any(|&i| self.near_in_mesh(p as u32, i)) {
            return true;
        }
        let [a, b, c] = self.material_triangle(t);
        self.triangles_of(p).iter().any(|&s| {
            let s = s as usize;
            self.chart[s] == self.chart[t] && {
                let q = self.material(s, p as u32);
                let w = closest_on_triangle(&q, &a, &b, &c);
                (q - (w[0] * a + w[1] * b + w[2] * c)).norm() < self.rest_radius
            }
        })
    }

    /// Edges `e` and `f` are not in contact (as for a particle and a triangle).
    pub fn edge_edge_exempt(&self, e: usize, f: usize) -> bool {
        if self.edges[e]
            .iter()
            .any(|&i| self.edges[f].iter().any(|&j| self.near_in_mesh(i, j)))
        {
            return true;
        }
        if !self.tangled.is_empty()
            && self
                .edge_triangles(f)
                .any(|t| self.edge_tangled_with(e, self.chart[t]))
        {
            return true;
        }
        if !self.pass_side.is_empty()
            && self.edges[e]
                .iter()
                .any(|&i| self.edges[f].iter().any(|&j| self.passing(i, j)))
        {
            return true;
        }
        if !self.loose.is_empty() && self.edges_loose(e, f) {
            return true;
        }
        self.edge_triangles(e).any(|s| {
            self.edge_triangles(f).any(|t| {
                self.chart[s] == self.chart[t] && {
                    let [p0, p1] = self.material_edge(s, e);
                    let [q0, q1] = self.material_edge(t, f);
                    let (u, v) = closest_on_segments(&p0, &p1, &q0, &q1);
                    (p0 + u * (p1 - p0) - q0 - v * (q1 - q0)).norm() < self.rest_radius
                }
            })
        })
    }

    /// Edge `e` and triangle `t` are never counted as intersecting (as for a particle and a
    /// triangle).
    pub fn edge_triangle_exempt(&self, e: usize, t: usize) -> bool {
        if self.edges[e]
            .iter()
            .any(|&i| self.triangles[t].iter().any(|&j| self.near_in_mesh(i, j)))
        {
            return true;
        }
        let tri = self.material_triangle(t);
        self.edge_triangles(e).any(|s| {
            self.chart[s] == self.chart[t] && {
                let [p, q] = self.material_edge(s, e);
                material_distance(&p, &q, &tri) < self.rest_radius
            }
        })
    }

    /// Whether the segment between particles `a` and `b` (a seam's pair) is never counted
    /// as crossing triangle `t`: `t` is near either of them for good (see
    /// [`Topology::vertex_triangle_exempt`]).
    pub fn segment_triangle_exempt(&self, a: usize, b: usize, t: usize) -> bool {
        self.near_for_good(a, t) || self.near_for_good(b, t)
    }

    /// The representatives within `rings` edges of particle `p`'s, seam partners counting
    /// as one, sorted.
    pub fn joined_within(&self, p: usize, rings: usize) -> Vec<u32> {
        within_rings(vec![self.rep[p]], rings, |r| {
            row(&self.neighbours, r as usize).iter().copied()
        })
    }

    /// Whether some corner of triangle `t` is one of `reps` (sorted representatives).
    pub fn triangle_among(&self, t: usize, reps: &[u32]) -> bool {
        self.triangles[t]
            .iter()
            .any(|&i| reps.binary_search(&self.rep[i as usize]).is_ok())
    }

    /// Whether triangle `t` speaks for the nearest point at barycentric `weights`: always
    /// inside the face; on an edge or at a vertex, only the first triangle having it.
    pub fn owns_point(&self, t: usize, weights: &[f64; 3]) -> bool {
        let zeros = weights.iter().filter(|&&w| w == 0.0).count();
        let bits = self.owns[t];
        match zeros {
            0 => true,
            1 => {
                let k = weights.iter().position(|&w| w == 0.0).expect("one zero");
                bits & (OWNS_EDGE << k) != 0
            }
            _ => {
                let k = weights.iter().position(|&w| w != 0.0).unwrap_or(0);
                bits & (OWNS_VERTEX << k) != 0
            }
        }
    }

    /// The corners (bits 0 to 2) and the edges opposite corners (bits 3 to 5) triangle `t`
    /// speaks for: each particle and each edge has one triangle.
    pub fn owned(&self, t: usize) -> u8 {
        self.owns[t]
    }

    /// The triangle across the edge opposite corner `k` of triangle `t`, if any.
    pub fn across(&self, t: usize, k: usize) -> Option<usize> {
        let s = self.across[t][k];
        (s != u32::MAX).then_some(s as usize)
    }

    pub fn triangles_of(&self, i: usize) -> &[u32] {
        row(&self.vertex_triangles, i)
    }
}

/// The distance between segment `p q` and triangle `t`, all in the plane z = 0.
fn material_distance(p: &Vec3, q: &Vec3, t: &[Vec3; 3]) -> f64 {
    let through = |p: &Vec3, q: &Vec3| {
        let up = Vec3::z();
        // The segment meets the flat triangle if one of its points does: test each end,
        // and the segment against each edge.
        let inside = |x: &Vec3| segment_crosses_triangle(&(x + up), &(x - up), t);
        inside(p) || inside(q)
    };
    if through(p, q) {
        return 0.0;
    }
    let to_triangle = |x: &Vec3| {
        let w = closest_on_triangle(x, &t[0], &t[1], &t[2]);
        (x - (w[0] * t[0] + w[1] * t[1] + w[2] * t[2])).norm()
    };
    let to_edge = |a: &Vec3, b: &Vec3| {
        let (u, v) = closest_on_segments(p, q, a, b);
        (p + u * (q - p) - a - v * (b - a)).norm()
    };
    to_triangle(p)
        .min(to_triangle(q))
        .min(to_edge(&t[0], &t[1]))
        .min(to_edge(&t[1], &t[2]))
        .min(to_edge(&t[2], &t[0]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::GridBuilder;

    #[test]
    fn each_edge_and_vertex_has_one_owner_and_seams_exempt_their_neighbours() {
        let mesh = GridBuilder::new(4, 3).size(0.3, 0.2).build().unwrap();
        let topo = Topology::new(&mesh, &[[0, 11]], 1e-3);
        for (i, _) in mesh.positions().iter().enumerate() {
            let owners = topo
                .triangles_of(i)
                .iter()
                .filter(|&&t| {
                    let k = topo.triangles[t as usize]
                        .iter()
                        .position(|&v| v as usize == i)
                        .unwrap();
                    topo.owns[t as usize] & (OWNS_VERTEX << k) != 0
                })
                .count();
            assert_eq!(owners, 1, "vertex {i}");
        }
        for e in &topo.edges {
            let owners = topo
                .triangles_of(e[0] as usize)
                .iter()
                .filter(|&&t| {
                    let tri = topo.triangles[t as usize];
                    (0..3).any(|k| {
                        !(tri[k] == e[0] || tri[k] == e[1])
                            && tri.contains(&e[0])
                            && tri.contains(&e[1])
                            && topo.owns[t as usize] & (OWNS_EDGE << k) != 0
                    })
                })
                .count();
            assert_eq!(owners, 1, "edge {e:?}");
        }
        // Particles 0 and 11 (opposite corners) are sewn: 0 is exempt from 11's triangles and
        // from those of 11's neighbours, but not from a triangle farther away.
        let t11 = topo.triangles_of(11)[0] as usize;
        assert!(topo.vertex_triangle_exempt(0, t11));
        let t7 = topo
            .triangles_of(7)
            .iter()
            .find(|&&t| !topo.triangles[t as usize].contains(&11));
        assert!(topo.vertex_triangle_exempt(0, *t7.unwrap() as usize));
        // Particle 4 (second row, first column) and the triangle of 6, 10, 11? Far: not exempt
        // unless they touch 4's neighbours.
        for t in 0..topo.triangles.len() {
            let near = topo.triangles[t].iter().any(|&i| topo.near_in_mesh(4, i));
            assert_eq!(topo.vertex_triangle_exempt(4, t), near, "triangle {t}");
        }
    }

    /// Square pieces of `n` x `n` particles, 20 cm wide, one at each height of `heights`,
    /// as one mesh.
    fn pieces(n: usize, heights: &[f64]) -> ClothMesh {
        let piece = |z: f64| {
            GridBuilder::new(n, n)
                .size(0.2, 0.2)
                .origin(Vec3::new(0.0, 0.0, z))
                .build()
                .unwrap()
        };
        ClothMesh::join(&heights.iter().map(|&z| piece(z)).collect::<Vec<_>>()).unwrap()
    }

    #[test]
    fn a_layer_pass_exempts_its_two_sides_from_each_other_and_nothing_else() {
        // Two pieces 3 x 3 apart: the first's particles are the layer, the second's first
        // row the side let through it.
        let mesh = pieces(3, &[0.0, 0.1]);
        let mut topo = Topology::new(&mesh, &[], 1e-3);
        let layer: Vec<usize> = (0..9).collect();
        let side: Vec<usize> = (9..12).collect();
        // The triangles not near particle `p` in the mesh.
        fn far_from(topo: &Topology, p: usize) -> Vec<usize> {
            (0..topo.triangles.len())
                .filter(|&t| !topo.triangles[t].iter().any(|&i| topo.near_in_mesh(p as u32, i)))
                .collect()
        }
        let none_exempt = |topo: &Topology| {
            (0..18).all(|p| {
                far_from(topo, p)
                    .into_iter()
                    .all(|t| !topo.vertex_triangle_exempt(p, t))
            })
        };
        assert!(none_exempt(&topo));
        topo.set_passes([[layer.as_slice(), side.as_slice()]]);
        for p in 0..18 {
            for t in far_from(&topo, p) {
                let has = |set: &[usize]| topo.triangles[t].iter().any(|&i| set.contains(&(i as usize)));
                let expected = (layer.contains(&p) && has(&side)) || (side.contains(&p) && has(&layer));
                assert_eq!(
                    topo.vertex_triangle_exempt(p, t),
                    expected,
                    "particle {p}, triangle {t}"
                );
            }
        }
        for e in 0..topo.edges.len() {
            for f in 0..topo.edges.len() {
                let ends =
                    |k: usize, set: &[usize]| topo.edges[k].iter().any(|&i| set.contains(&(i as usize)));
                let expected = (ends(e, &layer) && ends(f, &side)) || (ends(e, &side) && ends(f, &layer));
                if expected {
                    assert!(topo.edge_edge_exempt(e, f), "edges {e} {f}");
                }
                let same_piece = topo.edges[e][0] < 9 && topo.edges[f][0] < 9
                    || topo.edges[e][0] >= 9 && topo.edges[f][0] >= 9;
                if !expected && !same_piece {
                    assert!(!topo.edge_edge_exempt(e, f), "edges {e} {f}");
                }
            }
        }
        // Passes ended, nothing is exempt across the pieces.
        topo.set_passes([]);
        assert!(none_exempt(&topo));
    }

    #[test]
    fn loose_cloth_is_exempt_from_the_cloth_it_passes_through_and_from_nothing_else() {
        // Three pieces of 5 x 5 particles, 10 cm apart: an edge of the first's middle
        // (particle 12) through a triangle of the second's (37), and the third's middle (62)
        // through itself.
        let mesh = pieces(5, &[0.0, 0.1, 0.2]);
        let mut topo = Topology::new(&mesh, &[], 1e-3);
        let edge_of = |p: usize| mesh.edges().iter().position(|e| e.contains(&p)).unwrap();
        let triangle_of = |p: usize| mesh.triangles().iter().position(|t| t.contains(&p)).unwrap();
        let crossings = [(edge_of(12), triangle_of(37)), (edge_of(62), triangle_of(68))];
        topo.set_loose(&crossings, 1);
        // Loose: the crossings' particles and those an edge joins them to.
        let mut expected_loose: Vec<usize> = Vec::new();
        for &(e, t) in &crossings {
            let seeds: Vec<usize> = mesh.edges()[e].into_iter().chain(mesh.triangles()[t]).collect();
            for edge in mesh.edges() {
                for &s in &seeds {
                    if edge.contains(&s) {
                        expected_loose.extend(edge);
                    }
                }
            }
        }
        expected_loose.sort_unstable();
        expected_loose.dedup();
        let loose: Vec<usize> = (0..75).filter(|&p| topo.is_loose(p as u32)).collect();
        assert_eq!(loose, expected_loose);
        let piece_of = |p: usize| p / 25;
        let passing = |a: usize, b: usize| (a.min(b), a.max(b)) == (0, 1) || (a, b) == (2, 2);
        let far = |topo: &Topology, p: usize, t: usize| {
            !topo.triangles[t].iter().any(|&i| topo.near_in_mesh(p as u32, i)) && !topo.near_for_good(p, t)
        };
        let mut exempt = [0; 2];
        for p in 0..75 {
            for t in (0..topo.triangles.len()).filter(|&t| far(&topo, p, t)) {
                let q = topo.triangles[t][0] as usize;
                let expected = loose.contains(&p)
                    && topo.triangles[t].iter().any(|&i| loose.contains(&(i as usize)))
                    && passing(piece_of(p), piece_of(q));
                assert_eq!(
                    topo.vertex_triangle_exempt(p, t),
                    expected,
                    "particle {p}, triangle {t}"
                );
                if expected {
                    exempt[usize::from(piece_of(p) == 2)] += 1;
                }
            }
        }
        // Both the two pieces through each other and the one through itself.
        assert!(exempt[0] > 0 && exempt[1] > 0, "{exempt:?}");
        for e in 0..topo.edges.len() {
            for f in 0..topo.edges.len() {
                let (a, b) = (topo.edges[e][0] as usize, topo.edges[f][0] as usize);
                if piece_of(a) != piece_of(b) {
                    let ends = |k: usize| topo.edges[k].iter().any(|&i| loose.contains(&(i as usize)));
                    let expected = ends(e) && ends(f) && passing(piece_of(a), piece_of(b));
                    assert_eq!(topo.edge_edge_exempt(e, f), expected, "edges {e} {f}");
                }
            }
        }
        // Loose no more, nothing is exempt across the pieces.
        topo.set_loose(&[], 1);
        for p in 0..25 {
            for t in 32..64 {
                assert!(!topo.vertex_triangle_exempt(p, t), "particle {p}, triangle {t}");
            }
        }
        // Loose again, elsewhere and wider, with the buffers of the first call: the
        // particles within two edges of the crossing and no others.
        let (e, t) = crossings[1];
        topo.set_loose(&[(e, t)], 2);
        let seeds: Vec<usize> = mesh.edges()[e].into_iter().chain(mesh.triangles()[t]).collect();
        let expected = crate::mesh::Neighbours::of(&mesh).around(seeds, 2);
        let loose: Vec<usize> = (0..75).filter(|&p| topo.is_loose(p as u32)).collect();
        assert_eq!(loose, expected);
        assert!(loose.iter().all(|&p| piece_of(p) == 2) && loose.len() > expected_loose.len() / 2);
    }
}
