//! A pattern made into cloth: its panels meshed, placed around the body, and the seam
//! vertices paired one to one, ready to be sewn.

mod gathering;
mod layers;
mod placement_check;
mod ring;
mod error;
mod size;
mod touching;
mod weld;

pub use error::{GarmentError, HeldOpen};
pub use layers::Layers;
pub use placement_check::PlacementWarning;
pub use ring::{closing_said, Ring};
pub use size::{triangles_in, DEFAULT_MAX_TRIANGLES};
pub use touching::{Touching, TOUCH};
pub use weld::Welded;

use crate::meshing::mesh_region;
use crate::pattern::{BodyPart, Edge, Pattern, SeamOrientation};
use cloth_core::{math::Vec3, ClothMesh, PassThrough};
use nalgebra::Rotation2;

/// The default target edge length, m: about 6,000 particles for a dress.
pub const DEFAULT_EDGE_LENGTH: f64 = 0.015;
/// The most a curved edge turns over one boundary segment, radians (15 degrees).
pub const MAX_TURN: f64 = std::f64::consts::PI / 12.0;

/// Turns a [`Pattern`] into a [`Garment`].
#[derive(Debug, Clone)]
pub struct GarmentBuilder {
    pattern: Pattern,
    edge_length: f64,
    max_triangles: usize,
    file: String,
}

/// One seam of the garment: its vertex pairs in order along side a.
#[derive(Debug, Clone, PartialEq)]
pub struct SeamPairs {
    /// "panel 'front', edge 'side' (1) to panel 'back', edge 'side' (3)".
    pub name: String,
    pub pairs: Vec<[usize; 2]>,
}

/// The pattern's panels as one unsewn mesh (each panel its own piece, placed in 3D, with
/// its material coordinates turned to its grain line), and the seams' vertex pairs.
#[derive(Debug, Clone)]
pub struct Garment {
    pub mesh: ClothMesh,
    pub seams: Vec<SeamPairs>,
    /// The panel of each triangle.
    pub triangle_panel: Vec<usize>,
    pub panel_names: Vec<String>,
    /// The fabric preset named by each panel, if any.
    pub panel_fabrics: Vec<Option<String>>,
    /// The part of the body each panel dresses, if said.
    pub panel_dresses: Vec<Option<BodyPart>>,
    /// The triangles along the longer side of seams whose sides differ, gathered onto the
    /// shorter: they are sewn slack in compression (see [`gathering`]).
    pub gathered: Vec<usize>,
    /// The panels placed through a thin part of a body, to pass through it while sewn (see
    /// [`Garment::move_out_of`]).
    pub passing: Vec<PassThrough>,
    /// Particle pairs of different panels touching at the start where no seam joins them
    /// (see [`Garment::find_touching`]).
    pub touching: Vec<[usize; 2]>,
    /// The particles of each of the pattern's attached edges, with the way the edge is free
    /// to move (see [`crate::pattern::AttachedEdge`]).
    pub attached: Vec<(Vec<usize>, Vec3)>,
    /// The mesh vertices along each panel's outline edges, start to end.
    pub edge_vertices: Vec<Vec<Vec<usize>>>,
    /// Vertices pinned where the sewing leaves them, for the whole drape (see
    /// [`Garment::pin`]), ascending.
    pub pinned: Vec<usize>,
}

impl GarmentBuilder {
    pub fn new(pattern: Pattern) -> Self {
        Self {
            pattern,
            edge_length: DEFAULT_EDGE_LENGTH,
            max_triangles: DEFAULT_MAX_TRIANGLES,
            file: "pattern".into(),
        }
    }
    /// Target edge length of the mesh, m.
    pub fn edge_length(mut self, h: f64) -> Self {
        self.edge_length = h;
        self
    }
    /// The largest mesh to make, in triangles: a pattern that would give more is refused
    /// before anything is meshed.
    pub fn max_triangles(mut self, n: usize) -> Self {
        self.max_triangles = n;
        self
    }
    /// The pattern's source, named in errors.
    pub fn file(mut self, file: impl Into<String>) -> Self {
        self.file = file.into();
        self
    }

