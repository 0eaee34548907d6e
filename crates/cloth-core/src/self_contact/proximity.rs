//! Proximity: the particle-triangle and edge-edge pairs of the cloth closer than their
//! contact distance at the start of a step, or closing in fast enough to come that close
//! within it, each a [`Contact`] the step's solve holds at the distance.

use super::topology::Topology;
use crate::energy::repulsion::ContactFrame;
use crate::math::predicates::{closest_on_segments, closest_on_triangle, triangle_normal};
use crate::math::Vec3;
use crate::spatial::Aabb;

/// A pair of the cloth in contact with itself for one step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    pub particles: [u32; 4],
    pub frame: ContactFrame,
    /// The distance the repulsion keeps between the two points, m.
    pub distance: f64,
    /// The gap at the start of the step, m.
    pub gap: f64,
    /// Coulomb coefficient between the two layers.
    pub friction: f64,
}

impl Contact {
    pub(crate) fn gather(&self, u: &[Vec3]) -> [Vec3; 4] {
        self.particles.map(|i| u[i as usize])
    }
}

/// A pair beyond its contact distance, but closing in to within this fraction of it
/// beyond over the step at its present speed, is held at the distance in the step: it
/// lands on the other layer and stays, rather than falling onto it, being caught by the
/// impact passes and pushed off by the repulsion, step after step.
pub const LANDING_MARGIN: f64 = 0.1;
/// How far beyond its contact distance a pair is looked for, in contact distances.
pub const LOOK_AHEAD: f64 = 1.0;
/// Least cosine between the normal of a contact beside a triangle's edge or corner and the
/// triangle's own normal (15 degrees).
const ACROSS_FACE: f64 = 0.966;

/// What a proximity search needs of the cloth.
pub(crate) struct Cloth<'a> {
    pub topology: &'a Topology,
    pub x: &'a [Vec3],
    pub v: &'a [Vec3],
    /// The step's length, or `None` for an explicit step (too short to look ahead).
    pub h: Option<f64>,
    pub pinned: &'a [bool],
    /// Each particle's share of the contact distance (half its thickness) and its
    /// Coulomb coefficient.
    pub half_thickness: &'a [f64],
    pub friction: &'a [f64],
}

