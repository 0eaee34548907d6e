//! Force and stiffness assembly.
//!
//! Elements are graph-coloured so that no two elements of one colour share a vertex;
//! each colour is evaluated in parallel and every element adds its forces and blocks
//! straight into the global arrays. Within a colour the writes are disjoint, and the
//! colours run in a fixed order, so the sums are the same for any thread count.

use crate::energy::{
    attachment::{add_attachment, holds, Attachment},
    bending,
    damping::add_damping,
    particle,
    shear::add_shear,
    stretch::add_stretch,
    stretch::ThreadLaw,
    HessianMode, Local, TriangleRest,
};
use crate::fabric::{BendingLaw, Fabric};
use crate::forces::ForceOutputs;
use crate::linalg::BlockSparse;
use crate::math::{Mat3, Vec3};
use crate::mesh::ClothMesh;
use crate::parallelism::Parallelism;
use rayon::prelude::*;
use std::ops::Range;

/// Elements per parallel task.
const ELEMENTS_PER_TASK: usize = 256;

#[derive(Debug, Clone)]
struct TriElement {
    v: [u32; 3],
    /// Index of its fabric.
    fabric: u32,
    rest: TriangleRest,
    slots: [u32; 9],
}

#[derive(Debug, Clone)]
struct HingeElement {
    v: [u32; 4],
    stiffness: f64,
    /// The first wing's fabric's law, and the mean of the wings' Rayleigh damping.
    law: BendingLaw,
    damping: f64,
    slots: [u32; 16],
}

/// Two particles a seam pulls together while it is sewn, with the share of the pull they
/// take.
#[derive(Debug, Clone)]
struct SeamElement {
    v: [u32; 2],
    /// The pair's place in the seams given to [`ForceModel::new`] (the elements are
    /// reordered by colour).
    pair: u32,
    weight: f64,
    slots: [u32; 4],
}

/// A particle held on one side of a plane (see [`Attachment`]).
#[derive(Debug, Clone)]
struct AttachmentElement {
    v: [u32; 1],
    attachment: Attachment,
    slots: [u32; 1],
}

/// How hard the seams pull: a zero-length spring of `stiffness` (N/m) per pair up to a
/// gap of `reach` (m), and a constant pull of `stiffness * reach` beyond, so a wide gap
/// is closed by a bounded force instead of one that tears the panels; and a dashpot of
/// `damping` (N s/m) per pair on the pair's relative velocity, so a pair closes at most
/// at about `stiffness * reach / damping` however far apart it starts. Each pair takes
/// these times its weight (see [`crate::SimulationBuilder::seam_weights`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SeamPull {
    pub stiffness: f64,
    pub reach: f64,
    pub damping: f64,
}

/// A raw view for disjoint parallel writes (see the module comment for why they are disjoint).
#[derive(Clone, Copy)]
struct Shared<T>(*mut T);
unsafe impl<T> Send for Shared<T> {}
unsafe impl<T> Sync for Shared<T> {}
impl<T: std::ops::AddAssign> Shared<T> {
    /// `target[i] += value`.
    ///
    /// # Safety
    /// `i` is in bounds and no other thread accesses index `i` at the same time.
    #[inline]
    unsafe fn add(&self, i: usize, value: T) {
        unsafe { *self.0.add(i) += value }
    }
}

/// What the cloth hangs in: gravity, m/s^2, and the wind its drag acts against, m/s.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Loads {
    pub gravity: Vec3,
    pub wind: Vec3,
}

/// The cloth's internal and external forces over a fixed mesh.
#[derive(Debug, Clone)]
pub(crate) struct ForceModel {
    /// The fabrics, each triangle naming one (a garment's panels may differ).
    fabrics: Vec<Fabric>,
    /// The largest of the fabrics' Rayleigh damping: whether `K v` is needed without a
    /// stiffness target, and the seam pull's own damping.
    max_damping: f64,
    tris: Vec<TriElement>,
    tri_colors: Vec<Range<usize>>,
    hinges: Vec<HingeElement>,
    hinge_colors: Vec<Range<usize>>,
    seams: Vec<SeamElement>,
    seam_colors: Vec<Range<usize>>,
    seam_energy: Vec<f64>,
    seam_pull: SeamPull,
    attachments: Vec<AttachmentElement>,
    attachment_colors: Vec<Range<usize>>,
    attachment_energy: Vec<f64>,
    /// Stiffness of the penalties holding the cloth (attachments, sharp features), N/m.
    penalty_stiffness: f64,
    masses: Vec<f64>,
    /// Each particle's share of `drag * area`, kg/s.
    vertex_drag: Vec<f64>,
    tri_energy: Vec<f64>,
    hinge_energy: Vec<f64>,
    bending_calibration: Vec<[f64; 2]>,
}

/// What the cloth is made of: triangle `t` is of `fabrics[triangle_fabric[t]]` (as the
/// builder checked); `calibration` gives each fabric's bending calibration instead of
/// computing it.
pub(crate) struct Materials<'a> {
    pub fabrics: Vec<Fabric>,
    pub triangle_fabric: &'a [usize],
    pub calibration: Option<Vec<[f64; 2]>>,
}

