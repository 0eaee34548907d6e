//! Force and stiffness assembly.
//!
//! Elements are graph-coloured so that no two elements of one colour share a vertex;
//! each colour is evaluated in parallel and every element adds its forces and blocks
//! straight into the global arrays. Within a colour the writes are disjoint, and the
//! colours run in a fixed order, so the sums are the same for any thread count.

use crate::energy::{
    bending, damping::add_damping, particle, shear::add_shear, stretch::add_stretch,
    stretch::ThreadLaw, HessianMode, Local, TriangleRest,
};
use crate::fabric::Fabric;
use crate::linalg::BlockSparse;
use crate::mesh::ClothMesh;
use crate::{Mat3, Vec3};
use rayon::prelude::*;
use std::ops::Range;

/// Elements per parallel task.
const ELEMENTS_PER_TASK: usize = 256;

#[derive(Debug, Clone)]
struct TriElement {
    v: [u32; 3],
    rest: TriangleRest,
    slots: [u32; 9],
}

#[derive(Debug, Clone)]
struct HingeElement {
    v: [u32; 4],
    stiffness: f64,
    slots: [u32; 16],
}

/// A raw view for disjoint parallel writes (see the module comment for why they are disjoint).
#[derive(Clone, Copy)]
struct Shared<T>(*mut T);
unsafe impl<T> Send for Shared<T> {}
unsafe impl<T> Sync for Shared<T> {}
impl<T> Shared<T> {
    /// # Safety
    /// No other thread may access index `i` at the same time.
    #[inline]
    unsafe fn at(&self, i: usize) -> &mut T {
        unsafe { &mut *self.0.add(i) }
    }
}

/// Where the stiffness goes: `matrix += scale * K`.
pub(crate) struct StiffnessTarget<'a> {
    pub matrix: &'a mut BlockSparse,
    pub scale: f64,
}

/// The cloth's internal and external forces over a fixed mesh.
#[derive(Debug, Clone)]
pub(crate) struct ForceModel {
    fabric: Fabric,
    tris: Vec<TriElement>,
    tri_colors: Vec<Range<usize>>,
    hinges: Vec<HingeElement>,
    hinge_colors: Vec<Range<usize>>,
    masses: Vec<f64>,
    vertex_area: Vec<f64>,
    tri_energy: Vec<f64>,
    hinge_energy: Vec<f64>,
    bending_calibration: f64,
}

impl ForceModel {
    /// Builds the elements and the matrix pattern they fill.
    pub fn new(mesh: &ClothMesh, fabric: Fabric) -> (Self, BlockSparse) {
        let n = mesh.vertex_count();
        let mut pairs = Vec::new();
        for t in mesh.triangles() {
            pairs.extend([(t[0], t[1]), (t[1], t[2]), (t[0], t[2])]);
        }
        for h in mesh.hinges() {
            pairs.push((h.opposite[0], h.opposite[1]));
        }
        let matrix = BlockSparse::from_pairs(n, pairs);
        let slots = |v: &[usize]| -> Vec<u32> {
            let mut s = Vec::with_capacity(v.len() * v.len());
            for &r in v {
                for &c in v {
                    s.push(matrix.slot(r, c).expect("element pairs are in the pattern") as u32);
                }
            }
            s
        };

        let uv = mesh.uv();
        let tris: Vec<TriElement> = mesh
            .triangles()
            .iter()
            .map(|t| TriElement {
                v: t.map(|i| i as u32),
                rest: TriangleRest::new(t.map(|i| uv[i])).expect("validated mesh has no degenerate triangle"),
                slots: slots(t).try_into().expect("9 slots"),
            })
            .collect();
        let kappa = bending::calibration(mesh);
        let stiffness = bending::hinge_stiffnesses(mesh, &fabric.bending, kappa);
        let hinges: Vec<HingeElement> = mesh
            .hinges()
            .iter()
            .zip(&stiffness)
            .map(|(h, &k)| {
                let v = [h.edge[0], h.edge[1], h.opposite[0], h.opposite[1]];
                HingeElement {
                    v: v.map(|i| i as u32),
                    stiffness: k,
                    slots: slots(&v).try_into().expect("16 slots"),
                }
            })
            .collect();
        let (tris, tri_colors) = color(tris, n, |e| &e.v);
        let (hinges, hinge_colors) = color(hinges, n, |e| &e.v);

        let mut vertex_area = vec![0.0; n];
        for e in &tris {
            for &i in &e.v {
                vertex_area[i as usize] += e.rest.area / 3.0;
            }
        }
        let masses = vertex_area.iter().map(|a| a * fabric.area_density).collect();
        let model = Self {
            tri_energy: vec![0.0; tris.len()],
            hinge_energy: vec![0.0; hinges.len()],
            fabric,
            tris,
            tri_colors,
            hinges,
            hinge_colors,
            masses,
            vertex_area,
            bending_calibration: kappa,
        };
        (model, matrix)
    }

