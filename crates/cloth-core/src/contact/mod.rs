//! Contact of the cloth with rigid bodies, reached through the [`Collider`] trait.

mod collider;
mod step;
mod particle_contacts;
mod feature_contacts;

pub use collider::{Collider, ParticlePath, Proximity, SharpFeature, SurfacePoint};
pub(crate) use particle_contacts::ParticleContacts;
pub use particle_contacts::{ContactMode, PassThrough, SLIP_SPEED};
pub use step::{StepEnd, StepStart};

use crate::forces::ForceOutputs;
use crate::math::Vec3;
use crate::mesh::ClothMesh;
use std::sync::Arc;

/// The cloth's edges through the bodies' triangles, counted edge-triangle pair by pair as
/// the cloth's own intersections are ([`crate::count_self_intersections`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct BodyIntersections {
    /// Those that count: every crossing but the next.
    pub crossings: usize,
    /// Crossings of the bodies' thin parts by cloth that passes them for the whole
    /// simulation (see [`PassThrough::until_out`]): a skirt through the hands of a body
    /// in an A pose.
    pub thin_parts_passed: usize,
}

impl std::iter::Sum for BodyIntersections {
    fn sum<I: Iterator<Item = Self>>(iter: I) -> Self {
        iter.fold(Self::default(), |p, q| Self {
            crossings: p.crossings + q.crossings,
            thin_parts_passed: p.thin_parts_passed + q.thin_parts_passed,
        })
    }
}

/// The edges of `mesh` at positions `x` passing through the triangles of `collider`'s
/// bodies at time `t`; `passes_thin_parts` (empty, or one flag per particle) marks the
/// particles passing the bodies' thin parts for good, whose edges (with either end
/// passing) cross only the thick parts for the count.
pub fn count_body_intersections(
    collider: &dyn Collider,
    t: f64,
    mesh: &ClothMesh,
    x: &[Vec3],
    passes_thin_parts: &[bool],
) -> BodyIntersections {
    use rayon::prelude::*;
    mesh.edges()
        .par_iter()
        .map(|&edge| edge_crossings(collider, t, x, passes_thin_parts, edge))
        .sum()
}

/// As [`count_body_intersections`], edge by edge: each edge of `mesh` (its index in
/// [`ClothMesh::edges`]) with any crossing, and its crossings, in the edges' order.
pub fn body_intersections_by_edge(
    collider: &dyn Collider,
    t: f64,
    mesh: &ClothMesh,
    x: &[Vec3],
    passes_thin_parts: &[bool],
) -> Vec<(usize, BodyIntersections)> {
    use rayon::prelude::*;
    mesh.edges()
        .par_iter()
        .enumerate()
        .map(|(e, &edge)| (e, edge_crossings(collider, t, x, passes_thin_parts, edge)))
        .filter(|(_, found)| found.crossings + found.thin_parts_passed > 0)
        .collect()
}

/// The crossings of the bodies by one edge (see [`count_body_intersections`]).
fn edge_crossings(
    collider: &dyn Collider,
    t: f64,
    x: &[Vec3],
    passes_thin_parts: &[bool],
    [a, b]: [usize; 2],
) -> BodyIntersections {
    let passes = |i: usize| passes_thin_parts.get(i).copied().unwrap_or(false);
    let all = collider.segment_crossings(t, &x[a], &x[b]);
    if all > 0 && (passes(a) || passes(b)) {
        let thick = collider.thick_segment_crossings(t, &x[a], &x[b]);
        BodyIntersections {
            crossings: thick,
            thin_parts_passed: all.saturating_sub(thick),
        }
    } else {
        BodyIntersections {
            crossings: all,
            thin_parts_passed: 0,
        }
    }
}

/// Everything the solver keeps for contacts: the bodies, the per-particle state and the
/// scratch of the end-of-step passes.
#[derive(Debug)]
pub(crate) struct Contacts {
    pub collider: Arc<dyn Collider>,
    pub particles: ParticleContacts,
    /// Sharp features at the end of the current step, and those under cloth triangles.
    features: feature_contacts::FeatureSet,
    feature_hits: Vec<feature_contacts::FeatureContact>,
    /// Stiffness of the feature penalty, N/m.
    feature_stiffness: f64,
    /// Inverse masses, zero for pinned particles (they do not yield to a push).
    inv_mass: Vec<f64>,
    /// The step's end positions before the features' pushes (scratch, kept between
    /// steps).
    solved: Vec<Vec3>,
}