/// The particle pairs that seam forces may pull together (see [`SeamPull`]), each with its
/// weight.
#[derive(Clone, Copy)]
pub(crate) struct SeamPairs<'a> {
    pub pairs: &'a [[usize; 2]],
    pub weights: &'a [f64],
}

impl ForceModel {
    /// Builds the elements and the matrix pattern they fill. `attachments` hold particles
    /// on one side of planes; hinges along a clamp of `pinned` particles are stiffened (see
    /// [`bending::clamp_factor`]).
    pub fn new(
        mesh: &ClothMesh,
        materials: Materials<'_>,
        seams: SeamPairs<'_>,
        attachments: &[Attachment],
        pinned: &[bool],
    ) -> (Self, BlockSparse) {
        let Materials {
            fabrics,
            triangle_fabric,
            calibration,
        } = materials;
        let SeamPairs {
            pairs: seams,
            weights: seam_weights,
        } = seams;
        let fabric_of = |t: usize| triangle_fabric[t];
        let n = mesh.vertex_count();
        let mut pairs = Vec::new();
        for t in mesh.triangles() {
            pairs.extend([(t[0], t[1]), (t[1], t[2]), (t[0], t[2])]);
        }
        for h in mesh.hinges() {
            pairs.push((h.opposite[0], h.opposite[1]));
        }
        pairs.extend(seams.iter().map(|&[a, b]| (a, b)));
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

        let tris: Vec<TriElement> = mesh
            .triangles()
            .iter()
            .enumerate()
            .map(|(k, t)| TriElement {
                v: t.map(|i| i as u32),
                fabric: fabric_of(k) as u32,
                rest: TriangleRest::new(mesh.corner_uv(k))
                    .expect("validated mesh has no degenerate triangle"),
                slots: slots(t).try_into().expect("9 slots"),
            })
            .collect();
        let kappa = calibration.unwrap_or_else(|| {
            fabrics
                .iter()
                .map(|f| bending::calibration(mesh, &f.bending))
                .collect()
        });
        let scaled: Vec<_> = fabrics
            .iter()
            .zip(&kappa)
            .map(|(f, &k)| bending::calibrated(&f.bending, k))
            .collect();
        let stiffness = bending::hinge_stiffnesses_by_wing(mesh, |t| &scaled[fabric_of(t)]);
        let hinges: Vec<HingeElement> = mesh
            .hinges()
            .iter()
            .zip(&stiffness)
            .map(|(h, &k)| {
                let v = [h.edge[0], h.edge[1], h.opposite[0], h.opposite[1]];
                let [a, b] = h.triangles.map(|t| &fabrics[fabric_of(t)]);
                let wing_areas = h.triangles.map(|t| mesh.rest_area(t));
                HingeElement {
                    v: v.map(|i| i as u32),
                    stiffness: k * bending::clamp_factor(v, wing_areas, pinned),
                    law: a.bending_law,
                    damping: 0.5 * (a.damping + b.damping),
                    slots: slots(&v).try_into().expect("16 slots"),
                }
            })
            .collect();
        let seams: Vec<SeamElement> = seams
            .iter()
            .zip(seam_weights)
            .enumerate()
            .map(|(pair, (v, &weight))| SeamElement {
                v: v.map(|i| i as u32),
                pair: pair as u32,
                weight,
                slots: slots(v).try_into().expect("4 slots"),
            })
            .collect();
        let (tris, tri_colors) = color(tris, n, |e| &e.v);
        let (hinges, hinge_colors) = color(hinges, n, |e| &e.v);
        let (seams, seam_colors) = color(seams, n, |e| &e.v);
        let (attachments, attachment_colors) = attachment_elements(attachments, &matrix);

        let (mut masses, mut vertex_drag) = (vec![0.0; n], vec![0.0; n]);
        for e in &tris {
            let f = &fabrics[e.fabric as usize];
            for &i in &e.v {
                masses[i as usize] += f.area_density * e.rest.area / 3.0;
                vertex_drag[i as usize] += f.drag * e.rest.area / 3.0;
            }
        }
        // As stiff as ten cells of the stiffest fabric: a waist holding up a skirt, or cloth
        // pressed on a body's edge, gives a small fraction of a cell.
        let penalty_stiffness = 10.0 * fabrics.iter().map(Fabric::membrane_stiffness).fold(0.0, f64::max);
        let model = Self {
            tri_energy: vec![0.0; tris.len()],
            hinge_energy: vec![0.0; hinges.len()],
            max_damping: fabrics.iter().map(|f| f.damping).fold(0.0, f64::max),
            fabrics,
            tris,
            tri_colors,
            hinges,
            hinge_colors,
            seam_energy: vec![0.0; seams.len()],
            seams,
            seam_colors,
            seam_pull: SeamPull::default(),
            attachment_energy: vec![0.0; attachments.len()],
            attachments,
            attachment_colors,
            penalty_stiffness,
            masses,
            vertex_drag,
            bending_calibration: kappa,
        };
        (model, matrix)
    }

