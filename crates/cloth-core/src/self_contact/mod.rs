//! Contact of the cloth with itself: layers and folds that never pass through each other.
//!
//! Two stages a step, after Bridson, Fedkiw & Anderson (2002):
//! - **Proximity, in the solve.** At the start of the step every particle-triangle and
//!   edge-edge pair closer than its contact distance (the sum of the two layers' half
//!   thicknesses), or closing in on it within the step, becomes a spring on the gap along
//!   the pair's normal ([`crate::energy::repulsion`]), with Coulomb friction between the
//!   layers as a drag against their sliding (set after a scouting solve), both with their
//!   Jacobians in the implicit system as transient couplings of the block-sparse matrix,
//!   which the multigrid carries to its coarse levels. Found by walking a bounding volume
//!   hierarchy of the triangles, refitted each step, against itself (`cone_tree`).
//! - **Impacts, after it.** Every particle-triangle and edge-edge pair is tested for
//!   passing through each other along the straight paths of the step (`ccd`). A pair
//!   that does is put back on its side, inside the contact distance where the next step's
//!   repulsion holds it, and loses its approach speed (an inelastic impulse with Coulomb
//!   friction), passes of this going on over the pairs they disturb. Pairs still
//!   crossing after [`IMPULSE_PASSES`] are merged into impact zones that move as one,
//!   which cannot pass through themselves (Provot 1997), for [`ZONE_PASSES`]; what still
//!   crosses then stays where the step started it.
//!
//! Exempt are pairs with shared or neighbouring particles (the particles a seam pulls
//! together counting as one until welded) and pairs near in the flat cloth (`topology`).

mod settings;
mod layer_pass;
mod chunks;
mod cone;
mod topology;
mod contour;
mod ccd;
mod intersections;
mod proximity;
mod cone_tree;
mod response;
mod untangling;

pub use intersections::{
    closest_self_approach, count_self_intersections, self_intersecting_pairs, Intersections, SelfCrossings,
};

/// Two pieces of the cloth (charts: panels, for a garment) that passed through each other
/// when the simulation began. Held apart, they would stay hooked through each other, so
/// they are exempt from each other's collision until they have come apart (GarmentCode
/// places a hood through a bodice, a collar through a neckline, and the seams pull them
/// out of each other); from then on they collide as any cloth does.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Tangle {
    /// A triangle of each piece.
    pub triangles: [usize; 2],
    /// Edge-triangle pairs of the two passing through each other at the start.
    pub crossings: usize,
    /// The step after which they were found apart, and collide again; `None` while they
    /// are still through each other.
    pub released: Option<u64>,
}
pub use layer_pass::{LayerPass, LayerPassing};
pub use settings::{LayerFabric, SelfCollision};

use crate::contact::{StepStart, SLIP_SPEED};
use crate::energy::repulsion::{add_friction_drag, add_repulsion, RepulsionLaw};
use crate::energy::Local;
use crate::linalg::BlockSparse;
use crate::math::{Mat3, Vec3};
use crate::mesh::ClothMesh;
use crate::spatial::Aabb;
use ccd::Impact;
use chunks::ChunkedSearch;
use cone::Cone;
use cone_tree::{ConeTree, Search};
use contour::Motion;
use proximity::Cloth;
pub use proximity::Contact;
use topology::Topology;

/// Impulse passes over the impacts before the remaining ones are merged into zones.
pub const IMPULSE_PASSES: usize = 6;
/// Passes growing the impact zones at most.
pub const ZONE_PASSES: usize = 40;
/// Pairs nearer than this in the flat cloth, in the largest distance a contact is looked
/// for at, are exempt (see `topology`): a margin for the cloth's compression.
const REST_EXEMPTION: f64 = 1.5;

/// The radius within which pairs near in the flat cloth are exempt, for a largest contact
/// distance `distance`.
pub(crate) fn rest_radius(distance: f64) -> f64 {
    REST_EXEMPTION * (1.0 + proximity::LOOK_AHEAD) * distance
}

/// Default repulsion stiffness over the stiffest fabric's membrane stiffness.
const STIFFNESS_FRACTION: f64 = 0.1;

