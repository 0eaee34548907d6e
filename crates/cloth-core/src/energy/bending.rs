//! Bending on hinges from the signed dihedral angle.
//!
//! With the hinge edge `x0 -> x1` and the opposite vertices `x2`, `x3`, let
//! `a = x1 - x0`, `b = x2 - x0`, `c = x3 - x0`. Then the bend angle is
//! `psi = atan2(-|a| det(a, b, c), (a.c)(a.b) - (a.a)(b.c))` (the second argument is
//! the dot product of the two face normals, the first their cross product along the
//! edge), so psi = 0 when flat and its Hessian has a short closed form.
//!
//! The hinge energy is `k f(psi)` with `f = psi^2/2` (quadratic) or `1 - cos psi` (the
//! source's `mu_b cos^2(theta/2)` with `mu_b = 2k`). The stiffness is scaled from the
//! continuum rigidity B (N*m) as `k = B(fold direction) * |e|^2 / (A1 + A2)` with rest
//! quantities, which makes it independent of the mesh resolution, and the warp and weft
//! rigidities are multiplied by factors calibrated on the mesh's cells (see
//! [`calibration`]) so that bending across either thread comes out at its rigidity B.

use super::{HessianMode, Local};
use crate::fabric::{BendingLaw, BendingRigidity};
use crate::math::{Mat3, Vec3};
use crate::mesh::{ClothMesh, Hinge};

/// Signed bend angle of a hinge with its gradient (and Hessian) over (x0, x1, x2, x3).
pub struct Dihedral {
    pub psi: f64,
    pub grad: [Vec3; 4],
    /// Present when asked for.
    pub hess: Option<[[Mat3; 4]; 4]>,
}

/// The hinge angle; `None` when a face is degenerate (no normal).
pub fn dihedral(x: &[Vec3; 4], with_hessian: bool) -> Option<Dihedral> {
    let (a, b, c) = (x[1] - x[0], x[2] - x[0], x[3] - x[0]);
    let (aa, ab, ac, bc) = (a.dot(&a), a.dot(&b), a.dot(&c), b.dot(&c));
    let la = aa.sqrt();
    let bxc = b.cross(&c);
    let cxa = c.cross(&a);
    let axb = a.cross(&b);
    let det = a.dot(&bxc);
    let xv = ac * ab - aa * bc;
    let yv = -la * det;
    let r2 = xv * xv + yv * yv;
    // Both faces have (near) zero area when their normals' product vanishes.
    if !(r2 > 1e-24 * aa * aa * aa * aa) {
        return None;
    }
    let ah = a / la;
    let gx = [c * ab + b * ac - 2.0 * a * bc, a * ac - c * aa, a * ab - b * aa];
    let gy = [-(ah * det + la * bxc), -la * cxa, -la * axb];
    let (px, py) = (-yv / r2, xv / r2);
    let g3: [Vec3; 3] = std::array::from_fn(|k| px * gx[k] + py * gy[k]);
    let grad = [-(g3[0] + g3[1] + g3[2]), g3[0], g3[1], g3[2]];
    let psi = yv.atan2(xv);
    if !with_hessian {
        return Some(Dihedral {
            psi,
            grad,
            hess: None,
        });
    }
    let id = Mat3::identity();
    let z = Mat3::zeros();
    // Second derivatives of x and y over (a, b, c), block [k][l] = d2/(dk dl).
    let hx_ab = c * a.transpose() + ac * id - 2.0 * a * c.transpose();
    let hx_ac = b * a.transpose() + ab * id - 2.0 * a * b.transpose();
    let hx_bc = a * a.transpose() - aa * id;
    let hx = [
        [
            c * b.transpose() + b * c.transpose() - 2.0 * bc * id,
            hx_ab,
            hx_ac,
        ],
        [hx_ab.transpose(), z, hx_bc],
        [hx_ac.transpose(), hx_bc.transpose(), z],
    ];
    let hy_ab = -(ah * cxa.transpose() - la * c.cross_matrix());
    let hy_ac = -(ah * axb.transpose() + la * b.cross_matrix());
    let hy_bc = la * a.cross_matrix();
    let hy = [
        [
            -((id - ah * ah.transpose()) * (det / la) + ah * bxc.transpose() + bxc * ah.transpose()),
            hy_ab,
            hy_ac,
        ],
        [hy_ab.transpose(), z, hy_bc],
        [hy_ac.transpose(), hy_bc.transpose(), z],
    ];
    let r4 = r2 * r2;
    let (pxx, pyy, pxy) = (2.0 * xv * yv / r4, -2.0 * xv * yv / r4, (yv * yv - xv * xv) / r4);
    let mut h3 = [[z; 3]; 3];
    for k in 0..3 {
        for l in 0..3 {
            h3[k][l] = px * hx[k][l]
                + py * hy[k][l]
                + pxx * gx[k] * gx[l].transpose()
                + pyy * gy[k] * gy[l].transpose()
                + pxy * (gx[k] * gy[l].transpose() + gy[k] * gx[l].transpose());
        }
    }
    // Back from (a, b, c) to the vertices: x0 enters every difference with a minus sign.
    let mut hess = [[z; 4]; 4];
    for k in 0..3 {
        for l in 0..3 {
            hess[k + 1][l + 1] = h3[k][l];
        }
    }
    for k in 0..3 {
        let row: Mat3 = h3[k][0] + h3[k][1] + h3[k][2];
        hess[k + 1][0] = -row;
        hess[0][k + 1] = -row.transpose();
    }
    hess[0][0] = h3.iter().flatten().sum();
    Some(Dihedral {
        psi,
        grad,
        hess: Some(hess),
    })
}