    pub fn fabrics(&self) -> &[Fabric] {
        &self.fabrics
    }
    /// The fabric of each particle: that of the first triangle using it.
    pub fn particle_fabrics(&self) -> Vec<usize> {
        let mut of = vec![usize::MAX; self.masses.len()];
        for e in &self.tris {
            for &i in &e.v {
                if of[i as usize] == usize::MAX {
                    of[i as usize] = e.fabric as usize;
                }
            }
        }
        of
    }

    /// Holds the cloth by `attachments` in place of those it had (their particles are in
    /// `matrix`, the model's pattern, which has every diagonal block).
    pub fn set_attachments(&mut self, attachments: &[Attachment], matrix: &BlockSparse) {
        let (elements, colors) = attachment_elements(attachments, matrix);
        self.attachment_energy = vec![0.0; elements.len()];
        self.attachments = elements;
        self.attachment_colors = colors;
    }
    /// Sets how hard the seams pull (zero: not at all).
    pub fn set_seam_pull(&mut self, pull: SeamPull) {
        self.seam_pull = pull;
    }
    pub fn seam_pull(&self) -> SeamPull {
        self.seam_pull
    }
    /// Weighs each seam pair's pull by `weights`, in the order the seams were given (as
    /// the builder checked: one finite weight >= 0 per pair).
    pub fn set_seam_weights(&mut self, weights: &[f64]) {
        for e in &mut self.seams {
            e.weight = weights[e.pair as usize];
        }
    }
    /// Stiffness of the penalties holding the cloth (attachments, a body's sharp
    /// features), N/m: ten times the stiffest fabric's membrane.
    pub fn penalty_stiffness(&self) -> f64 {
        self.penalty_stiffness
    }
    pub fn masses(&self) -> &[f64] {
        &self.masses
    }
    /// `sqrt(3 sum m_i^2)`: the norm of the mass matrix's diagonal.
    pub fn mass_norm(&self) -> f64 {
        (3.0 * self.masses.iter().map(|m| m * m).sum::<f64>()).sqrt()
    }
    /// Each fabric's bending calibration factors.
    pub fn bending_calibration(&self) -> &[[f64; 2]] {
        &self.bending_calibration
    }
    /// The drag Jacobian's scalar `c A_i` of particle `i` (`dF/dv = -c A_i I`).
    pub fn drag_coefficient(&self, i: usize) -> f64 {
        self.vertex_drag[i]
    }