/// The particles triangle `s` speaks for, each against triangle `t`: each particle of the
/// cloth is searched against each triangle once, from the triangle that has it.
fn owned_particles(topology: &Topology, s: usize, t: usize) -> impl Iterator<Item = (usize, usize)> + '_ {
    let owned = topology.owned(s);
    (0..3)
        .filter(move |k| owned & (1 << k) != 0)
        .map(move |k| (topology.triangles[s][k] as usize, t))
}

/// The pairs of an edge triangle `s` speaks for and one `t` does (lower edge first).
fn owned_edge_pairs(topology: &Topology, s: usize, t: usize) -> impl Iterator<Item = (usize, usize)> + '_ {
    let (mine, theirs) = (topology.owned(s), topology.owned(t));
    (0..3).filter(move |k| mine & (8 << k) != 0).flat_map(move |k| {
        (0..3).filter(move |m| theirs & (8 << m) != 0).map(move |m| {
            let (e, f) = (topology.triangle_edges[s][k], topology.triangle_edges[t][m]);
            (e.min(f) as usize, e.max(f) as usize)
        })
    })
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
    /// The sides of the layer passes holding, in the order given (see
    /// [`SelfContacts::set_passes`]).
    pass_regions: Vec<intersections::PassRegion>,
    /// Each particle's half thickness (its share of a contact distance) and friction.
    half_thickness: Vec<f64>,
    /// Each particle's inverse mass, zero when pinned.
    inv_mass: Vec<f64>,
    /// The friction the step's contacts can exert on each particle, N, and the particles
    /// with some (see [`SelfContacts::set_friction`]).
    brake: Vec<f64>,
    braked: Vec<u32>,
    friction: Vec<f64>,
    stiffness: f64,
    /// The largest contact distance, m.
    reach: f64,
    /// Within this of each other, primitives passing through one plane touch, m.
    touch: f64,
    tree: ConeTree,
    /// The step's contacts, each one's friction drag (N s/m) and the stiffness of its
    /// repulsion at the start of the step (N/m).
    pub contacts: Vec<Contact>,
    drag: Vec<f64>,
    normal_stiffness: Vec<f64>,
    /// The contacts of each particle, (contact, corner), in compressed rows.
    by_particle: Vec<u32>,
    by_particle_list: Vec<(u32, u8)>,
    contact_search: ChunkedSearch<Contact>,
    impact_search: ChunkedSearch<Impact>,
    response: response::Scratch,
    /// Whether the cloth passed through itself when last looked at (see
    /// [`SelfContacts::pull_apart`]); it is looked at from the first step on until it
    /// does not, or the pull has stopped gaining.
    crossed: bool,
    /// The fewest crossings the pull has left, and the steps since it left fewer.
    fewest: usize,
    stale: u32,
    /// The most the pull moves a particle in a step, m ([`PULL_APART`] thicknesses of the
    /// thinnest fabric).
    pull_step: f64,
    /// Whether the cloth where it crosses is loose while the pull goes on (see
    /// [`SelfContacts::set_loose_pull`]).
    loose_pull: bool,
}

/// The most a particle is moved per step to pull cloth out of itself, in thicknesses of
/// the thinnest fabric (3 mm in cotton poplin). Smaller moves were undone by the step's
/// own forces as fast as they were made: at half a thickness GarmentCode's rand_1_042
/// kept 3 crossings to rest; at five, rand_1_034's collar stayed through its front
/// (6 to 10 crossings a step, 5 to rest); at ten, both came apart within a dozen steps.
const PULL_APART: f64 = 10.0;

/// Steps the pull goes on without leaving fewer crossings than its best before it stops
/// for good: moved every step, cloth held through itself (GarmentCode's rand_1_091, a
/// skirt through its inserts; rand_1_085, a collar's back through its bodice) never came
/// to rest (768 and 1,049 drape steps), where a panel that comes apart does so within a
/// few dozen.
const PULL_PATIENCE: u32 = 100;

/// Rings of neighbours round the particles of the edges and triangles crossing each other
/// that are loose while the cloth is pulled out of itself (see [`SelfContacts::pull_apart`]).
const LOOSE_RINGS: usize = 1;

