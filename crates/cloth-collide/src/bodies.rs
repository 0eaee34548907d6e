//! A set of bodies: what the solver collides the cloth with.

use crate::body::Parts;
use crate::Body;
use cloth_core::{math::Vec3, Collider, ParticlePath, Proximity, SharpFeature, SurfacePoint};
use nalgebra::Point3;

/// The rigid bodies of a scene, answering the solver's contact queries.
#[derive(Debug, Clone, Default)]
pub struct Bodies {
    bodies: Vec<Body>,
}

impl Bodies {
    pub fn new(bodies: Vec<Body>) -> Self {
        Self { bodies }
    }
    pub fn push(&mut self, body: Body) {
        self.bodies.push(body);
    }
    pub fn bodies(&self) -> &[Body] {
        &self.bodies
    }

    /// The smallest signed distance of `x` from any body at time `t` (negative: inside),
    /// with the body's index; `None` without bodies.
    pub fn signed_distance(&self, t: f64, x: &Vec3) -> Option<(f64, usize)> {
        self.bodies
            .iter()
            .enumerate()
            .map(|(k, b)| (b.signed_distance(t, x), k))
            .min_by(|a, b| a.0.total_cmp(&b.0))
    }

    /// The deepest any of `points` is inside a body at time `t`, m (0 when none is inside),
    /// with the point's index.
    pub fn deepest_inside(&self, t: f64, points: &[Vec3]) -> (f64, Option<usize>) {
        use rayon::prelude::*;
        points
            .par_iter()
            .enumerate()
            .map(|(i, x)| match self.signed_distance(t, x) {
                Some((d, _)) if d < 0.0 => (-d, Some(i)),
                _ => (0.0, None),
            })
            .reduce(|| (0.0, None), |a, b| if b.0 > a.0 { b } else { a })
    }
}

impl Bodies {
    /// The nearest entry or surface point over `parts` of every body (see
    /// [`Collider::sweep`]).
    fn sweep_parts(
        &self,
        parts: Parts,
        path: &ParticlePath,
        start_gap_lower_bound: f64,
        reach: f64,
    ) -> Proximity {
        let mut best: Option<(SurfacePoint, f64)> = None;
        for (k, body) in self.bodies.iter().enumerate() {
            let d = body.thickness();
            let Some(hit) = body.sweep(parts, path, start_gap_lower_bound + d, d + reach) else {
                continue;
            };
            // The earliest entry wins; among plain proximities, the smallest gap.
            let rank = if hit.crossed {
                hit.entry - 2.0
            } else {
                hit.distance - hit.thickness
            };
            if best.as_ref().is_some_and(|(_, r)| *r <= rank) {
                continue;
            }
            let point = SurfacePoint {
                body: k,
                point: hit.point,
                normal: hit.normal,
                distance: hit.distance,
                velocity: body.motion().velocity_at(path.t1, &hit.point),
                thickness: hit.thickness,
                friction: body.friction(),
                crossed: hit.crossed,
            };
            best = Some((point, rank));
        }
        match best {
            Some((p, _)) => Proximity::Near(p),
            None => Proximity::Far {
                gap_lower_bound: reach,
            },
        }
    }
}

impl Collider for Bodies {
    fn sweep(&self, path: &ParticlePath, start_gap_lower_bound: f64, reach: f64) -> Proximity {
        self.sweep_parts(Parts::All, path, start_gap_lower_bound, reach)
    }

    fn sweep_past_thin_parts(
        &self,
        path: &ParticlePath,
        start_gap_lower_bound: f64,
        reach: f64,
    ) -> Proximity {
        self.sweep_parts(Parts::Thick, path, start_gap_lower_bound, reach)
    }

    fn motion_bound(&self, t0: f64, t1: f64) -> f64 {
        self.bodies
            .iter()
            .map(|b| b.motion().displacement_bound(t0, t1, b.radius()))
            .fold(0.0, f64::max)
    }

    /// With no body, the default thickness: the contact margins stay positive, as the
    /// simulation asks, though there is nothing to meet (a garment sewn and hung in the
    /// air by its pins).
    fn max_thickness(&self) -> f64 {
        if self.bodies.is_empty() {
            return crate::body::DEFAULT_THICKNESS;
        }
        self.bodies.iter().map(|b| b.thickness()).fold(0.0, f64::max)
    }

    fn segment_crossings(&self, t: f64, a: &Vec3, b: &Vec3) -> usize {
        self.bodies
            .iter()
            .map(|body| body.segment_crossings(t, a, b))
            .sum()
    }

    fn thick_segment_crossings(&self, t: f64, a: &Vec3, b: &Vec3) -> usize {
        self.bodies
            .iter()
            .map(|body| body.segment_crossings_of(Parts::Thick, t, a, b))
            .sum()
    }

    fn sharp_features(&self, t: f64, out: &mut Vec<SharpFeature>) {
        for body in &self.bodies {
            if body.sharp_features().is_empty() {
                continue;
            }
            let pose = body.pose(t);
            let vertices = body.surface().vertices();
            for f in body.sharp_features() {
                let a = (pose * Point3::from(vertices[f.a as usize])).coords;
                let b = (pose * Point3::from(vertices[f.b as usize])).coords;
                out.push(SharpFeature {
                    a,
                    b,
                    normal: pose.rotation * f.normal,
                    velocity: body.motion().velocity_at(t, &(0.5 * (a + b))),
                    thickness: body.thickness(),
                    friction: body.friction(),
                });
            }
        }
    }
}