    /// Forces at `(x, v)` under `loads` into `out.force` (elastic, damping, gravity, drag),
    /// `K v` into `out.hv` when damping or a stiffness target needs it, and
    /// `(h^2 + h beta) K` into the target's matrix.
    /// Returns the potential energy (elastic + gravitational).
    pub fn evaluate(
        &mut self,
        x: &[Vec3],
        v: &[Vec3],
        loads: &Loads,
        out: ForceOutputs<'_, '_>,
        par: Parallelism,
    ) -> f64 {
        let (gravity, wind) = (&loads.gravity, &loads.wind);
        let ForceOutputs {
            force,
            hv,
            mut stiffness,
        } = out;
        let need_k = stiffness.is_some() || self.max_damping > 0.0 || self.seam_pull.damping > 0.0;
        let mode = if need_k {
            HessianMode::Projected
        } else {
            HessianMode::None
        };
        let (masses, drag) = (&self.masses, &self.vertex_drag);
        let init = |(i, (f, h)): (usize, (&mut Vec3, &mut Vec3))| {
            *f = masses[i] * gravity;
            if drag[i] > 0.0 {
                *f += particle::drag(drag[i], 1.0, &v[i], wind).0;
            }
            *h = Vec3::zeros();
        };
        if par.is_rayon() {
            force
                .par_iter_mut()
                .zip(hv.par_iter_mut())
                .enumerate()
                .for_each(init);
        } else {
            force.iter_mut().zip(hv.iter_mut()).enumerate().for_each(init);
        }

        let sink = Sink {
            v,
            need_k,
            force: Shared(force.as_mut_ptr()),
            hv: Shared(hv.as_mut_ptr()),
            matrix: stiffness
                .as_mut()
                .map(|s| Shared(s.matrix.blocks_mut().as_mut_ptr())),
            h: stiffness.as_ref().map_or(0.0, |s| s.h),
        };
        let fabrics = &self.fabrics;

        let tri_kernel = |e: &TriElement, energy: &mut f64| {
            let fabric = &fabrics[e.fabric as usize];
            let [warp, weft] = ThreadLaw::of(fabric);
            let xe = e.v.map(|i| x[i as usize]);
            let mut local = Local::<3>::default();
            add_stretch(&e.rest, warp, weft, &xe, mode, &mut local);
            add_shear(&e.rest, fabric.shear_modulus, &xe, mode, &mut local);
            *energy = local.energy;
            let beta = fabric.damping;
            // SAFETY: elements of one colour share no vertex, so no two threads write
            // the same particle or the same matrix row.
            unsafe { sink.put(&local, &e.v, &e.slots, beta) };
        };
        let hinge_kernel = |e: &HingeElement, energy: &mut f64| {
            let xe = e.v.map(|i| x[i as usize]);
            let mut local = Local::<4>::default();
            bending::add_bending(e.law, e.stiffness, &xe, mode, &mut local);
            *energy = local.energy;
            let beta = e.damping;
            // SAFETY: as above.
            unsafe { sink.put(&local, &e.v, &e.slots, beta) };
        };
        run_colored(
            &self.tris,
            &self.tri_colors,
            &mut self.tri_energy,
            par,
            tri_kernel,
        );
        run_colored(
            &self.hinges,
            &self.hinge_colors,
            &mut self.hinge_energy,
            par,
            hinge_kernel,
        );
        let pull = self.seam_pull;
        if pull.stiffness > 0.0 {
            let beta = self.max_damping;
            let seam_kernel = |e: &SeamElement, energy: &mut f64| {
                let mut local = Local::<2>::default();
                let weighted = SeamPull {
                    stiffness: e.weight * pull.stiffness,
                    reach: pull.reach,
                    damping: e.weight * pull.damping,
                };
                let secant = add_seam_pull(
                    weighted,
                    [x[e.v[0] as usize], x[e.v[1] as usize]],
                    need_k,
                    &mut local,
                );
                *energy = local.energy;
                if secant <= 0.0 {
                    // A pair of weight zero adds nothing.
                    return;
                }
                // The dashpot is the pair's Rayleigh damping: its Hessian is the secant
                // stiffness times the pair's identity blocks, so `beta K` is `damping`
                // times them.
                let beta = beta + weighted.damping / secant;
                // SAFETY: as above.
                unsafe { sink.put(&local, &e.v, &e.slots, beta) };
            };
            run_colored(
                &self.seams,
                &self.seam_colors,
                &mut self.seam_energy,
                par,
                seam_kernel,
            );
        } else {
            self.seam_energy.iter_mut().for_each(|e| *e = 0.0);
        }

        let k = self.penalty_stiffness;
        let attachment_kernel = |e: &AttachmentElement, energy: &mut f64| {
            let i = e.v[0] as usize;
            *energy = 0.0;
            if holds(&e.attachment, &x[i], &v[i], sink.h) {
                let mut local = Local::<1>::default();
                add_attachment(&e.attachment, k, &x[i], need_k, &mut local);
                *energy = local.energy;
                // SAFETY: as above.
                unsafe { sink.put(&local, &e.v, &e.slots, ATTACHMENT_DAMPING) };
            }
        };
        run_colored(
            &self.attachments,
            &self.attachment_colors,
            &mut self.attachment_energy,
            par,
            attachment_kernel,
        );

        let gravity_energy: f64 = x
            .iter()
            .zip(masses)
            .map(|(xi, &m)| particle::gravity_energy(m, gravity, xi))
            .sum();
        self.tri_energy.iter().sum::<f64>()
            + self.hinge_energy.iter().sum::<f64>()
            + self.seam_energy.iter().sum::<f64>()
            + self.attachment_energy.iter().sum::<f64>()
            + gravity_energy
    }
}

/// Rayleigh damping of the attachments, s: GarmentCode's (a damping of 10 against a
/// stiffness of 1,000), which stops a particle's motion along the normal within a step
/// once it is held, instead of letting it bounce off the plane.
const ATTACHMENT_DAMPING: f64 = 0.01;

/// A seam pair's pull: `k d^2 / 2` up to the reach `r`, then `k r (d - r / 2)`, so the
/// force is `k d` and then a constant `k r` along the gap. The Hessian is `k` times the
/// identity inside the reach; beyond it, the secant `k r / d` times the identity. The
/// exact one there, `k r / d (I - n n^T)`, has no stiffness along the gap: the implicit
/// step would then meet a constant force as explicitly as forward Euler and carry the
/// pair far past closing (by about `k r h^2 / m`), where the secant sees it coming.
/// Returns the stiffness the Hessian has, `k` or `k r / d`.
pub(crate) fn add_seam_pull(pull: SeamPull, x: [Vec3; 2], with_hessian: bool, out: &mut Local<2>) -> f64 {
    let SeamPull {
        stiffness: k,
        reach: r,
        ..
    } = pull;
    let gap = x[0] - x[1];
    let d = gap.norm();
    let (energy, grad, hess) = if d <= r {
        (0.5 * k * d * d, k * gap, Mat3::identity() * k)
    } else {
        (
            k * r * (d - 0.5 * r),
            gap * (k * r / d),
            Mat3::identity() * (k * r / d),
        )
    };
    out.energy += energy;
    out.grad[0] += grad;
    out.grad[1] -= grad;
    if with_hessian {
        out.hess[0][0] += hess;
        out.hess[1][1] += hess;
        out.hess[0][1] -= hess;
        out.hess[1][0] -= hess;
    }
    hess[(0, 0)]
}

