use cloth_core::energy::{bending, HessianMode, Local};
use cloth_core::*;
fn energy(mesh: &ClothMesh, k: &[f64], x: &[Vec3]) -> f64 {
    let mut e = 0.0;
    for (h, kk) in mesh.hinges().iter().zip(k) {
        let xe = [h.edge[0], h.edge[1], h.opposite[0], h.opposite[1]].map(|i| x[i]);
        let mut l = Local::<4>::default();
        bending::add_bending(BendingLaw::Quadratic, *kk, &xe, HessianMode::None, &mut l);
        e += l.energy;
    }
    e
}
fn main() {
    for diag in [GridDiagonals::Uniform, GridDiagonals::Alternating] {
        for n in [11, 21, 41] {
            let mesh = GridBuilder::new(n, n).size(0.2, 0.2).diagonals(diag).build().unwrap();
            let kappa = bending::calibration(&mesh);
            let b = 1e-5;
            let k = bending::hinge_stiffnesses(&mesh, &BendingRigidity::isotropic(b), kappa);
            let r = 1.0; // radius
            let mut out = vec![];
            for deg in [0.0f64, 22.5, 45.0, 67.5, 90.0, 135.0] {
                let (c, s) = (deg.to_radians().cos(), deg.to_radians().sin());
                let x: Vec<Vec3> = mesh.uv().iter().map(|p| {
                    let a = c * (p.x - 0.1) + s * (p.y - 0.1); // coordinate across the fold
                    let t = -s * (p.x - 0.1) + c * (p.y - 0.1);
                    let th = a / r;
                    Vec3::new(r * th.sin() * c - t * s, r * th.sin() * s + t * c, r * (1.0 - th.cos()))
                }).collect();
                let e = energy(&mesh, &k, &x);
                out.push(e / (0.5 * b / (r * r) * mesh.total_rest_area()));
            }
            println!("{diag:?} n={n} kappa={kappa:.4} ratio by direction 0..90: {:?}", out.iter().map(|v| format!("{v:.3}")).collect::<Vec<_>>());
        }
    }
}