/// Adds the bending energy of one hinge with stiffness `k` (N*m per rad^2).
pub fn add_bending(law: BendingLaw, k: f64, x: &[Vec3; 4], mode: HessianMode, out: &mut Local<4>) {
    if k == 0.0 {
        return;
    }
    let Some(d) = dihedral(x, mode == HessianMode::Exact) else {
        return;
    };
    let (f, f1, f2) = match law {
        BendingLaw::Quadratic => (0.5 * d.psi * d.psi, d.psi, 1.0),
        BendingLaw::SourceCosine => (1.0 - d.psi.cos(), d.psi.sin(), d.psi.cos()),
    };
    out.energy += k * f;
    for i in 0..4 {
        out.grad[i] += (k * f1) * d.grad[i];
    }
    match mode {
        HessianMode::None => {}
        // The psi-curvature term k f' d2psi is indefinite; it vanishes when flat.
        HessianMode::Projected => out.add_outer(k * f2.max(0.0), &d.grad),
        HessianMode::Exact => {
            out.add_outer(k * f2, &d.grad);
            if let Some(h) = d.hess {
                for i in 0..4 {
                    for j in 0..4 {
                        out.hess[i][j] += (k * f1) * h[i][j];
                    }
                }
            }
        }
    }
}

/// The factor on a hinge's stiffness where one wing is clamped: a triangle whose three
/// vertices are pinned is held rigid, so the hinge's bend lies wholly in the free wing
/// and its stiffness is `B |e|^2 / A_free` rather than `B |e|^2 / (A1 + A2)`. Without
/// it a clamp sits half a cell inside the clamped region, an error of first order in the
/// cell size (twice the cell over the overhang, relative, on a cantilever's tip drop).
/// `ids` are the hinge's (edge, edge, opposite, opposite) vertices.
/// `wing_areas` are the rest areas of the triangles holding `ids[2]` and `ids[3]`.
pub fn clamp_factor(ids: [usize; 4], wing_areas: [f64; 2], pinned: &[bool]) -> f64 {
    let wing_pinned = |o: usize| pinned[ids[0]] && pinned[ids[1]] && pinned[ids[o]];
    let [a2, a3] = wing_areas;
    match (wing_pinned(2), wing_pinned(3)) {
        (true, false) => (a2 + a3) / a3,
        (false, true) => (a2 + a3) / a2,
        _ => 1.0,
    }
}

/// The hinge's edge in each wing's material coordinates (edge[0] to edge[1]). Across a
/// seam the two panels see the edge at their own angles to their grain.
fn wing_edges(mesh: &ClothMesh, h: &Hinge) -> [nalgebra::Vector2<f64>; 2] {
    h.triangles.map(|t| {
        let tri = mesh.triangles()[t];
        let c = mesh.corner_uv(t);
        let at = |v: usize| {
            c[tri
                .iter()
                .position(|&i| i == v)
                .expect("hinge edge is on its wing")]
        };
        at(h.edge[1]) - at(h.edge[0])
    })
}