/// Where elements add their forces, `K v` and stiffness: the global arrays, shared by
/// the threads of one colour.
#[derive(Clone, Copy)]
struct Sink<'a> {
    v: &'a [Vec3],
    need_k: bool,
    force: Shared<Vec3>,
    hv: Shared<Vec3>,
    matrix: Option<Shared<Mat3>>,
    h: f64,
}

impl Sink<'_> {
    /// Adds one element's force (with its Rayleigh damping `beta`), `K v` and
    /// `(h^2 + h beta) K`.
    ///
    /// # Safety
    /// No other thread may touch the element's particles or matrix rows meanwhile.
    #[inline]
    unsafe fn put<const N: usize>(&self, local: &Local<N>, verts: &[u32; N], slots: &[u32], beta: f64) {
        let mut f: [Vec3; N] = local.grad.map(|g| -g);
        let mut kv = [Vec3::zeros(); N];
        if self.need_k {
            let ve = verts.map(|i| self.v[i as usize]);
            add_damping(beta, local, &ve, &mut f, &mut kv);
        }
        for k in 0..N {
            let i = verts[k] as usize;
            unsafe {
                self.force.add(i, f[k]);
                self.hv.add(i, kv[k]);
            }
        }
        if let Some(m) = self.matrix {
            let scale = self.h * self.h + self.h * beta;
            for r in 0..N {
                for c in 0..N {
                    unsafe { m.add(slots[r * N + c] as usize, scale * local.hess[r][c]) };
                }
            }
        }
    }
}

fn run_colored<E: Sync>(
    elements: &[E],
    colors: &[Range<usize>],
    energy: &mut [f64],
    par: Parallelism,
    kernel: impl Fn(&E, &mut f64) + Sync,
) {
    for range in colors {
        let (els, en) = (&elements[range.clone()], &mut energy[range.clone()]);
        if par.is_rayon() {
            els.par_chunks(ELEMENTS_PER_TASK)
                .zip(en.par_chunks_mut(ELEMENTS_PER_TASK))
                .for_each(|(es, ens)| es.iter().zip(ens).for_each(|(e, en)| kernel(e, en)));
        } else {
            els.iter().zip(en.iter_mut()).for_each(|(e, en)| kernel(e, en));
        }
    }
}

