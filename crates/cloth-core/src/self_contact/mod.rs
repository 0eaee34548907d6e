//! Contact of the cloth with itself: layers and folds that never pass through each other.
//!
//! Two stages a step, after Bridson, Fedkiw & Anderson (2002):
//! - **Proximity, in the solve.** At the start of the step every particle-triangle and
//!   edge-edge pair closer than its contact distance (the sum of the two layers' half
//!   thicknesses) becomes a one-sided spring on the gap along the pair's normal
//!   ([`crate::energy::repulsion`]), with Coulomb friction between the layers as a drag
//!   against their sliding, both with their Jacobians in the implicit system (as
//!   transient couplings of the block-sparse matrix, which the multigrid carries to its
//!   coarse levels). Found through bounding volume hierarchies refitted each step.
//! - **Impacts, after it.** Every particle-triangle and edge-edge pair is tested for
//!   passing through each other along the straight paths of the step ([`ccd`]). A pair
//!   that does is put back on its side, inside the contact distance where the next step's
//!   repulsion holds it, and loses its approach speed (an inelastic impulse with Coulomb
//!   friction), passes of this going on over the pairs they disturb. Pairs still
//!   crossing after [`IMPULSE_PASSES`] are merged into impact zones that move as one,
//!   which cannot pass through themselves (Provot 1997); zones grow until nothing
//!   crosses.
//!
//! Pairs sharing a particle are exempt, and so are the particles a seam pulls together
//! (they will be one), with their triangles and edges.

mod bvh;
mod ccd;
mod chunks;
pub mod geometry;
mod intersections;
mod proximity;
mod response;
mod settings;
mod topology;

pub use intersections::{closest_self_approach, count_self_intersections, Intersections};
pub use settings::SelfCollision;

use crate::contact::SLIP_SPEED;
use crate::energy::repulsion::{add_friction_drag, add_repulsion, RepulsionLaw};
use crate::energy::Local;
use crate::linalg::BlockSparse;
use crate::mesh::ClothMesh;
use crate::{Mat3, Vec3};
use bvh::{Aabb, Bvh};
use ccd::Impact;
use chunks::ChunkedSearch;
use proximity::Cloth;
pub use proximity::Contact;
use topology::Topology;

/// Impulse passes over the impacts before the remaining ones are merged into zones.
pub const IMPULSE_PASSES: usize = 6;
/// Passes growing the impact zones at most.
pub const ZONE_PASSES: usize = 40;
/// Pairs nearer than this in the flat cloth, in the largest distance a contact is looked
/// for at, are exempt (see [`topology`]): a margin for the cloth's compression.
const REST_EXEMPTION: f64 = 1.5;

/// The radius within which pairs near in the flat cloth are exempt, for a largest contact
/// distance `distance`.
pub(crate) fn rest_radius(distance: f64) -> f64 {
    REST_EXEMPTION * (1.0 + proximity::LOOK_AHEAD) * distance
}

/// Default repulsion stiffness over the stiffest fabric's membrane stiffness.
const STIFFNESS_FRACTION: f64 = 0.1;

/// What a search item is: particles `0..n`, then the triangles, then the edges.
enum Item {
    Particle(usize),
    Triangle(usize),
    Edge(usize),
}

/// The kind of search item `item` of a cloth of `n` particles and `t` triangles.
fn item_kind(item: usize, n: usize, t: usize) -> Item {
    if item < n {
        Item::Particle(item)
    } else if item < n + t {
        Item::Triangle(item - n)
    } else {
        Item::Edge(item - n - t)
    }
}

/// The contacts of each of `n` particles, by counting sort: `rows[i]..rows[i + 1]` of
/// `list` holds particle `i`'s (contact, corner) pairs.
fn index_by_particle(contacts: &[Contact], n: usize, rows: &mut Vec<u32>, list: &mut Vec<(u32, u8)>) {
    rows.clear();
    rows.resize(n + 1, 0);
    for c in contacts {
        for k in 0..4 {
            if c.frame.weights[k] != 0.0 {
                rows[c.particles[k] as usize + 1] += 1;
            }
        }
    }
    for i in 0..n {
        rows[i + 1] += rows[i];
    }
    list.clear();
    list.resize(rows[n] as usize, (0, 0));
    // Fill each row from its end, stepping the row's start back to where it began.
    for (ci, c) in contacts.iter().enumerate().rev() {
        for k in (0..4).rev() {
            if c.frame.weights[k] != 0.0 {
                let i = c.particles[k] as usize;
                rows[i + 1] -= 1;
                list[rows[i + 1] as usize] = (ci as u32, k as u8);
            }
        }
    }
    // rows[i + 1] now holds row i's start: shift back.
    rows.rotate_left(1);
    rows[n] = list.len() as u32;
}

