//! Building a surface: the checks, in the order a user should fix them.

use cloth_core::Vec3;

use super::edges::{edge_groups, sorted_sides, Side};
use super::options::DEFAULT_WELD_FRACTION;
use super::weld::{weld, Welded};
use super::{SurfaceError, SurfaceOptions, TriSurface};

/// A triangle whose doubled area is below this fraction of its longest edge squared is flat
/// to rounding: its normal means nothing.
const ZERO_AREA: f64 = 1e-12;
/// A component whose |volume| is below this fraction of its bounding-box diagonal cubed is
/// flat or folded onto itself (a 1 m plate would be under a nanometre thick).
const ZERO_VOLUME: f64 = 1e-9;

impl TriSurface {
    /// Validates, scales and welds a mesh into a surface.
    ///
    /// Checks, in order: options; empty (no triangles, no vertices); non-finite coordinate;
    /// index out of range; then after welding: zero-area triangle (nothing is dropped
    /// silently), non-manifold edge, open edge, inconsistent orientation, and the signed
    /// volume of each closed component (inward ones are flipped when
    /// [`SurfaceOptions::flip_inward`] is set).
    pub fn new(
        mut vertices: Vec<Vec3>,
        triangles: Vec<[u32; 3]>,
        options: &SurfaceOptions,
    ) -> Result<Self, SurfaceError> {
        options.check()?;
        if triangles.is_empty() {
            return Err(SurfaceError::Empty {
                what: "triangles".into(),
            });
        }
        if vertices.is_empty() {
            return Err(SurfaceError::Empty {
                what: "vertices".into(),
            });
        }
        for (vertex, p) in vertices.iter_mut().enumerate() {
            *p *= options.scale;
            if let Some(&value) = p.iter().find(|c| !c.is_finite()) {
                return Err(SurfaceError::NonFinite { vertex, value });
            }
        }
        for (triangle, tri) in triangles.iter().enumerate() {
            if let Some(&index) = tri.iter().find(|&&i| i as usize >= vertices.len()) {
                return Err(SurfaceError::IndexOutOfRange {
                    triangle,
                    index: index as usize,
                    count: vertices.len(),
                });
            }
        }
        let weld_distance = options
            .weld_distance
            .unwrap_or_else(|| DEFAULT_WELD_FRACTION * diagonal(&vertices));
        let mesh = weld(&vertices, &triangles, weld_distance);
        check_areas(&mesh, weld_distance)?;
        let sides = sorted_sides(&mesh.triangles);
        check_edges(&mesh, &sides)?;
        let Welded {
            vertices,
            mut triangles,
            ..
        } = mesh;
        orient_components(&vertices, &mut triangles, &sides, options.flip_inward)?;
        Ok(Self { vertices, triangles })
    }
}

fn diagonal(vertices: &[Vec3]) -> f64 {
    let (lo, hi) = super::measure::bounds(vertices);
    (hi - lo).norm()
}

fn check_areas(mesh: &Welded, weld_distance: f64) -> Result<(), SurfaceError> {
    for (triangle, tri) in mesh.triangles.iter().enumerate() {
        let [p, q, r] = tri.map(|i| mesh.vertices[i as usize]);
        let doubled = (q - p).cross(&(r - p)).norm();
        let longest = [q - p, r - q, p - r]
            .iter()
            .map(|e| e.norm_squared())
            .fold(0.0, f64::max);
        // Two equal indices give exactly zero, so this also catches collapsed triangles.
        if doubled <= ZERO_AREA * longest {
            return Err(SurfaceError::Degenerate {
                triangle,
                area: 0.5 * doubled,
                weld_distance,
            });
        }
    }
    Ok(())
}