/// Rest geometry of a hinge in material space: `|e|^2 / (A1 + A2)` and the fold
/// direction in each wing.
fn hinge_rest(mesh: &ClothMesh, h: &Hinge) -> (f64, [nalgebra::Vector2<f64>; 2]) {
    let e = wing_edges(mesh, h);
    let len2 = e[0].norm() * e[1].norm();
    let areas = mesh.rest_area(h.triangles[0]) + mesh.rest_area(h.triangles[1]);
    (len2 / areas, e.map(|e| e / e.norm()))
}

/// Calibration of the hinge stiffness against the continuum rigidity: the factors
/// `[kappa_warp, kappa_weft]` that scale the warp and weft rigidities.
///
/// The flat rest mesh is bent to unit curvature across the warp, `z = u^2 / 2` (then
/// across the weft), as a fabric is in a bending measurement: the strip stays free to
/// curve sideways and to twist (`v^2 / 2` and `u v` with free amplitudes), and to relax
/// at the mesh scale (a fluctuation `w`). A hinge mesh relaxes a lot: cells fold along
/// their diagonals and share the bend, and the diagonal hinges couple bending to sideways
/// curvature. The relaxed hinge energy (linearised: a sparse Cholesky and a 3 x 3 Schur
/// complement) is matched to the continuum `B K^2 / 2` per unit area in each direction,
/// a few fixed-point rounds settling the coupling between the two. A cantilever then
/// comes out at the rigidity B. A wide sheet forced into a cylinder cannot use the
/// sideways freedom and is somewhat stiffer (about 10% on a grid with alternating
/// diagonals): the hinge model's own Poisson-like coupling, which real cloth lacks.
///
/// `w` is held at zero on the two outermost vertex rings (a clamped edge, so no smooth
/// `w` can undo the curvature) and only triangles four or more rings in are counted. A
/// grid is calibrated on a 24 x 24 patch of the same cells, so a narrow strip gets the
/// value of its pattern; other meshes on themselves. A non-grid mesh with no triangle
/// four rings from its boundary (under about nine vertices across) is left at 1, which
/// on grid-like cells is about a fifth too soft. Bias bending on grids comes out
/// stiffer than the rigidity interpolated for it.
pub fn calibration(mesh: &ClothMesh, rigidity: &BendingRigidity) -> [f64; 2] {
    let patch = mesh.grid().and_then(|g| {
        crate::mesh::GridBuilder::new(25, 25)
            .spacing(g.du, g.dv)
            .diagonals(g.diagonals)
            .build()
            .ok()
    });
    // A sewn garment is calibrated on its panels, where material coordinates are smooth.
    let cut = (patch.is_none() && mesh.has_seams()).then(|| mesh.cut_at_seams());
    let target = patch.as_ref().or(cut.as_ref()).unwrap_or(mesh);
    relaxed_calibration(target, rigidity).unwrap_or([1.0, 1.0])
}

/// Rings held at w = 0, and the first ring whose triangles are counted.
const CLAMPED_RINGS: usize = 2;
const COUNTED_RING: usize = 4;
/// Fixed-point rounds between the warp and weft factors (they settle to 1e-6 in a few).
const ROUNDS: usize = 12;

/// Flat-state data of one hinge for the calibration.
struct FlatHinge {
    edge: [usize; 2],
    ids: [usize; 4],
    dz: [f64; 4],
    ratio: f64,
    fold: (f64, f64),
    /// Angle under the macroscopic modes u^2/2, v^2/2, u v.
    modes: nalgebra::Vector3<f64>,
}