    pub fn fabric(&self) -> &Fabric {
        &self.fabric
    }
    pub fn masses(&self) -> &[f64] {
        &self.masses
    }
    pub fn bending_calibration(&self) -> f64 {
        self.bending_calibration
    }
    /// The drag Jacobian's scalar `c A_i` of particle `i` (`dF/dv = -c A_i I`).
    pub fn drag_coefficient(&self, i: usize) -> f64 {
        self.fabric.drag * self.vertex_area[i]
    }

    /// Forces at `(x, v)` into `force` (elastic, damping, gravity, drag), `K v` into `hv`
    /// when damping or a stiffness target needs it, and `scale K` into the target's matrix.
    /// Returns the potential energy (elastic + gravitational).
    #[allow(clippy::too_many_arguments)]
    pub fn evaluate(
        &mut self,
        x: &[Vec3],
        v: &[Vec3],
        gravity: &Vec3,
        wind: &Vec3,
        force: &mut [Vec3],
        hv: &mut [Vec3],
        mut stiffness: Option<StiffnessTarget<'_>>,
        parallel: bool,
    ) -> f64 {
        let beta = self.fabric.damping;
        let need_k = stiffness.is_some() || beta > 0.0;
        let mode = if need_k { HessianMode::Projected } else { HessianMode::None };
        let (masses, area, drag) = (&self.masses, &self.vertex_area, self.fabric.drag);
        let init = |(i, (f, h)): (usize, (&mut Vec3, &mut Vec3))| {
            *f = masses[i] * gravity;
            if drag > 0.0 {
                *f += particle::drag(drag, area[i], &v[i], wind).0;
            }
            *h = Vec3::zeros();
        };
        if parallel {
            force.par_iter_mut().zip(hv.par_iter_mut()).enumerate().for_each(init);
        } else {
            force.iter_mut().zip(hv.iter_mut()).enumerate().for_each(init);
        }

        let fshare = Shared(force.as_mut_ptr());
        let hshare = Shared(hv.as_mut_ptr());
        let scale = stiffness.as_ref().map_or(0.0, |s| s.scale);
        let mshare = stiffness.as_mut().map(|s| Shared(s.matrix.blocks_mut().as_mut_ptr()));
        let fabric = &self.fabric;
        let warp = ThreadLaw { tension: &fabric.warp, compression: fabric.compression_warp };
        let weft = ThreadLaw { tension: &fabric.weft, compression: fabric.compression_weft };

        let tri_kernel = |e: &TriElement, energy: &mut f64| {
            let xe = e.v.map(|i| x[i as usize]);
            let mut local = Local::<3>::default();
            add_stretch(&e.rest, warp, weft, &xe, mode, &mut local);
            add_shear(&e.rest, fabric.shear_modulus, &xe, mode, &mut local);
            *energy = local.energy;
            // SAFETY: elements of one colour share no vertex, so no two threads write
            // the same particle or the same matrix row.
            unsafe { scatter(&local, &e.v, &e.slots, v, beta, need_k, fshare, hshare, mshare, scale) };
        };
        let law = fabric.bending_law;
        let hinge_kernel = |e: &HingeElement, energy: &mut f64| {
            let xe = e.v.map(|i| x[i as usize]);
            let mut local = Local::<4>::default();
            bending::add_bending(law, e.stiffness, &xe, mode, &mut local);
            *energy = local.energy;
            // SAFETY: as above.
            unsafe { scatter(&local, &e.v, &e.slots, v, beta, need_k, fshare, hshare, mshare, scale) };
        };
        run_colored(&self.tris, &self.tri_colors, &mut self.tri_energy, parallel, tri_kernel);
        run_colored(&self.hinges, &self.hinge_colors, &mut self.hinge_energy, parallel, hinge_kernel);

        let gravity_energy: f64 =
            x.iter().zip(masses).map(|(xi, &m)| particle::gravity_energy(m, gravity, xi)).sum();
        self.tri_energy.iter().sum::<f64>() + self.hinge_energy.iter().sum::<f64>() + gravity_energy
    }
}