/// Non-manifold, then open, then inconsistent: each later check assumes the earlier passed.
fn check_edges(mesh: &Welded, sides: &[Side]) -> Result<(), SurfaceError> {
    let ends = |s: &Side| {
        let at = |i: u32| {
            let p = mesh.vertices[i as usize];
            [p.x, p.y, p.z]
        };
        (
            mesh.original[s.lo as usize],
            mesh.original[s.hi as usize],
            at(s.lo),
            at(s.hi),
        )
    };
    if let Some(group) = edge_groups(sides).find(|g| g.len() > 2) {
        let (a, b, a_at, b_at) = ends(&group[0]);
        return Err(SurfaceError::NonManifold {
            a,
            b,
            count: group.len(),
            a_at,
            b_at,
        });
    }
    let boundary_edges = edge_groups(sides).filter(|g| g.len() == 1).count();
    if let Some(group) = edge_groups(sides).find(|g| g.len() == 1) {
        let (a, b, a_at, b_at) = ends(&group[0]);
        return Err(SurfaceError::Open {
            a,
            b,
            boundary_edges,
            a_at,
            b_at,
        });
    }
    if let Some(group) = edge_groups(sides).find(|g| g[0].forward == g[1].forward) {
        let (a, b, a_at, b_at) = ends(&group[0]);
        return Err(SurfaceError::Inconsistent { a, b, a_at, b_at });
    }
    Ok(())
}

/// Labels triangles by edge-connected component, labels numbered in order of first triangle.
pub(super) fn components(triangle_count: usize, sides: &[Side]) -> Vec<usize> {
    let mut parent: Vec<usize> = (0..triangle_count).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for group in edge_groups(sides) {
        for pair in group.windows(2) {
            let (a, b) = (
                root(&mut parent, pair[0].triangle as usize),
                root(&mut parent, pair[1].triangle as usize),
            );
            parent[a.max(b)] = a.min(b);
        }
    }
    let mut label = vec![usize::MAX; triangle_count];
    let mut count = 0;
    (0..triangle_count)
        .map(|t| {
            let r = root(&mut parent, t);
            if label[r] == usize::MAX {
                label[r] = count;
                count += 1;
            }
            label[r]
        })
        .collect()
}

/// Each closed component must enclose positive volume on its own: a table of five boxes is
/// fine, but one box turned inside out among them is not.
fn orient_components(
    vertices: &[Vec3],
    triangles: &mut [[u32; 3]],
    sides: &[Side],
    flip_inward: bool,
) -> Result<(), SurfaceError> {
    struct Part {
        first: usize,
        origin: Vec3,
        volume: f64,
        lo: Vec3,
        hi: Vec3,
    }
    let label = components(triangles.len(), sides);
    let mut parts: Vec<Part> = Vec::new();
    for (t, tri) in triangles.iter().enumerate() {
        let [p, q, r] = tri.map(|i| vertices[i as usize]);
        if label[t] == parts.len() {
            // Measuring from a point on the component keeps the volume sum well conditioned.
            parts.push(Part {
                first: t,
                origin: p,
                volume: 0.0,
                lo: p,
                hi: p,
            });
        }
        let part = &mut parts[label[t]];
        for x in [p, q, r] {
            part.lo = part.lo.inf(&x);
            part.hi = part.hi.sup(&x);
        }
        let (p, q, r) = (p - part.origin, q - part.origin, r - part.origin);
        part.volume += p.dot(&q.cross(&r)) / 6.0;
    }
    let mut flip = vec![false; parts.len()];
    for (k, part) in parts.iter().enumerate() {
        if part.volume.abs() <= ZERO_VOLUME * (part.hi - part.lo).norm().powi(3) {
            return Err(SurfaceError::ZeroVolume {
                triangle: part.first,
                volume: part.volume,
            });
        }
        if part.volume < 0.0 {
            if !flip_inward {
                return Err(SurfaceError::Inward {
                    triangle: part.first,
                    volume: part.volume,
                });
            }
            flip[k] = true;
        }
    }
    for (t, tri) in triangles.iter_mut().enumerate() {
        if flip[label[t]] {
            tri.swap(1, 2);
        }
    }
    Ok(())
}