/// The cloth's self-collision state and scratch, owned by the simulation.
#[derive(Debug)]
pub(crate) struct SelfContacts {
    topology: Topology,
    /// Each particle's half thickness (its share of a contact distance) and friction.
    half_thickness: Vec<f64>,
    friction: Vec<f64>,
    stiffness: f64,
    /// The largest contact distance, m.
    reach: f64,
    /// Within this of each other, primitives passing through one plane touch, m.
    touch: f64,
    triangle_tree: Bvh,
    edge_tree: Bvh,
    vertex_tree: Bvh,
    /// The step's contacts, and each one's friction drag, N s/m.
    pub contacts: Vec<Contact>,
    drag: Vec<f64>,
    /// The contacts of each particle, (contact, corner), in compressed rows.
    by_particle: Vec<u32>,
    by_particle_list: Vec<(u32, u8)>,
    /// Every particle and edge: the items of a full search (see [`item_kind`]).
    all_items: Vec<u32>,
    contact_search: ChunkedSearch<Contact>,
    impact_search: ChunkedSearch<Impact>,
    response: response::Scratch,
}

impl SelfContacts {
    /// Self-collision for `mesh` with `seams` (pairs of particles to be joined), each
    /// particle of fabric `thickness[i]`, `friction[i]`; `settings` override them.
    pub fn new(
        mesh: &ClothMesh,
        seams: &[[usize; 2]],
        settings: &SelfCollision,
        thickness: impl Fn(usize) -> f64,
        friction: impl Fn(usize) -> f64,
        membrane_stiffness: f64,
    ) -> Self {
        let n = mesh.vertex_count();
        let half_thickness: Vec<f64> = (0..n)
            .map(|i| 0.5 * settings.thickness.unwrap_or_else(|| thickness(i)))
            .collect();
        let largest = 2.0 * half_thickness.iter().copied().fold(0.0, f64::max);
        let topology = Topology::new(mesh, seams, rest_radius(largest));
        let friction: Vec<f64> = (0..n)
            .map(|i| settings.friction.unwrap_or_else(|| friction(i)))
            .collect();
        let reach = 2.0 * half_thickness.iter().copied().fold(0.0, f64::max);
        let touch = 0.02 * 2.0 * half_thickness.iter().copied().fold(f64::INFINITY, f64::min);
        let x = mesh.positions();
        let centre = |ids: &[u32]| ids.iter().map(|&i| x[i as usize]).sum::<Vec3>() / ids.len() as f64;
        let triangle_tree = Bvh::new(&topology.triangles.iter().map(|t| centre(t)).collect::<Vec<_>>());
        let edge_tree = Bvh::new(&topology.edges.iter().map(|e| centre(e)).collect::<Vec<_>>());
        let vertex_tree = Bvh::new(x);
        let t = topology.triangles.len();
        let all_items = (0..n as u32)
            .chain((n + t) as u32..(n + t + topology.edges.len()) as u32)
            .collect();
        Self {
            stiffness: settings
                .stiffness
                .unwrap_or(STIFFNESS_FRACTION * membrane_stiffness),
            response: response::Scratch::new(n, topology.triangles.len(), topology.edges.len()),
            topology,
            half_thickness,
            friction,
            reach,
            touch,
            triangle_tree,
            edge_tree,
            vertex_tree,
            contacts: Vec::new(),
            drag: Vec::new(),
            by_particle: Vec::new(),
            by_particle_list: Vec::new(),
            all_items,
            contact_search: ChunkedSearch::default(),
            impact_search: ChunkedSearch::default(),
        }
    }