    /// Resamples every edge (both sides of a seam with the same count), meshes each panel,
    /// places it and pairs the seam vertices.
    pub fn build(self) -> Result<Garment, GarmentError> {
        let Self {
            pattern,
            edge_length: h,
            max_triangles,
            file,
        } = self;
        if !(h.is_finite() && h > 0.0) {
            return Err(GarmentError::Parameter {
                name: "edge_length",
                value: h,
                expected: "a positive length in m",
            });
        }
        pattern.validate(&file)?;
        let (triangles, largest) = pattern.estimated_triangles(h);
        if triangles > max_triangles as f64 {
            let panel = &pattern.panels[largest];
            let (width, height) = size::extent(panel);
            return Err(GarmentError::TooLarge {
                file,
                panel: panel.name.clone(),
                width,
                height,
                edge_length: h,
                triangles,
                limit: max_triangles,
            });
        }
        // Pieces per outline edge: a seam's sides share the larger count.
        // At the target length, or finer where the edge turns fast (a tight armhole or
        // neckline keeps its shape on a coarse mesh); refinement's angle limit then grades
        // the mesh from the fine boundary to the interior.
        let pieces_of = |e: &Edge| {
            let by_length = (e.length() / h).round() as usize;
            let by_turn = (e.turning() / MAX_TURN).ceil() as usize;
            by_length.max(by_turn).max(1)
        };
        let mut pieces: Vec<Vec<usize>> = pattern
            .panels
            .iter()
            .map(|p| p.outline.iter().map(pieces_of).collect())
            .collect();
        for seam in &pattern.seams {
            let n = pieces[seam.a.panel][seam.a.edge].max(pieces[seam.b.panel][seam.b.edge]);
            pieces[seam.a.panel][seam.a.edge] = n;
            pieces[seam.b.panel][seam.b.edge] = n;
        }

        let (mut positions, mut uv, mut triangles) = (Vec::new(), Vec::new(), Vec::new());
        let mut triangle_panel = Vec::new();
        // Mesh vertices along each outline edge, start to end.
        let mut edge_vertices: Vec<Vec<Vec<usize>>> = Vec::with_capacity(pattern.panels.len());
        for (p, panel) in pattern.panels.iter().enumerate() {
            let mut outline = Vec::new();
            let mut starts = Vec::with_capacity(panel.outline.len());
            for (e, edge) in panel.outline.iter().enumerate() {
                starts.push(outline.len());
                let points = edge.resample(pieces[p][e]);
                outline.extend_from_slice(&points[..points.len() - 1]);
            }
            let mut loops = vec![outline];
            for hole in &panel.holes {
                let mut l = Vec::new();
                for edge in hole {
                    let points = edge.resample(pieces_of(edge));
                    l.extend_from_slice(&points[..points.len() - 1]);
                }
                loops.push(l);
            }
            let region = mesh_region(&loops, &[], h).map_err(|e| GarmentError::Meshing {
                file: file.clone(),
                panel: panel.name.clone(),
                source: e,
            })?;
            let offset = positions.len();
            let turn = Rotation2::new(-panel.grain.y.atan2(panel.grain.x));
            for q in &region.uv {
                positions.push(panel.placement.place(*q));
                uv.push(turn * q);
            }
            triangles.extend(region.triangles.iter().map(|t| t.map(|i| i + offset)));
            triangle_panel.extend(std::iter::repeat_n(p, region.triangles.len()));
            let ring = &region.loop_vertices[0];
            edge_vertices.push(
                (0..panel.outline.len())
                    .map(|e| {
                        (0..=pieces[p][e])
                            .map(|k| offset + ring[(starts[e] + k) % ring.len()])
                            .collect()
                    })
                    .collect(),
            );
        }
        let mesh = ClothMesh::new(positions, uv, triangles).map_err(|source| GarmentError::Mesh {
            what: "the meshed panels",
            source,
        })?;

        let mut seams = Vec::with_capacity(pattern.seams.len());
        for seam in &pattern.seams {
            let a = &edge_vertices[seam.a.panel][seam.a.edge];
            let b = &edge_vertices[seam.b.panel][seam.b.edge];
            let x = mesh.positions();
            let spread = |b: &mut dyn Iterator<Item = &usize>| -> f64 {
                a.iter().zip(b).map(|(&i, &j)| (x[i] - x[j]).norm()).sum()
            };
            let same = match seam.orientation {
                SeamOrientation::Same => true,
                SeamOrientation::Opposite => false,
                SeamOrientation::Auto => spread(&mut b.iter()) < spread(&mut b.iter().rev()),
            };
            let pairs = (0..a.len())
                .map(|k| [a[k], if same { b[k] } else { b[b.len() - 1 - k] }])
                // A dart's legs meet at its tip, which pairs with itself.
                .filter(|[i, j]| i != j)
                .collect();
            seams.push(SeamPairs {
                name: format!("{} to {}", pattern.describe(&seam.a), pattern.describe(&seam.b)),
                pairs,
            });
        }
        let attached = pattern
            .attachments
            .iter()
            .map(|a| (edge_vertices[a.edge.panel][a.edge.edge].clone(), a.direction))
            .collect();
        let gathered = gathering::gathered_triangles(&mesh, &seams);
        Ok(Garment {
            mesh,
            seams,
            triangle_panel,
            panel_names: pattern.panels.iter().map(|p| p.name.clone()).collect(),
            panel_fabrics: pattern.panels.iter().map(|p| p.fabric.clone()).collect(),
            panel_dresses: pattern.panels.iter().map(|p| p.dresses).collect(),
            gathered,
            passing: Vec::new(),
            touching: Vec::new(),
            attached,
            edge_vertices,
            pinned: Vec::new(),
        })
    }
}