fn relaxed_calibration(mesh: &ClothMesh, rigidity: &BendingRigidity) -> Option<[f64; 2]> {
    let scale = 0.5 * (rigidity.warp + rigidity.weft);
    if !(scale > 0.0) {
        return None;
    }
    let uv = mesh.uv();
    let ring = rings_from_boundary(mesh)?;
    let mut index = vec![usize::MAX; mesh.vertex_count()];
    let mut free = 0;
    for (i, r) in ring.iter().enumerate() {
        if *r >= CLAMPED_RINGS {
            index[i] = free;
            free += 1;
        }
    }
    if free == 0 {
        return None;
    }
    let hinges: Vec<FlatHinge> = mesh
        .hinges()
        .iter()
        .filter_map(|h| {
            let ids = [h.edge[0], h.edge[1], h.opposite[0], h.opposite[1]];
            let o = uv[ids[0]];
            let local = ids.map(|i| uv[i] - o);
            let dh = dihedral(&local.map(|q| Vec3::new(q.x, q.y, 0.0)), false)?;
            let dz = dh.grad.map(|g| g.z);
            // Calibration meshes have no seams: both wings see the same edge.
            let (ratio, [dir, _]) = hinge_rest(mesh, h);
            let (tu, tv) = (dir.x, dir.y);
            // psi ignores affine fields, so local coordinates serve.
            let mut modes = nalgebra::Vector3::zeros();
            for k in 0..4 {
                let (x, y) = (local[k].x, local[k].y);
                modes += dz[k] * nalgebra::Vector3::new(0.5 * x * x, 0.5 * y * y, x * y);
            }
            Some(FlatHinge {
                edge: h.edge,
                ids,
                dz,
                ratio,
                fold: (tu, tv),
                modes,
            })
        })
        .collect();
    // A direction without rigidity would leave its modes free and the system singular;
    // a tiny floor gives the continuous limit (its factor then scales zero anyway).
    let rigidity = BendingRigidity {
        warp: rigidity.warp.max(1e-6 * scale),
        weft: rigidity.weft.max(1e-6 * scale),
        bias: rigidity.bias,
    };
    let relaxation = Relaxation::new(mesh, &hinges, &index, free, &ring)?;
    let target = [0.5 * rigidity.warp / scale, 0.5 * rigidity.weft / scale];
    let mut kappa = [1.0, 1.0];
    for _ in 0..ROUNDS {
        let scaled = BendingRigidity {
            warp: kappa[0] * rigidity.warp / scale,
            weft: kappa[1] * rigidity.weft / scale,
            bias: rigidity.bias.map(|b| 0.5 * (kappa[0] + kappa[1]) * b / scale),
        };
        let k: Vec<f64> = hinges
            .iter()
            .map(|h| h.ratio * scaled.along_fold(h.fold.0, h.fold.1))
            .collect();
        let energy = relaxation.energies(&k)?;
        let mut change: f64 = 0.0;
        for d in 0..2 {
            if target[d] > 0.0 {
                let factor = target[d] / energy[d];
                kappa[d] *= factor;
                change = change.max((factor - 1.0).abs());
            }
        }
        if change < 1e-9 {
            break;
        }
    }
    kappa.iter().all(|k| k.is_finite() && *k > 0.0).then_some(kappa)
}

/// The linear system of a flat mesh's relaxation under imposed bends, set up once for
/// the rounds of a calibration, which change only the hinges' stiffnesses: the pattern
/// of the fluctuation's stiffness (its lower triangle), where each term goes in it, and
/// its symbolic Cholesky factor; and each counted triangle's hinges.
struct Relaxation<'a> {
    hinges: &'a [FlatHinge],
    index: &'a [usize],
    free: usize,
    pattern: faer::sparse::SymbolicSparseColMat<usize>,
    /// Each hinge term of the lower triangle, in the hinges' order: the slot of the
    /// pattern's values it adds to, the hinge, and the hinge's two particles.
    terms: Vec<(usize, usize, usize, usize)>,
    /// Each free particle's diagonal slot.
    diagonal: Vec<usize>,
    symbolic: faer::sparse::linalg::solvers::SymbolicLlt<usize>,
    /// Per triangle four rings in whose edges are all hinges: its rest area and its hinges.
    counted: Vec<(f64, [usize; 3])>,
}