impl SelfContacts {
    /// Self-collision for `mesh` with `seams` (pairs of particles to be joined), each
    /// particle's layer as `fabric` says; `settings` override it.
    pub fn new<T: Fn(usize) -> f64, F: Fn(usize) -> f64>(
        mesh: &ClothMesh,
        seams: &[[usize; 2]],
        masses: &[f64],
        pinned: &[bool],
        settings: &SelfCollision,
        fabric: LayerFabric<T, F>,
    ) -> Self {
        let LayerFabric {
            thickness,
            friction,
            membrane_stiffness,
        } = fabric;
        let n = mesh.vertex_count();
        let half_thickness: Vec<f64> = (0..n)
            .map(|i| 0.5 * settings.thickness.unwrap_or_else(|| thickness(i)))
            .collect();
        // The largest contact distance, within which pairs are looked for.
        let reach = 2.0 * half_thickness.iter().copied().fold(0.0, f64::max);
        let topology = Topology::new(mesh, seams, rest_radius(reach));
        let friction: Vec<f64> = (0..n)
            .map(|i| settings.friction.unwrap_or_else(|| friction(i)))
            .collect();
        let thinnest = 2.0 * half_thickness.iter().copied().fold(f64::INFINITY, f64::min);
        let touch = 0.02 * thinnest;
        let pull_step = PULL_APART * thinnest;
        let tree = ConeTree::new(&topology, mesh.positions());
        Self {
            stiffness: settings
                .stiffness
                .unwrap_or(STIFFNESS_FRACTION * membrane_stiffness),
            response: response::Scratch::new(n),
            topology,
            pass_regions: Vec::new(),
            half_thickness,
            inv_mass: masses
                .iter()
                .zip(pinned)
                .map(|(m, &p)| if p { 0.0 } else { 1.0 / m })
                .collect(),
            friction,
            brake: vec![0.0; n],
            // Every particle at most: the list never grows in a step.
            braked: Vec::with_capacity(n),
            reach,
            touch,
            tree,
            contacts: Vec::new(),
            drag: Vec::new(),
            normal_stiffness: Vec::new(),
            by_particle: Vec::new(),
            by_particle_list: Vec::new(),
            contact_search: ChunkedSearch::default(),
            impact_search: ChunkedSearch::default(),
            crossed: true,
            fewest: usize::MAX,
            stale: 0,
            pull_step,
            loose_pull: false,
        }
    }