impl Garment {
    /// Every seam's vertex pairs in one list.
    pub fn seam_pairs(&self) -> Vec<[usize; 2]> {
        self.seams.iter().flat_map(|s| s.pairs.iter().copied()).collect()
    }

    /// The length of seam each pair of [`Garment::seam_pairs`] stands for in the flat
    /// cloth, m, in the same order: half the way to its neighbours along each side, the
    /// shorter side's (a gathered side is drawn in onto the other). GarmentCode's outlines
    /// have edges of a millimetre or two, whose particles are a hundredth the mass of the
    /// others: pulled as hard as a pair on a whole cell, they were thrown at 2 m/s in the
    /// first step of sewing.
    pub fn seam_shares(&self) -> Vec<f64> {
        let uv = self.mesh.uv();
        let mut shares = Vec::new();
        for seam in &self.seams {
            let n = seam.pairs.len();
            let side = |k: usize, s: usize| {
                let at = |j: usize| uv[seam.pairs[j][s]];
                let before = if k > 0 { (at(k) - at(k - 1)).norm() } else { 0.0 };
                let after = if k + 1 < n {
                    (at(k + 1) - at(k)).norm()
                } else {
                    0.0
                };
                0.5 * (before + after)
            };
            shares.extend((0..n).map(|k| side(k, 0).min(side(k, 1))));
        }
        shares
    }

    /// The panel of each particle (before sewing, each is of one panel).
    pub(crate) fn particle_panels(&self) -> Vec<usize> {
        let mut panel = vec![0; self.mesh.vertex_count()];
        for (t, tri) in self.mesh.triangles().iter().enumerate() {
            for &i in tri {
                panel[i] = self.triangle_panel[t];
            }
        }
        panel
    }

    /// The particles of each panel (before sewing, each is of one panel).
    /// Pins an outline edge of a panel (`Some(side)`) or a whole panel (`None` edge of
    /// `side.panel`): held where the sewing leaves them, for the whole drape. They are
    /// not held while sewn, which moves them with their seams. Returns how many vertices
    /// were pinned; a side the garment does not have pins none.
    pub fn pin(&mut self, panel: usize, edge: Option<usize>) -> usize {
        let vertices: Vec<usize> = match edge {
            Some(e) => self
                .edge_vertices
                .get(panel)
                .and_then(|edges| edges.get(e))
                .cloned()
                .unwrap_or_default(),
            None => self.panel_members().into_iter().nth(panel).unwrap_or_default(),
        };
        let count = vertices.len();
        self.pinned.extend(vertices);
        self.pinned.sort_unstable();
        self.pinned.dedup();
        count
    }

    pub(crate) fn panel_members(&self) -> Vec<Vec<usize>> {
        let mut members = vec![Vec::new(); self.panel_names.len()];
        let mut seen = vec![false; self.mesh.vertex_count()];
        for (t, tri) in self.mesh.triangles().iter().enumerate() {
            for &i in tri {
                if !std::mem::replace(&mut seen[i], true) {
                    members[self.triangle_panel[t]].push(i);
                }
            }
        }
        members
    }

    /// Each panel's outward unit normal. Panels face out of the garment (+z of their
    /// frames), and their triangles are wound counter-clockwise seen from the front: the
    /// area-weighted normal points out.
    pub(crate) fn panel_facing(&self) -> Vec<Vec3> {
        let x = self.mesh.positions();
        let mut facing = vec![Vec3::zeros(); self.panel_names.len()];
        for (t, tri) in self.mesh.triangles().iter().enumerate() {
            let [a, b, c] = tri.map(|i| x[i]);
            facing[self.triangle_panel[t]] += (b - a).cross(&(c - a));
        }
        facing
            .iter()
            .map(|n| n.try_normalize(1e-12).unwrap_or(Vec3::x()))
            .collect()
    }

    /// The seam with the widest gap at `positions`, and that gap, m (checked every
    /// sewing step, so it allocates nothing).
    pub fn widest_gap(&self, positions: &[Vec3]) -> (usize, f64) {
        let (seam, _, gap) = self.widest_pair(positions);
        (seam, gap)
    }

    /// The pair of particles farthest apart at `positions`, its seam and its gap, m (seam
    /// 0 and no pair, gap 0, for a garment without seams).
    pub fn widest_pair(&self, positions: &[Vec3]) -> (usize, Option<[usize; 2]>, f64) {
        // Compared squared: one square root per call, not per pair.
        let mut widest = (0, None, 0.0);
        for (s, seam) in self.seams.iter().enumerate() {
            for &[a, b] in &seam.pairs {
                let gap2 = (positions[a] - positions[b]).norm_squared();
                if widest.1.is_none() || gap2 > widest.2 {
                    widest = (s, Some([a, b]), gap2);
                }
            }
        }
        (widest.0, widest.1, widest.2.sqrt())
    }
}