/// Greedy colouring by shared vertices; returns the elements grouped by colour.
/// The elements of `attachments`, coloured, their blocks the diagonal ones of `matrix`.
fn attachment_elements(
    attachments: &[Attachment],
    matrix: &BlockSparse,
) -> (Vec<AttachmentElement>, Vec<Range<usize>>) {
    let elements = attachments
        .iter()
        .map(|a| AttachmentElement {
            v: [a.particle as u32],
            attachment: *a,
            slots: [matrix
                .slot(a.particle, a.particle)
                .expect("every diagonal block is in the pattern") as u32],
        })
        .collect();
    color(elements, matrix.n(), |e| &e.v)
}

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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::energy::bending::add_bending;
    use crate::forces::StiffnessTarget;
    use crate::mesh::GridBuilder;
    use crate::Fabric;
    use rand::rngs::StdRng;
    use rand::{Rng, SeedableRng};

    /// A small crumpled sheet: random displacements stretch, compress, shear and fold it.
    fn setup() -> (ClothMesh, ForceModel, BlockSparse, Vec<Vec3>, Vec<Vec3>) {
        let mesh = GridBuilder::new(5, 4).size(0.08, 0.06).build().unwrap();
        let mut fabric = Fabric::isotropic_linear(0.2, 400.0, 15.0, 2e-5)
            .with_damping(0.02)
            .with_drag(0.3);
        fabric.warp = crate::TensileLaw::PowerLaw {
            strain_ref: 0.1,
            tension_ref: 40.0,
            exponent: 2.0,
        };
        // One seam pair within the pull's reach and two beyond it, sharing a particle.
        let (mut model, matrix) = ForceModel::new(
            &mesh,
            Materials {
                fabrics: vec![fabric],
                triangle_fabric: &vec![0; mesh.triangles().len()],
                calibration: None,
            },
            SeamPairs {
                pairs: &SEAMS,
                weights: &WEIGHTS,
            },
            &attachments(&mesh),
            &vec![false; mesh.vertex_count()],
        );
        model.set_seam_pull(SeamPull {
            stiffness: 50.0,
            reach: 0.05,
            damping: 0.0,
        });
        let mut rng = StdRng::seed_from_u64(7);
        let x = mesh
            .positions()
            .iter()
            .map(|p| p + Vec3::from_fn(|_, _| rng.random_range(-0.006..0.006)))
            .collect();
        let v = (0..mesh.vertex_count())
            .map(|_| Vec3::from_fn(|_, _| rng.random_range(-0.5..0.5)))
            .collect();
        (mesh, model, matrix, x, v)
    }

    /// Two attachments holding particle 5 (each plane 2 cm past it, more than the crumpling
    /// moves it) and one leaving particle 7 free.
    fn attachments(mesh: &ClothMesh) -> Vec<Attachment> {
        let x = mesh.positions();
        let at = |particle: usize, direction: Vec3, offset: f64| {
            let direction = direction.normalize();
            Attachment {
                particle,
                point: x[particle] + offset * direction,
                direction,
            }
        };
        vec![
            at(5, Vec3::new(0.2, -0.1, 1.0), 0.02),
            at(5, Vec3::new(1.0, 0.3, 0.0), 0.02),
            at(7, Vec3::z(), -0.02),
        ]
    }

    const SEAMS: [[usize; 2]; 3] = [[0, 1], [0, 19], [3, 12]];
    /// Each pair's share of the pull.
    const WEIGHTS: [f64; 3] = [1.0, 0.5, 2.0];

    /// The pull on pair `k` of [`SEAMS`]: the model's, times the pair's weight.
    fn weighted(pull: SeamPull, k: usize) -> SeamPull {
        SeamPull {
            stiffness: WEIGHTS[k] * pull.stiffness,
            reach: pull.reach,
            damping: WEIGHTS[k] * pull.damping,
        }
    }

    #[test]
    fn seam_pull_derivatives_match_finite_differences() {
        let pull = SeamPull {
            stiffness: 30.0,
            reach: 0.04,
            damping: 0.0,
        };
        // Gaps inside and beyond the reach.
        for (gap, exact) in [
            (Vec3::new(0.01, -0.02, 0.005), true),
            (Vec3::new(0.05, 0.03, -0.02), false),
        ] {
            let x = [Vec3::new(0.1, 0.2, 0.3), Vec3::new(0.1, 0.2, 0.3) - gap];
            let eval = |x: [Vec3; 2]| {
                let mut l = Local::<2>::default();
                add_seam_pull(pull, x, true, &mut l);
                l
            };
            let l = eval(x);
            let h = 1e-6;
            for i in 0..2 {
                for d in 0..3 {
                    let (mut xp, mut xm) = (x, x);
                    xp[i][d] += h;
                    xm[i][d] -= h;
                    let (lp, lm) = (eval(xp), eval(xm));
                    let fd = (lp.energy - lm.energy) / (2.0 * h);
                    assert!(
                        (fd - l.grad[i][d]).abs() < 1e-7,
                        "grad {i}{d}: {fd} vs {}",
                        l.grad[i][d]
                    );
                    for j in 0..2 {
                        let fd_col = (lp.grad[j] - lm.grad[j]) / (2.0 * h);
                        let col = l.hess[j][i].column(d).clone_owned();
                        if exact {
                            assert!(
                                (fd_col - col).norm() < 1e-6,
                                "hess {j}{i} col {d}: {fd_col} vs {col}"
                            );
                        } else {
                            // Beyond the reach: the exact Hessian across the gap, the secant along it.
                            let n = gap.normalize();
                            let across = |c: Vec3| c - n * n.dot(&c);
                            assert!(
                                (across(fd_col) - across(col)).norm() < 1e-6,
                                "hess {j}{i} col {d}"
                            );
                        }
                    }
                }
            }
        }
        // The secant along the gap: H (x0 - x1) is the gradient.
        let x = [Vec3::new(0.05, 0.03, -0.02), Vec3::zeros()];
        let mut l = Local::<2>::default();
        add_seam_pull(pull, x, true, &mut l);
        assert!((l.hess[0][0] * x[0] - l.grad[0]).norm() < 1e-12);
        // The pull beyond the reach is the constant k r.
        let mut l = Local::<2>::default();
        add_seam_pull(pull, [Vec3::new(1.0, 0.0, 0.0), Vec3::zeros()], false, &mut l);
        assert!((l.grad[0].norm() - 30.0 * 0.04).abs() < 1e-12);
    }

    #[test]
    fn assembled_forces_are_minus_the_energy_gradient() {
        let (_, mut model, _, x, _) = setup();
        let n = x.len();
        let (g, wind, still) = (Vec3::new(0.0, 0.0, -9.81), Vec3::zeros(), vec![Vec3::zeros(); n]);
        let (mut f, mut hv) = (vec![Vec3::zeros(); n], vec![Vec3::zeros(); n]);
        model.evaluate(
            &x,
            &still,
            &Loads { gravity: g, wind },
            ForceOutputs {
                force: &mut f,
                hv: &mut hv,
                stiffness: None,
            },
            Parallelism::Sequential,
        );
        let scale = f.iter().map(|f| f.norm()).fold(0.0, f64::max);
        let energy = |model: &mut ForceModel, x: &[Vec3]| {
            let (mut f, mut hv) = (vec![Vec3::zeros(); n], vec![Vec3::zeros(); n]);
            model.evaluate(
                x,
                &still,
                &Loads { gravity: g, wind },
                ForceOutputs {
                    force: &mut f,
                    hv: &mut hv,
                    stiffness: None,
                },
                Parallelism::Sequential,
            )
        };
        let h = 1e-7;
        for i in 0..n {
            for d in 0..3 {
                let (mut xp, mut xm) = (x.clone(), x.clone());
                xp[i][d] += h;
                xm[i][d] -= h;
                let (ep, em) = (energy(&mut model, &xp), energy(&mut model, &xm));
                let fd = -(ep - em) / (2.0 * h);
                assert!(
                    (fd - f[i][d]).abs() <= 1e-5 * scale,
                    "particle {i} axis {d}: {} vs {fd}",
                    f[i][d]
                );
            }
        }
    }

    #[test]
    fn assembled_stiffness_is_the_sum_of_psd_element_blocks() {
        let (mesh, mut model, mut matrix, x, v) = setup();
        let n = x.len();
        let (g, wind) = (Vec3::zeros(), Vec3::zeros());
        let (mut f, mut hv) = (vec![Vec3::zeros(); n], vec![Vec3::zeros(); n]);
        model.evaluate(
            &x,
            &v,
            &Loads { gravity: g, wind },
            ForceOutputs {
                force: &mut f,
                hv: &mut hv,
                stiffness: Some(StiffnessTarget {
                    matrix: &mut matrix,
                    h: 1.0,
                }),
            },
            Parallelism::Rayon,
        );
        // The same sum, element by element, in dense form.
        let mut dense = nalgebra::DMatrix::<f64>::zeros(3 * n, 3 * n);
        let fab = model.fabrics()[0].clone();
        let [warp, weft] = ThreadLaw::of(&fab);
        let mut add = |ids: &[usize], h: &nalgebra::DMatrix<f64>| {
            for (a, &i) in ids.iter().enumerate() {
                for (b, &j) in ids.iter().enumerate() {
                    let block = h.view((3 * a, 3 * b), (3, 3)).clone_owned();
                    let mut target = dense.view_mut((3 * i, 3 * j), (3, 3));
                    target += block;
                }
            }
        };
        for (k, t) in mesh.triangles().iter().enumerate() {
            let rest = TriangleRest::new(mesh.corner_uv(k)).unwrap();
            let mut l = Local::<3>::default();
            add_stretch(
                &rest,
                warp,
                weft,
                &t.map(|i| x[i]),
                HessianMode::Projected,
                &mut l,
            );
            add_shear(
                &rest,
                fab.shear_modulus,
                &t.map(|i| x[i]),
                HessianMode::Projected,
                &mut l,
            );
            let h = l.hessian_dense();
            assert!(
                h.clone().symmetric_eigen().eigenvalues.min() >= -1e-9 * h.amax(),
                "triangle block not PSD"
            );
            add(t, &h);
        }
        let k = bending::hinge_stiffnesses(&mesh, &fab.bending, bending::calibration(&mesh, &fab.bending));
        for (hinge, k) in mesh.hinges().iter().zip(k) {
            let ids = [hinge.edge[0], hinge.edge[1], hinge.opposite[0], hinge.opposite[1]];
            let mut l = Local::<4>::default();
            add_bending(
                fab.bending_law,
                k,
                &ids.map(|i| x[i]),
                HessianMode::Projected,
                &mut l,
            );
            let h = l.hessian_dense();
            assert!(
                h.clone().symmetric_eigen().eigenvalues.min() >= -1e-9 * h.amax().max(1e-300),
                "hinge block not PSD"
            );
            add(&ids, &h);
        }
        for (k, pair) in SEAMS.into_iter().enumerate() {
            let mut l = Local::<2>::default();
            add_seam_pull(weighted(model.seam_pull(), k), pair.map(|i| x[i]), true, &mut l);
            add(&pair, &l.hessian_dense());
        }
        // The attachments' blocks carry their own damping: scaled to the fabric's here, and
        // K v has them unscaled.
        let rescale = (1.0 + ATTACHMENT_DAMPING) / (1.0 + fab.damping);
        let mut kv_attachments = vec![Vec3::zeros(); n];
        for a in attachments(&mesh) {
            if !holds(&a, &x[a.particle], &v[a.particle], 1.0) {
                continue;
            }
            let mut l = Local::<1>::default();
            add_attachment(&a, model.penalty_stiffness, &x[a.particle], true, &mut l);
            add(&[a.particle], &(l.hessian_dense() * rescale));
            kv_attachments[a.particle] += (1.0 - rescale) * l.hess[0][0] * v[a.particle];
        }
        // The target holds (h^2 + h beta) K, here with h = 1.
        let assembled = matrix.to_dense() / (1.0 + fab.damping);
        let scale = dense.amax();
        assert!(
            (&assembled - &dense).amax() <= 1e-12 * scale,
            "assembly differs from the element sum"
        );
        assert!(
            (&assembled - assembled.transpose()).amax() <= 1e-12 * scale,
            "not symmetric"
        );
        assert!(
            assembled.symmetric_eigen().eigenvalues.min() >= -1e-9 * scale,
            "global stiffness not PSD"
        );
        // K v returned alongside matches the matrix.
        let mut kv = vec![Vec3::zeros(); n];
        matrix.mul(&v, &mut kv, Parallelism::Sequential);
        for ((a, b), c) in kv.iter().zip(&hv).zip(&kv_attachments) {
            assert!((a / (1.0 + fab.damping) + c - b).norm() <= 1e-10 * scale);
        }
    }

    #[test]
    fn the_seam_dashpot_resists_each_pairs_relative_velocity() {
        let (_, mut model, mut matrix, x, v) = setup();
        let n = x.len();
        let zero = Vec3::zeros();
        let h = 0.01;
        let mut run = |model: &mut ForceModel| {
            matrix.blocks_mut().iter_mut().for_each(|b| *b = Mat3::zeros());
            let (mut f, mut hv) = (vec![zero; n], vec![zero; n]);
            let target = StiffnessTarget {
                matrix: &mut matrix,
                h,
            };
            model.evaluate(
                &x,
                &v,
                &Loads {
                    gravity: zero,
                    wind: zero,
                },
                ForceOutputs {
                    force: &mut f,
                    hv: &mut hv,
                    stiffness: Some(target),
                },
                Parallelism::Sequential,
            );
            (f, matrix.to_dense())
        };
        let (f0, m0) = run(&mut model);
        let c = 0.4;
        model.set_seam_pull(SeamPull {
            damping: c,
            ..model.seam_pull()
        });
        let (f1, m1) = run(&mut model);
        // Force: -w c (v_a - v_b) on a, the opposite on b, pair by pair (w its weight).
        let mut expected = vec![zero; n];
        let mut blocks = nalgebra::DMatrix::<f64>::zeros(3 * n, 3 * n);
        for (k, [a, b]) in SEAMS.into_iter().enumerate() {
            let c = WEIGHTS[k] * c;
            let df = -c * (v[a] - v[b]);
            expected[a] += df;
            expected[b] -= df;
            for (i, j, sign) in [(a, a, 1.0), (b, b, 1.0), (a, b, -1.0), (b, a, -1.0)] {
                for d in 0..3 {
                    blocks[(3 * i + d, 3 * j + d)] += sign * h * c;
                }
            }
        }
        for i in 0..n {
            assert!((f1[i] - f0[i] - expected[i]).norm() < 1e-12, "particle {i}");
        }
        // Matrix: h c times the pair's identity blocks (the damping part of h^2 + h beta).
        assert!((m1 - m0 - blocks).amax() < 1e-12);
    }

    #[test]
    fn internal_forces_have_no_net_force_or_torque() {
        let (_, mut model, _, x, v) = setup();
        let n = x.len();
        model.vertex_drag.iter_mut().for_each(|d| *d = 0.0); // drag is an external force
        model.attachments.clear(); // as attachments are
        model.attachment_colors.clear();
        let zero = Vec3::zeros();
        // Elastic forces at rest velocity: no net force, no net torque.
        let mut f = vec![zero; n];
        model.evaluate(
            &x,
            &vec![zero; n],
            &Loads {
                gravity: zero,
                wind: zero,
            },
            ForceOutputs {
                force: &mut f,
                hv: &mut vec![zero; n],
                stiffness: None,
            },
            Parallelism::Sequential,
        );
        let scale = f.iter().map(|f| f.norm()).fold(0.0, f64::max);
        let net: Vec3 = f.iter().sum();
        let torque: Vec3 = x.iter().zip(&f).map(|(p, f)| p.cross(f)).sum();
        assert!(net.norm() <= 1e-10 * scale, "net force {net}");
        assert!(torque.norm() <= 1e-10 * scale, "net torque {torque}");
        // With damping: still no net force (K maps translations to zero). Stiffness-
        // proportional damping of a stressed state is not torque-free, so no torque check.
        model.evaluate(
            &x,
            &v,
            &Loads {
                gravity: zero,
                wind: zero,
            },
            ForceOutputs {
                force: &mut f,
                hv: &mut vec![zero; n],
                stiffness: None,
            },
            Parallelism::Sequential,
        );
        let net: Vec3 = f.iter().sum();
        assert!(
            net.norm() <= 1e-10 * f.iter().map(|f| f.norm()).fold(0.0, f64::max),
            "net force {net}"
        );
    }

    #[test]
    fn colours_share_no_vertex() {
        let (mesh, model, ..) = setup();
        for (elements, colors) in [
            (
                model.tris.iter().map(|e| e.v.to_vec()).collect::<Vec<_>>(),
                &model.tri_colors,
            ),
            (
                model.hinges.iter().map(|e| e.v.to_vec()).collect(),
                &model.hinge_colors,
            ),
        ] {
            let total: usize = colors.iter().map(|r| r.len()).sum();
            assert_eq!(total, elements.len());
            for r in colors {
                let mut seen = vec![false; mesh.vertex_count()];
                for e in &elements[r.clone()] {
                    for &v in e {
                        assert!(
                            !std::mem::replace(&mut seen[v as usize], true),
                            "vertex {v} twice in a colour"
                        );
                    }
                }
            }
        }
    }
}
