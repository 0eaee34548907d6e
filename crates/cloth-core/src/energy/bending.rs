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
//! continuum rigidity B (N*m) as `k = kappa * B(fold direction) * |e|^2 / (A1 + A2)`
//! with rest quantities, which makes it independent of the mesh resolution; the mesh
//! constant `kappa` is calibrated on the rest mesh (see [`calibration`]) so that a
//! sheet bent to curvature K stores `B K^2 / 2` per unit area, averaged over the
//! directions of bending.

use super::{HessianMode, Local};
use crate::fabric::{BendingLaw, BendingRigidity};
use crate::mesh::ClothMesh;
use crate::{Mat3, Vec3};

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
        return Some(Dihedral { psi, grad, hess: None });
    }
    let id = Mat3::identity();
    let z = Mat3::zeros();
    // Second derivatives of x and y over (a, b, c), block [k][l] = d2/(dk dl).
    let hx_ab = c * a.transpose() + ac * id - 2.0 * a * c.transpose();
    let hx_ac = b * a.transpose() + ab * id - 2.0 * a * b.transpose();
    let hx_bc = a * a.transpose() - aa * id;
    let hx = [
        [c * b.transpose() + b * c.transpose() - 2.0 * bc * id, hx_ab, hx_ac],
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
    Some(Dihedral { psi, grad, hess: Some(hess) })
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

/// Rest geometry of a hinge in material space: `|e|^2 / (A1 + A2)` and the fold direction.
fn hinge_rest(mesh: &ClothMesh, edge: [usize; 2], opposite: [usize; 2]) -> (f64, f64, f64) {
    let uv = mesh.uv();
    let e = uv[edge[1]] - uv[edge[0]];
    let tri_area = |o: usize| {
        let f = uv[o] - uv[edge[0]];
        0.5 * (e.x * f.y - e.y * f.x).abs()
    };
    let len2 = e.norm_squared();
    let ratio = len2 / (tri_area(opposite[0]) + tri_area(opposite[1]));
    let len = len2.sqrt();
    (ratio, e.x / len, e.y / len)
}

/// The mesh constant `kappa`. The flat rest mesh is lifted along z by `z = K s^2 / 2`
/// (a cylinder of curvature K across the warp, then across the weft) and the hinges'
/// linearised energy is matched to the continuum `B K^2 / 2` per unit area. Each hinge's
/// energy is shared between its two triangles and only triangles whose three edges are
/// all hinges are counted, so the boundary does not make the constant drift with the
/// resolution (it is exactly 1 on grids of any size).
///
/// Warp and weft are the directions fabrics are measured in (KES-F, cantilever), so they
/// are matched exactly. A hinge mesh cannot be isotropic on a grid (three hinge
/// directions per cell cannot carry twist independently): bending along the bias is
/// stiffer, 1.5x on a grid with alternating diagonals and 3x along one diagonal with
/// uniform ones. On unstructured, near-equilateral meshes the error is spread evenly
/// over all directions.
pub fn calibration(mesh: &ClothMesh) -> f64 {
    let uv = mesh.uv();
    let mut response = std::collections::HashMap::with_capacity(mesh.hinges().len());
    for h in mesh.hinges() {
        let ids = [h.edge[0], h.edge[1], h.opposite[0], h.opposite[1]];
        let o = uv[ids[0]];
        let local: [nalgebra::Vector2<f64>; 4] = ids.map(|i| uv[i] - o);
        let flat: [Vec3; 4] = local.map(|p| Vec3::new(p.x, p.y, 0.0));
        let Some(d) = dihedral(&flat, false) else { continue };
        // psi is linear in the lift: psi = sum_i dpsi/dz_i K u_i^2 / 2 across the warp.
        let (mut g_warp, mut g_weft) = (0.0, 0.0);
        for (p, g) in local.iter().zip(d.grad.iter()) {
            g_warp += 0.5 * g.z * p.x * p.x;
            g_weft += 0.5 * g.z * p.y * p.y;
        }
        let (ratio, _, _) = hinge_rest(mesh, h.edge, h.opposite);
        // Energy at unit stiffness ratio-scaled, averaged over the two bends.
        response.insert(h.edge, 0.5 * ratio * 0.5 * (g_warp * g_warp + g_weft * g_weft));
    }
    let (mut discrete, mut covered) = (0.0, 0.0);
    for (t, tri) in mesh.triangles().iter().enumerate() {
        let shares: Option<Vec<f64>> = (0..3)
            .map(|k| {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                response.get(&if a < b { [a, b] } else { [b, a] }).copied()
            })
            .collect();
        if let Some(shares) = shares {
            covered += mesh.rest_area(t);
            discrete += 0.5 * shares.iter().sum::<f64>();
        }
    }
    if discrete > 0.0 {
        0.5 * covered / discrete
    } else {
        1.0
    }
}

/// Stiffness of every hinge of `mesh` for the given rigidity: `kappa B |e|^2 / (A1 + A2)`.
pub fn hinge_stiffnesses(mesh: &ClothMesh, rigidity: &BendingRigidity, kappa: f64) -> Vec<f64> {
    mesh.hinges()
        .iter()
        .map(|h| {
            let (ratio, tu, tv) = hinge_rest(mesh, h.edge, h.opposite);
            kappa * rigidity.along_fold(tu, tv) * ratio
        })
        .collect()
}