impl<'a> Relaxation<'a> {
    fn new(
        mesh: &ClothMesh,
        hinges: &'a [FlatHinge],
        index: &'a [usize],
        free: usize,
        ring: &[usize],
    ) -> Option<Self> {
        use faer::sparse::linalg::solvers::SymbolicLlt;
        use faer::sparse::SymbolicSparseColMat;
        // (row, col, hinge, a, c) for hinge `hinge`'s term between its particles `a` and `c`.
        let mut entries = Vec::new();
        for (k, h) in hinges.iter().enumerate() {
            for a in 0..4 {
                let ia = index[h.ids[a]];
                for c in 0..4 {
                    let ic = index[h.ids[c]];
                    if ia != usize::MAX && ic != usize::MAX && ia >= ic {
                        entries.push((ia, ic, k, a, c));
                    }
                }
            }
        }
        // By columns, every diagonal block in it.
        let mut unique: Vec<(usize, usize)> = entries
            .iter()
            .map(|e| (e.1, e.0))
            .chain((0..free).map(|i| (i, i)))
            .collect();
        unique.sort_unstable();
        unique.dedup();
        let mut col_ptr = vec![0usize; free + 1];
        for &(col, _) in &unique {
            col_ptr[col + 1] += 1;
        }
        for c in 0..free {
            col_ptr[c + 1] += col_ptr[c];
        }
        let row_idx: Vec<usize> = unique.iter().map(|&(_, row)| row).collect();
        let slot = |col: usize, row: usize| unique.binary_search(&(col, row)).expect("in the pattern");
        let terms = entries
            .iter()
            .map(|&(row, col, k, a, c)| (slot(col, row), k, a, c))
            .collect();
        let diagonal = (0..free).map(|i| slot(i, i)).collect();
        let pattern = SymbolicSparseColMat::new_checked(free, free, col_ptr, None, row_idx);
        let symbolic = SymbolicLlt::try_new(pattern.as_ref(), faer::Side::Lower).ok()?;
        let of_edge: std::collections::HashMap<[usize; 2], usize> =
            hinges.iter().enumerate().map(|(k, h)| (h.edge, k)).collect();
        let counted = mesh
            .triangles()
            .iter()
            .enumerate()
            .filter(|(_, tri)| tri.iter().all(|&i| ring[i] >= COUNTED_RING))
            .filter_map(|(t, tri)| {
                let hinge = |c: usize| {
                    let (p, q) = (tri[c], tri[(c + 1) % 3]);
                    of_edge.get(&if p < q { [p, q] } else { [q, p] }).copied()
                };
                Some((mesh.rest_area(t), [hinge(0)?, hinge(1)?, hinge(2)?]))
            })
            .collect();
        Some(Self {
            hinges,
            index,
            free,
            pattern,
            terms,
            diagonal,
            symbolic,
            counted,
        })
    }

    /// Energy per unit area of the relaxed unit bends across the warp and across the
    /// weft, with hinge stiffnesses `k`.
    fn energies(&self, k: &[f64]) -> Option<[f64; 2]> {
        use faer::prelude::*;
        use faer::sparse::linalg::solvers::Llt;
        use faer::sparse::SparseColMatRef;

        let (hinges, index, free) = (self.hinges, self.index, self.free);
        let mut b = Mat::<f64>::zeros(free, 3);
        let mut d = nalgebra::Matrix3::<f64>::zeros();
        for (h, &kh) in hinges.iter().zip(k) {
            d += kh * h.modes * h.modes.transpose();
            for a in 0..4 {
                let ia = index[h.ids[a]];
                if ia == usize::MAX {
                    continue;
                }
                for q in 0..3 {
                    b[(ia, q)] += kh * h.dz[a] * h.modes[q];
                }
            }
        }
        // Each term added in the hinges' order, the same for every run.
        let mut values = vec![0.0; self.pattern.row_idx().len()];
        for &(slot, hinge, a, c) in &self.terms {
            values[slot] += k[hinge] * hinges[hinge].dz[a] * hinges[hinge].dz[c];
        }
        // A free particle that no term reaches would leave the matrix singular.
        let diag_max = self.diagonal.iter().map(|&s| values[s]).fold(0.0, f64::max);
        for &s in &self.diagonal {
            values[s] += 1e-12 * diag_max;
        }
        let h = SparseColMatRef::new(self.pattern.as_ref(), &values);
        let factor = Llt::try_new_with_symbolic(self.symbolic.clone(), h, faer::Side::Lower).ok()?;
        let x = factor.solve(&b);
        // Schur complement of the three modes once the fluctuation has relaxed.
        let mut schur = d;
        for i in 0..free {
            for p in 0..3 {
                for q in 0..3 {
                    schur[(p, q)] -= b[(i, p)] * x[(i, q)];
                }
            }
        }
        let mut out = [0.0; 2];
        let mut response = vec![0.0; hinges.len()];
        for (imposed, sideways) in [(0usize, 1usize), (1, 0)] {
            // Free amplitudes of the sideways curvature and the twist.
            let f = [sideways, 2];
            let sff = nalgebra::Matrix2::new(
                schur[(f[0], f[0])],
                schur[(f[0], f[1])],
                schur[(f[1], f[0])],
                schur[(f[1], f[1])],
            );
            let sfi = nalgebra::Vector2::new(schur[(f[0], imposed)], schur[(f[1], imposed)]);
            let alpha = -sff.lu().solve(&sfi)?;
            let mut amp = nalgebra::Vector3::<f64>::zeros();
            amp[imposed] = 1.0;
            amp[f[0]] = alpha[0];
            amp[f[1]] = alpha[1];
            // The fluctuation w = -H^-1 sum_q amp_q b_q.
            let wz = |i: usize| -> f64 {
                let r = index[i];
                if r == usize::MAX {
                    0.0
                } else {
                    -(0..3).map(|q| amp[q] * x[(r, q)]).sum::<f64>()
                }
            };
            for ((h, &kh), e) in hinges.iter().zip(k).zip(&mut response) {
                let theta = h.modes.dot(&amp) + (0..4).map(|c| h.dz[c] * wz(h.ids[c])).sum::<f64>();
                *e = 0.5 * kh * theta * theta;
            }
            let (mut energy, mut covered) = (0.0, 0.0);
            for (area, ids) in &self.counted {
                covered += area;
                energy += 0.5 * ids.iter().map(|&k| response[k]).sum::<f64>();
            }
            if !(covered > 0.0 && energy > 0.0) {
                return None;
            }
            out[imposed] = energy / covered;
        }
        Some(out)
    }
}