impl Cloth<'_> {
    /// The weighted mean of a per-particle value over a contact's two points (each
    /// point's weights sum to one, so their absolute values sum to two).
    fn mean(&self, values: &[f64], particles: &[u32; 4], weights: &[f64; 4]) -> f64 {
        0.5 * (0..4)
            .map(|k| weights[k].abs() * values[particles[k] as usize])
            .sum::<f64>()
    }

    fn contact(&self, particles: [u32; 4], weights: [f64; 4]) -> Option<Contact> {
        if particles.iter().all(|&i| self.pinned[i as usize]) {
            return None;
        }
        let distance = 2.0 * self.mean(self.half_thickness, &particles, &weights);
        let gap: Vec3 = (0..4).map(|k| weights[k] * self.x[particles[k] as usize]).sum();
        let d = gap.norm();
        if d >= (1.0 + LOOK_AHEAD) * distance {
            return None;
        }
        // Touching to rounding, the direction between the points says nothing, and the pair
        // is not two layers but one folded into itself (rows of a flat sheet collapsed into
        // each other): it is no contact to hold apart.
        if d <= 1e-9 * distance {
            return None;
        }
        let normal = gap / d;
        if d >= distance {
            let h = self.h?;
            let closing: f64 = (0..4)
                .map(|k| weights[k] * normal.dot(&self.v[particles[k] as usize]))
                .sum();
            if d + h * closing.min(0.0) >= (1.0 + LANDING_MARGIN) * distance {
                return None;
            }
        }
        Some(Contact {
            particles,
            frame: ContactFrame { weights, normal },
            distance,
            gap: d,
            friction: self.mean(self.friction, &particles, &weights),
        })
    }

    /// The triangles around `p`'s nearest point on triangle `t` (at barycentric `w`, on
    /// an edge or a corner), other than `t`: one of them over whose face `p` lies, if any.
    fn covered(&self, p: &Vec3, t: usize, w: &[f64; 3]) -> bool {
        let tri = self.topology.triangles[t];
        let face_of = |s: usize| {
            let [a, b, c] = self.topology.triangles[s].map(|i| self.x[i as usize]);
            closest_on_triangle(p, &a, &b, &c)
        };
        match w.iter().filter(|&&x| x == 0.0).count() {
            1 => {
                let k = w.iter().position(|&x| x == 0.0).expect("one zero");
                self.topology
                    .across(t, k)
                    .is_some_and(|s| face_of(s).iter().all(|&x| x > 0.0))
            }
            _ => {
                // At a corner: a triangle around it with p over its face, or beside one of
                // its edges through the corner.
                let k = w.iter().position(|&x| x != 0.0).unwrap_or(0);
                let corner = tri[k];
                self.topology.triangles_of(corner as usize).iter().any(|&s| {
                    let s = s as usize;
                    if s == t {
                        return false;
                    }
                    let ws = face_of(s);
                    let zeros = ws.iter().filter(|&&x| x == 0.0).count();
                    let at = self.topology.triangles[s].iter().position(|&v| v == corner);
                    zeros == 0
                        || (zeros == 1
                            && at.is_some_and(|at| {
                                ws[at] != 0.0 && ws.iter().position(|&x| x == 0.0) != Some(at)
                            }))
                })
            }
        }
    }

    /// Particle `p` against triangle `t`, if within `reach`. Where `p`'s nearest point on
    /// the triangle is on its edge or corner, the contact stands only if no triangle around
    /// that edge or corner has `p` over its face: over a smooth surface the face's contact
    /// is the surface's, and the neighbours' would be ridges at every edge that catch a
    /// layer sliding across them. Over a ridge or a border, the edge or corner is the
    /// nearest surface, and the first triangle having it speaks for it.
    pub fn particle_triangle(&self, p: usize, t: usize, reach: f64, found: &mut Vec<Contact>) {
        let xp = self.x[p];
        let tri = self.topology.triangles[t];
        let [a, b, c] = tri.map(|i| self.x[i as usize]);
        if !Aabb::of([a, b, c]).overlaps(&Aabb::point(&xp).inflated(reach)) {
            return;
        }
        let w = closest_on_triangle(&xp, &a, &b, &c);
        // The exemption (fixed, but searched in the flat cloth) after the cheaper test.
        if (xp - (w[0] * a + w[1] * b + w[2] * c)).norm() >= reach
            || self.topology.vertex_triangle_exempt(p, t)
        {
            return;
        }
        let zeros = w.iter().filter(|&&x| x == 0.0).count();
        if zeros > 0 && (!self.topology.owns_point(t, &w) || self.covered(&xp, t, &w)) {
            return;
        }
        let particles = [p as u32, tri[0], tri[1], tri[2]];
        let Some(contact) = self.contact(particles, [1.0, -w[0], -w[1], -w[2]]) else {
            return;
        };
        // Beside an edge or a corner, a contact nearly across the face's plane is one; one
        // slanting off it is a particle level with the border of the other layer, which it
        // slides past and would be stopped by as by a wall, and a pair not yet in contact
        // there is not landing on the layer.
        if zeros > 0 {
            let across = triangle_normal(&a, &b, &c)
                .is_some_and(|n| n.dot(&contact.frame.normal).abs() >= ACROSS_FACE);
            if !across || contact.gap >= contact.distance {
                return;
            }
        }
        found.push(contact);
    }

    /// Edges `e` and `f` within `reach` of each other, where the nearest points are inside
    /// both edges: a nearest point at an end is a particle's, which its triangles' contacts
    /// have.
    pub fn edge_edge(&self, e: usize, f: usize, reach: f64, found: &mut Vec<Contact>) {
        let ([i, j], [k, l]) = (self.topology.edges[e], self.topology.edges[f]);
        let (p0, p1) = (self.x[i as usize], self.x[j as usize]);
        let (q0, q1) = (self.x[k as usize], self.x[l as usize]);
        if !Aabb::of([q0, q1]).overlaps(&Aabb::of([p0, p1]).inflated(reach)) {
            return;
        }
        let (s, t) = closest_on_segments(&p0, &p1, &q0, &q1);
        if !(s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0) {
            return;
        }
        // The exemption (fixed, but searched in the flat cloth) for contacts only.
        let contact = self.contact([i, j, k, l], [1.0 - s, s, t - 1.0, -t]);
        found.extend(contact.filter(|_| !self.topology.edge_edge_exempt(e, f)));
    }
}