/// What the end-of-step contact passes did.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct ContactCounts {
    pub corrected: usize,
    pub crossings: usize,
    pub features: usize,
}

impl Contacts {
    /// `feature_stiffness` (N/m): ten times the fabric's tensile stiffness, so the cloth
    /// rests within the thickness on a corner carrying its weight; an explicit step must
    /// be a few times shorter near features than the cloth alone would allow.
    /// `cloth_friction`: each particle's fabric's Coulomb coefficient, for bodies without
    /// their own.
    pub fn new(
        collider: Arc<dyn Collider>,
        masses: &[f64],
        pinned: &[bool],
        feature_stiffness: f64,
        cloth_friction: Vec<f64>,
    ) -> Self {
        // Far particles are not asked again until they may have come within this much of
        // the contact layer; a few thicknesses keep the bounded queries cheap.
        let reach = 4.0 * collider.max_thickness();
        let inv_mass = masses
            .iter()
            .zip(pinned)
            .map(|(m, &p)| if p { 0.0 } else { 1.0 / m })
            .collect();
        Self {
            collider,
            particles: ParticleContacts::new(reach, cloth_friction),
            features: feature_contacts::FeatureSet::default(),
            feature_hits: Vec::new(),
            feature_stiffness,
            inv_mass,
            solved: Vec::new(),
        }
    }

    /// Lets only `scale` of the friction on the bodies act (1 all, as built; 0 none), the
    /// bodies' own coefficients and the cloth's alike.
    pub fn scale_friction(&mut self, scale: f64) {
        self.particles.friction_scale = scale;
    }

    /// Finds the sharp features (at the step's end time) under cloth triangles at the
    /// step's start.
    pub fn detect_features(&mut self, start: &StepStart<'_>, triangles: &[[usize; 3]]) {
        let collider = self.collider.as_ref();
        let t1 = start.t0 + start.h;
        self.features.update(|out| collider.sharp_features(t1, out));
        let particles = &self.particles;
        let reach = feature_contacts::FeatureReach {
            gap_bound: |i| particles.feature_gap_bound(i),
            max_thickness: self.collider.max_thickness(),
        };
        feature_contacts::detect_features(
            &mut self.features,
            triangles,
            start.x,
            reach,
            |own, i| particles.friction(own, i),
            &mut self.feature_hits,
        );
    }

    /// Number of feature contacts in the current step.
    pub fn feature_contacts(&self) -> usize {
        self.feature_hits.len()
    }

    /// The feature penalty's forces and `K v`, and for an implicit step of length `h` its
    /// matrix terms and friction (see [`feature_contacts::add_penalty`]); returns its energy.
    pub fn add_feature_penalty(&self, x: &[Vec3], v: &[Vec3], out: ForceOutputs<'_, '_>) -> f64 {
        feature_contacts::add_penalty(&self.feature_hits, self.feature_stiffness, x, v, out)
    }

    /// The end-of-step passes: the push-out speed taken back out of the contacts'
    /// velocities, the path test of every particle, and sharp features through cloth
    /// triangles; then each particle a contact holds gets its body's normal as support.
    pub fn finish_step(&mut self, end: &mut StepEnd<'_>, triangles: &[[usize; 3]]) -> ContactCounts {
        self.particles.finish(end.v1);
        let collider = self.collider.as_ref();
        let sweep = self.particles.sweep(collider, end);
        let particles = &self.particles;
        // Only the features' pushes need the positions before them.
        self.solved.clear();
        if !self.features.features.is_empty() {
            self.solved.extend_from_slice(end.x1);
        }
        let reach = feature_contacts::FeatureReach {
            gap_bound: |i| particles.feature_gap_bound(i),
            max_thickness: collider.max_thickness(),
        };
        let features = feature_contacts::resolve_features(
            &mut self.features,
            triangles,
            end,
            &self.solved,
            &self.inv_mass,
            reach,
        );
        end.support.fill(Vec3::zeros());
        for c in self.particles.active.iter().filter(|c| c.live) {
            end.support[c.particle()] = c.normal;
        }
        ContactCounts {
            corrected: sweep.corrected,
            crossings: sweep.crossings,
            features,
        }
    }
}