    /// Finds the contacts at the step's start (looking ahead along the motion only in an
    /// implicit step; explicit steps are too short).
    pub fn detect(&mut self, start: &StepStart<'_>) {
        let StepStart {
            x,
            v,
            pinned,
            h,
            implicit,
            par,
            ..
        } = *start;
        let step = implicit.then_some(h);
        let topo = &self.topology;
        // Two triangles' boxes, each grown by half the reach, overlap where they may be
        // within it.
        let reach = (1.0 + proximity::LOOK_AHEAD) * self.reach;
        self.tree.refit(
            |t| Aabb::of(topo.triangles[t].map(|i| x[i as usize])).inflated(0.5 * reach),
            |t| {
                let [a, b, c] = topo.triangles[t].map(|i| x[i as usize]);
                Cone::along((b - a).cross(&(c - a)))
            },
        );
        let search = Search {
            topology: topo,
            motion: Motion { start: x, end: x },
            only_dirty: false,
        };
        self.tree.plan(&search);
        let cloth = Cloth {
            topology: topo,
            x,
            v,
            h: step,
            pinned,
            half_thickness: &self.half_thickness,
            friction: &self.friction,
        };
        let tree = &self.tree;
        self.contact_search
            .run(&tree.tasks, par, &mut self.contacts, |task, found| {
                tree.triangle_pairs(task, &search, |s, t| {
                    // A triangle's own particles and edges are exempt from it.
                    if s == t {
                        return;
                    }
                    for (p, t) in owned_particles(topo, s, t).chain(owned_particles(topo, t, s)) {
                        cloth.particle_triangle(p, t, reach, found);
                    }
                    for (e, f) in owned_edge_pairs(topo, s, t) {
                        cloth.edge_edge(e, f, reach, found);
                    }
                });
            });
        let n = topo.particles();
        index_by_particle(
            &self.contacts,
            n,
            &mut self.by_particle,
            &mut self.by_particle_list,
        );
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

    /// Whether the step's contacts have friction to set after a scouting solve.
    pub fn has_friction(&self) -> bool {
        self.contacts
            .iter()
            .any(|c| c.friction > 0.0 && c.gap < c.distance)
    }

    /// The friction each particle's contacts can exert, `L_i = sum |w| mu f` over its
    /// contacts, into `brake`, from each contact's `mu f` (`f` its push) in `limits`.
    fn gather_brakes(&mut self, limits: &[f64]) {
        for &i in &self.braked {
            self.brake[i as usize] = 0.0;
        }
        self.braked.clear();
        for (c, &limit) in self.contacts.iter().zip(limits) {
            if limit == 0.0 {
                continue;
            }
            for k in 0..4 {
                let i = c.particles[k] as usize;
                if self.brake[i] == 0.0 {
                    self.braked.push(i as u32);
                }
                self.brake[i] += c.frame.weights[k].abs() * limit;
            }
        }
    }

    /// Coulomb friction for each contact as a viscous drag `c` against the two points'
    /// sliding (relative, across the normal), from the sliding `u*` that the step would
    /// end with without friction between the layers (`slide(c, inverse masses)`). Friction can take off
    /// it what the friction of every contact on the pair's particles can,
    /// `h sum_k |w_k| L_k / m_k` (see [`SelfContacts::gather_brakes`]; pinned particles do
    /// not move): a particle lies on a layer through several contacts, and each alone
    /// would take the whole layer's friction for its own. When what is left, `s`, exceeds
    /// [`SLIP_SPEED`], `c = mu f / s` ends the pair sliding at `s` against exactly `mu f`;
    /// otherwise `c = mu f / SLIP_SPEED` holds it.
    fn set_friction(&mut self, h: f64, slide: impl Fn(&Contact, &[f64]) -> f64) {
        // Each contact's limit `mu f` first, in place of its drag.
        let mut drag = std::mem::take(&mut self.drag);
        drag.clear();
        drag.extend(
            self.contacts
                .iter()
                .map(|c| c.friction * self.law(c).at(c.gap).1.max(0.0)),
        );
        self.gather_brakes(&drag);
        for (c, d) in self.contacts.iter().zip(&mut drag) {
            let brake: f64 = (0..4)
                .map(|k| {
                    let i = c.particles[k] as usize;
                    c.frame.weights[k].abs() * self.inv_mass[i] * self.brake[i]
                })
                .sum();
            *d /= (slide(c, &self.inv_mass) - h * brake).max(SLIP_SPEED);
        }
        self.drag = drag;
    }

    /// The tangential part of the pair's relative motion `u`.
    fn sliding(c: &Contact, u: Vec3) -> f64 {
        let n = c.frame.normal;
        (u - u.dot(&n) * n).norm()
    }

    /// Friction for an explicit step of length `h` from `v`, `force` every other force:
    /// the sliding without it predicted pair by pair, `u + h sum_k w_k F_k / m_k`, and the
    /// drag capped at what forward Euler integrates stably.
    pub fn explicit_friction(&mut self, v: &[Vec3], force: &[Vec3], h: f64) {
        self.set_friction(h, |c, inv_mass| {
            let pull: Vec3 = (0..4)
                .map(|k| {
                    let i = c.particles[k] as usize;
                    (c.frame.weights[k] * inv_mass[i]) * force[i]
                })
                .sum();
            Self::sliding(c, c.frame.relative(&c.gather(v)) + h * pull)
        });
        for (c, drag) in self.contacts.iter().zip(&mut self.drag) {
            // Forward Euler damps a drag c on mass m only while h c / m < 2.
            let mobility: f64 = (0..4)
                .map(|k| c.frame.weights[k].powi(2) * self.inv_mass[c.particles[k] as usize])
                .sum();
            *drag = drag.min(0.5 / (h * mobility));
        }
    }

    /// An implicit step's friction, none at first: it is set after a scouting solve
    /// ([`SelfContacts::friction_from_motion`]).
    pub fn no_friction(&mut self) {
        self.drag.clear();
        self.drag.resize(self.contacts.len(), 0.0);
    }

    /// Friction from a scouting solve of the step without it, which ended with
    /// velocities `v_end`, then brought into the system: `b += h F_f(v0)` and the
    /// couplings `A += h C` (with the repulsion's, set again). The scout's motion carries
    /// the cloth's elastic response, which a prediction from each pair's own particles'
    /// forces misses: there the pairs of a sliding sheet see forces that vary from particle
    /// to particle, and those that predict stopping hold the whole sheet.
    pub fn friction_from_motion(
        &mut self,
        v0: &[Vec3],
        v_end: &[Vec3],
        h: f64,
        b: &mut [Vec3],
        matrix: &mut BlockSparse,
    ) {
        self.set_friction(h, |c, _| Self::sliding(c, c.frame.relative(&c.gather(v_end))));
        for (c, &drag) in self.contacts.iter().zip(&self.drag) {
            let mut local = Local::<4>::default();
            add_friction_drag(&c.frame, drag, &c.gather(v0), &mut local);
            for k in 0..4 {
                b[c.particles[k] as usize] -= h * local.grad[k];
            }
        }
        self.couple(matrix, h);
    }

    /// The contacts' forces (repulsion, and friction at `v` with the drags set) added to
    /// `force`, and the repulsion's `K v` to `kv`. Returns the repulsion's energy.
    pub fn add_forces(&mut self, x: &[Vec3], v: &[Vec3], force: &mut [Vec3], kv: &mut [Vec3]) -> f64 {
        let mut energy = 0.0;
        let (mut spring, mut friction) = (Local::<4>::default(), Local::<4>::default());
        self.normal_stiffness.clear();
        for (c, &drag) in self.contacts.iter().zip(&self.drag) {
            spring.clear();
            friction.clear();
            let (xe, ve) = (c.gather(x), c.gather(v));
            let law = self.law(c);
            let stiffness = add_repulsion(&c.frame, &law, &xe, &mut spring);
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
            self.normal_stiffness.push(stiffness);
        }
        energy
    }

    /// The contacts' terms of an implicit step of length `h`, `h^2 K + h C`, as the
    /// transient couplings of `matrix` (replacing any it had, gathered for its products):
    /// each `(h^2 f' n n^T + h c P)` on its four particles by weight (the element Hessians
    /// are `w_a w_b` times these).
    pub fn couple(&self, matrix: &mut BlockSparse, h: f64) {
        matrix.clear_transient();
        for ((c, &drag), &stiffness) in self.contacts.iter().zip(&self.drag).zip(&self.normal_stiffness) {
            let nn = c.frame.normal * c.frame.normal.transpose();
            let k = (h * h * stiffness) * nn + (h * drag) * (Mat3::identity() - nn);
            let terms = (0..4)
                .filter(|&a| c.frame.weights[a] != 0.0)
                .map(|a| (c.particles[a] as usize, c.frame.weights[a] * Mat3::identity()));
            matrix.add_coupling(k, terms);
        }
        matrix.finish_transient();
    }

    /// Finds the pieces of the cloth passing through each other at `x` and makes each such
    /// pair exempt from the other (see [`Tangle`]).
    pub fn untangle(&mut self, x: &[Vec3]) -> Vec<Tangle> {
        let crossing = intersections::crossings_by_chart(&self.topology, x, |_| true);
        self.topology.set_tangled(crossing.iter().map(|&(pair, _)| pair));
        let first = self.topology.chart_triangles();
        crossing
            .into_iter()
            .map(|((a, b), n)| Tangle {
                triangles: [first[a as usize], first[b as usize]],
                crossings: n,
                released: None,
            })
            .collect()
    }

    /// Moves the cloth at `x` out of itself where it passes through itself (see
    /// `untangling`), each particle at most [`PULL_APART`] thicknesses, pinned ones not at
    /// all; returns how many edge-triangle crossings there were. Once the cloth is found
    /// clear it is not looked at again: its collision keeps it so, and the steps of a
    /// simulation that began clear allocate nothing. Nor is it once [`PULL_PATIENCE`]
    /// steps have not left fewer crossings than the fewest yet.
    ///
    /// With the loose pull on (see [`SelfContacts::set_loose_pull`]), the cloth round each
    /// crossing is loose until then.
    pub fn pull_apart(&mut self, x: &mut [Vec3]) -> usize {
        if !self.crossed {
            return 0;
        }
        let inv_mass = &self.inv_mass;
        let pairs = untangling::pull_apart(&self.topology, x, |i| inv_mass[i] == 0.0, self.pull_step);
        let crossings = pairs.len();
        if crossings < self.fewest {
            (self.fewest, self.stale) = (crossings, 0);
        } else {
            self.stale += 1;
        }
        self.crossed = crossings > 0 && self.stale < PULL_PATIENCE;
        // Loose, the cloth where it crosses is so for the next step; once the pull has
        // stopped, the collision holds what is left as it is.
        let loose: &[(usize, usize)] = if self.crossed && self.loose_pull {
            &pairs
        } else {
            &[]
        };
        self.topology.set_loose(loose, LOOSE_RINGS);
        crossings
    }

    /// Pulls the cloth out of itself again, from the crossings it has now, with the two
    /// pieces of each crossing loose round it ([`LOOSE_RINGS`]): exempt from each other
    /// there, as GarmentCode's simulator leaves the particles of edges through cloth out of
    /// its collision, and in contact with any other cloth. A collision that starts crossed
    /// holds the cloth crossed, and undid each step what the pull had moved: GarmentCode's
    /// rand_1_034 and rand_1_099 kept 2 and 4 crossings where a collar meets the shoulder,
    /// the pull stopped for want of progress; loose, they came apart. Loose cloth also
    /// slides further through itself (rand_1_091's godet: 8 crossings to 35), so this is
    /// for a caller who can keep the better of the two. Off, the pull stops, and the
    /// collision holds what crosses as it is.
    pub fn set_loose_pull(&mut self, on: bool) {
        self.loose_pull = on;
        self.crossed = on;
        (self.fewest, self.stale) = (usize::MAX, 0);
        if !on {
            self.topology.set_loose(&[], LOOSE_RINGS);
        }
    }

    /// Whether the cloth is still being pulled out of itself (see
    /// [`SelfContacts::pull_apart`]): it is not at rest while it is.
    pub fn pulling_apart(&self) -> bool {
        self.crossed
    }

    /// Whether some pieces are exempt from each other, having begun tangled.
    pub fn has_tangles(&self) -> bool {
        !self.topology.tangled().is_empty()
    }

    /// Ends the exemption of the tangled pieces that no longer pass through each other at
    /// `x`; returns a triangle of each of both pieces, for each pair released.
    pub fn release_untangled(&mut self, x: &[Vec3]) -> Vec<[usize; 2]> {
        let tangled = self.topology.tangled().to_vec();
        let involved = |c: u32| tangled.iter().any(|&(a, b)| a == c || b == c);
        let crossing = intersections::crossings_by_chart(&self.topology, x, involved);
        let still = |pair: &(u32, u32)| crossing.binary_search_by(|(p, _)| p.cmp(pair)).is_ok();
        let (kept, apart): (Vec<_>, Vec<_>) = tangled.into_iter().partition(|p| still(p));
        if apart.is_empty() {
            return Vec::new();
        }
        self.topology.set_tangled(kept);
        let first = self.topology.chart_triangles();
        apart
            .into_iter()
            .map(|(a, b)| [first[a as usize], first[b as usize]])
            .collect()
    }

    /// Makes the two sides of each of `passes` exempt from each other (and no others).
    /// Their particles must be the cloth's.
    pub fn set_passes<'a>(&mut self, passes: impl IntoIterator<Item = &'a LayerPass>) {
        let sides: Vec<[&[usize]; 2]> = passes
            .into_iter()
            .map(|p| [p.layer.as_slice(), p.side.as_slice()])
            .collect();
        self.topology.set_passes(sides.iter().copied());
        self.pass_regions = sides
            .into_iter()
            .map(|s| intersections::PassRegion::new(&self.topology, s))
            .collect();
    }

    /// How many edge-triangle pairs of the two sides of the `k`-th pass given to
    /// [`SelfContacts::set_passes`] pass through each other at `x`.
    pub fn pass_crossings(&self, k: usize, x: &[Vec3]) -> usize {
        intersections::crossings_between(&self.topology, x, &self.pass_regions[k])
    }

    /// The triangles the segment between each of `pairs` passes through at `x`, as
    /// (pair, triangle), sorted (triangles near either particle for good not counted).
    pub fn across_pairs(&self, x: &[Vec3], pairs: &[[usize; 2]]) -> Vec<(usize, usize)> {
        intersections::across_pairs(&self.topology, x, pairs)
    }

    /// Counts the intersecting edge-triangle pairs of the cloth at `x` (pairs sharing a
    /// particle, or seam partners, exempt).
    pub fn intersections(&self, x: &[Vec3]) -> Intersections {
        intersections::count(&self.topology, x)
    }

    /// The smallest distance of a particle from a triangle at `x`, if under `within`
    /// (exempt pairs as for [`SelfContacts::intersections`]).
    pub fn closest_approach(&self, x: &[Vec3], within: f64) -> Option<f64> {
        intersections::closest_approach(&self.topology, x, within)
    }
}