/// Edge-graph distance of every vertex from the boundary; `None` for a closed mesh.
fn rings_from_boundary(mesh: &ClothMesh) -> Option<Vec<usize>> {
    let n = mesh.vertex_count();
    let interior: std::collections::HashSet<[usize; 2]> = mesh.hinges().iter().map(|h| h.edge).collect();
    let mut neighbours = vec![Vec::new(); n];
    let mut ring = vec![usize::MAX; n];
    let mut queue = std::collections::VecDeque::new();
    for e in mesh.edges() {
        neighbours[e[0]].push(e[1]);
        neighbours[e[1]].push(e[0]);
        if !interior.contains(e) {
            for &v in e {
                if ring[v] != 0 {
                    ring[v] = 0;
                    queue.push_back(v);
                }
            }
        }
    }
    if queue.is_empty() {
        return None;
    }
    while let Some(v) = queue.pop_front() {
        for &u in &neighbours[v] {
            if ring[u] == usize::MAX {
                ring[u] = ring[v] + 1;
                queue.push_back(u);
            }
        }
    }
    Some(ring)
}

/// Stiffness of every hinge of `mesh`: `B(fold) |e|^2 / (A1 + A2)`, with the warp and
/// weft rigidities scaled by the [`calibration`] factors.
pub fn hinge_stiffnesses(mesh: &ClothMesh, rigidity: &BendingRigidity, kappa: [f64; 2]) -> Vec<f64> {
    let scaled = calibrated(rigidity, kappa);
    hinge_stiffnesses_by_wing(mesh, |_| &scaled)
}

/// The rigidity scaled by the [`calibration`] factors.
pub fn calibrated(rigidity: &BendingRigidity, kappa: [f64; 2]) -> BendingRigidity {
    BendingRigidity {
        warp: kappa[0] * rigidity.warp,
        weft: kappa[1] * rigidity.weft,
        bias: rigidity.bias.map(|b| 0.5 * (kappa[0] + kappa[1]) * b),
    }
}

/// As [`hinge_stiffnesses`], with each triangle's own (calibrated) rigidity: where two
/// fabrics are sewn together, or across any seam, each wing folds at its own angle to its
/// own grain, and the hinge takes the mean of the two.
pub fn hinge_stiffnesses_by_wing<'a>(
    mesh: &ClothMesh,
    rigidity_of_triangle: impl Fn(usize) -> &'a BendingRigidity,
) -> Vec<f64> {
    mesh.hinges()
        .iter()
        .map(|h| {
            let (ratio, dirs) = hinge_rest(mesh, h);
            let rigidity: f64 = (0..2)
                .map(|w| rigidity_of_triangle(h.triangles[w]).along_fold(dirs[w].x, dirs[w].y))
                .sum::<f64>()
                / 2.0;
            rigidity * ratio
        })
        .collect()
}