    /// Finds the contacts at `x` for a step of length `h` from velocities `v`, and sets
    /// each one's friction: a drag `mu f / s` against the two points' sliding, `f` the
    /// repulsion's push and `s` their sliding speed at the start (at least [`SLIP_SPEED`],
    /// under which friction holds them). Explicit steps take at most the drag they can
    /// integrate stably.
    pub fn detect(
        &mut self,
        x: &[Vec3],
        v: &[Vec3],
        masses: &[f64],
        pinned: &[bool],
        h: f64,
        implicit: bool,
        parallel: bool,
    ) {
        let step = implicit.then_some(h);
        let topo = &self.topology;
        self.triangle_tree
            .refit(|t| Aabb::of(topo.triangles[t].map(|i| x[i as usize])));
        self.edge_tree
            .refit(|e| Aabb::of(topo.edges[e].map(|i| x[i as usize])));
        let cloth = Cloth {
            topology: topo,
            x,
            v,
            h: step,
            pinned,
            half_thickness: &self.half_thickness,
            friction: &self.friction,
        };
        let (n, t) = (topo.particles(), topo.triangles.len());
        let reach = (1.0 + proximity::LOOK_AHEAD) * self.reach;
        let (triangles, edges) = (&self.triangle_tree, &self.edge_tree);
        self.contact_search.run(
            &self.all_items,
            parallel,
            &mut self.contacts,
            |item, found| match item_kind(item, n, t) {
                Item::Particle(i) => cloth.particle_triangle(i, triangles, reach, found),
                Item::Edge(e) => cloth.edge_edge(e, edges, reach, found),
                Item::Triangle(_) => {}
            },
        );
        index_by_particle(
            &self.contacts,
            n,
            &mut self.by_particle,
            &mut self.by_particle_list,
        );
        self.drag.clear();
        for c in &self.contacts {
            let push = self.law(c).at(c.gap).1.max(0.0);
            let sliding = {
                let n = c.frame.normal;
                let u = c.frame.relative(&c.gather(v));
                (u - u.dot(&n) * n).norm()
            };
            let mut drag = c.friction * push / sliding.max(SLIP_SPEED);
            if !implicit {
                // Forward Euler damps a drag c on mass m only while h c / m < 2.
                let lightest = (0..4)
                    .filter(|&k| c.frame.weights[k] != 0.0)
                    .map(|k| masses[c.particles[k] as usize])
                    .fold(f64::INFINITY, f64::min);
                drag = drag.min(0.5 * lightest / h);
            }
            self.drag.push(drag);
        }
    }

    fn law(&self, c: &Contact) -> RepulsionLaw {
        RepulsionLaw {
            stiffness: self.stiffness,
            distance: c.distance,
        }
    }

    /// Whether particle `i` lies on other cloth on the side `normal` points away from:
    /// in a contact of the step whose other point is that way.
    pub fn lies_on_cloth(&self, i: usize, normal: &Vec3) -> bool {
        let Some(&[first, last]) = self.by_particle.get(i..i + 2) else {
            return false;
        };
        self.by_particle_list[first as usize..last as usize]
            .iter()
            .any(|&(c, k)| {
                let c = &self.contacts[c as usize];
                // The contact's normal points to the side of the particles weighted positively.
                c.frame.weights[k as usize].signum() * c.frame.normal.dot(normal) > 0.5
            })
    }

    /// The contacts' forces (repulsion and friction at `v`) into `force` and the
    /// repulsion's `K v` into `kv`; for an implicit step of length `h`, `h^2 K + h C` into
    /// the matrix's transient couplings. Returns the repulsion's energy.
    pub fn add_forces(
        &self,
        x: &[Vec3],
        v: &[Vec3],
        force: &mut [Vec3],
        kv: &mut [Vec3],
        mut implicit: Option<(&mut BlockSparse, f64)>,
    ) -> f64 {
        let mut energy = 0.0;
        let (mut spring, mut friction) = (Local::<4>::default(), Local::<4>::default());
        for (c, &drag) in self.contacts.iter().zip(&self.drag) {
            spring.clear();
            friction.clear();
            let (xe, ve) = (c.gather(x), c.gather(v));
            let law = self.law(c);
            add_repulsion(&c.frame, &law, &xe, &mut spring);
            add_friction_drag(&c.frame, drag, &ve, &mut friction);
            // A pair landing from beyond the distance has none yet.
            if c.gap < c.distance {
                energy += spring.energy;
            }
            for a in 0..4 {
                let i = c.particles[a] as usize;
                force[i] -= spring.grad[a] + friction.grad[a];
                kv[i] += (0..4).map(|b| spring.hess[a][b] * ve[b]).sum::<Vec3>();
            }
            if let Some((m, h)) = implicit.as_mut() {
                // The element Hessians are `w_a w_b` times these.
                let n = c.frame.normal;
                let stiffness = (*h * *h * law.at(c.frame.gap(&xe)).2) * (n * n.transpose())
                    + (*h * drag) * (Mat3::identity() - n * n.transpose());
                let terms = (0..4)
                    .filter(|&a| c.frame.weights[a] != 0.0)
                    .map(|a| (c.particles[a] as usize, c.frame.weights[a] * Mat3::identity()));
                m.add_coupling(stiffness, terms);
            }
        }
        energy
    }

    /// Counts the intersecting edge-triangle pairs of the cloth at `x` (pairs sharing a
    /// particle, or seam partners, exempt).
    pub fn intersections(&self, x: &[Vec3]) -> Intersections {
        intersections::count(&self.topology, x)
    }
}