/// Adds one element's force (with damping), `K v` and `scale K` to the global arrays.
///
/// # Safety
/// No other thread may touch the element's particles or matrix rows meanwhile.
#[allow(clippy::too_many_arguments)]
#[inline]
unsafe fn scatter<const N: usize>(
    local: &Local<N>,
    verts: &[u32; N],
    slots: &[u32],
    v: &[Vec3],
    beta: f64,
    need_k: bool,
    force: Shared<Vec3>,
    hv: Shared<Vec3>,
    matrix: Option<Shared<Mat3>>,
    scale: f64,
) {
    let mut f: [Vec3; N] = local.grad.map(|g| -g);
    let mut kv = [Vec3::zeros(); N];
    if need_k {
        let ve = verts.map(|i| v[i as usize]);
        add_damping(beta, local, &ve, &mut f, &mut kv);
    }
    for k in 0..N {
        let i = verts[k] as usize;
        unsafe {
            *force.at(i) += f[k];
            *hv.at(i) += kv[k];
        }
    }
    if let Some(m) = matrix {
        for r in 0..N {
            for c in 0..N {
                unsafe { *m.at(slots[r * N + c] as usize) += scale * local.hess[r][c] };
            }
        }
    }
}

fn run_colored<E: Sync>(
    elements: &[E],
    colors: &[Range<usize>],
    energy: &mut [f64],
    parallel: bool,
    kernel: impl Fn(&E, &mut f64) + Sync,
) {
    for range in colors {
        let (els, en) = (&elements[range.clone()], &mut energy[range.clone()]);
        if parallel {
            els.par_chunks(ELEMENTS_PER_TASK)
                .zip(en.par_chunks_mut(ELEMENTS_PER_TASK))
                .for_each(|(es, ens)| es.iter().zip(ens).for_each(|(e, en)| kernel(e, en)));
        } else {
            els.iter().zip(en.iter_mut()).for_each(|(e, en)| kernel(e, en));
        }
    }
}

/// Greedy colouring by shared vertices; returns the elements grouped by colour.
fn color<E, const N: usize>(
    elements: Vec<E>,
    n_vertices: usize,
    verts: impl Fn(&E) -> &[u32; N],
) -> (Vec<E>, Vec<Range<usize>>) {
    let mut used: Vec<Vec<u16>> = vec![Vec::new(); n_vertices];
    let mut colors = Vec::with_capacity(elements.len());
    let mut count = 0usize;
    for e in &elements {
        let vs = verts(e);
        let c = (0u16..)
            .find(|c| vs.iter().all(|&i| !used[i as usize].contains(c)))
            .expect("a free colour exists");
        for &i in vs {
            used[i as usize].push(c);
        }
        colors.push(c);
        count = count.max(c as usize + 1);
    }
    let mut buckets: Vec<Vec<E>> = (0..count).map(|_| Vec::new()).collect();
    for (e, c) in elements.into_iter().zip(colors) {
        buckets[c as usize].push(e);
    }
    let mut ranges = Vec::with_capacity(count);
    let mut out = Vec::new();
    for b in buckets {
        let start = out.len();
        out.extend(b);
        ranges.push(start..out.len());
    }
    (out, ranges)
}
