//! Building a surface from a mesh as users have it: refused only when it can have no
//! inside at all, otherwise repaired where that is sound and described where it is not.

use cloth_core::math::union_find::{find, union};
use cloth_core::math::Vec3;

use super::defects::SurfaceDefect;
use super::edges::{edge_groups, sorted_sides, Side};
use super::options::DEFAULT_WELD_FRACTION;
use super::orientation::{components, orient};
use super::overlap::buried_triangles;
use super::weld::{weld, Welded};
use super::{SurfaceError, SurfaceOptions, TriSurface};

/// A triangle whose doubled area is below this fraction of its longest edge squared is flat
/// to rounding: its normal means nothing.
const ZERO_AREA: f64 = 1e-12;
/// A part whose |volume| is below this fraction of its bounding-box diagonal cubed is flat
/// or folded onto itself (a 1 m plate would be under a nanometre thick).
const ZERO_VOLUME: f64 = 1e-9;

impl TriSurface {
    /// Builds a body's surface from a mesh, scaled by [`SurfaceOptions::scale`].
    ///
    /// Refused (nothing could be inside it): no triangles or vertices, a non-finite
    /// coordinate, an index out of range, every triangle of zero area, or nothing enclosed
    /// (a flat sheet). Everything else loads, with a [`SurfaceDefect`] for each kind of
    /// imperfection: open vertices within the weld distance are joined, zero-area triangles
    /// dropped, triangles turned to agree with their neighbours and inward parts outward;
    /// holes, edges of more than two triangles, parts that cannot be oriented and parts
    /// overlapping others are kept as they are, and inside/outside then comes from the
    /// generalized winding number instead of the nearest triangle. A closed 2-manifold
    /// loads exactly as given.
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
        let mut defects = Vec::new();
        let weld_distance = options
            .weld_distance
            .unwrap_or_else(|| DEFAULT_WELD_FRACTION * diagonal(&vertices));
        let Welded {
            vertices,
            triangles,
            joined,
        } = weld(&vertices, &triangles, weld_distance);
        if joined > 0 {
            defects.push(SurfaceDefect::Welded {
                vertices: joined,
                distance: weld_distance,
            });
        }
        let mut triangles = drop_degenerate(&vertices, triangles, &mut defects, weld_distance)?;
        let sides = sorted_sides(&triangles);
        edge_defects(&vertices, &sides, &mut defects);
        let orientation = orient(&mut triangles, &sides);
        if orientation.flipped > 0 {
            defects.push(SurfaceDefect::Reoriented {
                triangles: orientation.flipped,
            });
        }
        if orientation.conflicts > 0 {
            defects.push(SurfaceDefect::NonOrientable {
                edges: orientation.conflicts,
            });
        }
        let label = components(triangles.len(), &sides);
        turn_parts_outward(&vertices, &mut triangles, &label, &mut defects)?;
        let buried = buried_triangles(&vertices, &triangles, &label);
        let count = buried.iter().filter(|&&b| b).count();
        if count > 0 {
            let mut parts: Vec<usize> = (0..triangles.len())
                .filter(|&t| buried[t])
                .map(|t| label[t])
                .collect();
            parts.sort_unstable();
            parts.dedup();
            defects.push(SurfaceDefect::Overlapping {
                parts: parts.len(),
                buried: count,
            });
        }
        Ok(Self::assemble(vertices, triangles, buried, defects))
    }
}

fn diagonal(vertices: &[Vec3]) -> f64 {
    let (lo, hi) = super::measure::bounds(vertices);
    (hi - lo).norm()
}

/// Zero-area triangles carry no normal: dropped with a note, unless nothing would be left.
fn drop_degenerate(
    vertices: &[Vec3],
    triangles: Vec<[u32; 3]>,
    defects: &mut Vec<SurfaceDefect>,
    weld_distance: f64,
) -> Result<Vec<[u32; 3]>, SurfaceError> {
    let degenerate = |tri: &[u32; 3]| {
        let [p, q, r] = tri.map(|i| vertices[i as usize]);
        let doubled = (q - p).cross(&(r - p)).norm();
        let longest = [q - p, r - q, p - r]
            .iter()
            .map(|e| e.norm_squared())
            .fold(0.0, f64::max);
        // Two equal indices give exactly zero, so this also catches collapsed triangles.
        doubled <= ZERO_AREA * longest
    };
    let Some(first) = triangles.iter().position(degenerate) else {
        return Ok(triangles);
    };
    let before = triangles.len();
    let kept: Vec<[u32; 3]> = triangles.into_iter().filter(|t| !degenerate(t)).collect();
    if kept.is_empty() {
        return Err(SurfaceError::Degenerate {
            triangles: before,
            weld_distance,
        });
    }
    defects.push(SurfaceDefect::Degenerate {
        triangles: before - kept.len(),
        first,
    });
    Ok(kept)
}

/// Holes (edges of one triangle, grouped into loops) and edges of three or more.
fn edge_defects(vertices: &[Vec3], sides: &[Side], defects: &mut Vec<SurfaceDefect>) {
    let at = |i: u32| {
        let p = vertices[i as usize];
        [p.x, p.y, p.z]
    };
    let open: Vec<&Side> = edge_groups(sides)
        .filter(|g| g.len() == 1)
        .map(|g| &g[0])
        .collect();
    if !open.is_empty() {
        // Loops: the open edges' vertices joined by the open edges.
        let mut parent: Vec<u32> = (0..vertices.len() as u32).collect();
        for s in &open {
            union(&mut parent, s.lo, s.hi);
        }
        let mut perimeter = std::collections::BTreeMap::<u32, (f64, u32)>::new();
        for s in &open {
            let r = find(&mut parent, s.lo);
            let length = (vertices[s.hi as usize] - vertices[s.lo as usize]).norm();
            perimeter.entry(r).or_insert((0.0, s.lo)).0 += length;
        }
        let &(largest, through) = perimeter
            .values()
            .max_by(|a, b| a.0.total_cmp(&b.0))
            .expect("there are open edges");
        defects.push(SurfaceDefect::Holes {
            loops: perimeter.len(),
            edges: open.len(),
            perimeter: largest,
            at: at(through),
        });
    }
    let mut crowded = edge_groups(sides).filter(|g| g.len() > 2);
    if let Some(first) = crowded.next() {
        defects.push(SurfaceDefect::NonManifold {
            edges: 1 + crowded.count(),
            at: at(first[0].lo),
        });
    }
}

/// Turns each part that faces inward (negative signed volume) outward; parts enclosing
/// nothing stay as they are. Refused when no part encloses anything.
fn turn_parts_outward(
    vertices: &[Vec3],
    triangles: &mut [[u32; 3]],
    label: &[usize],
    defects: &mut Vec<SurfaceDefect>,
) -> Result<(), SurfaceError> {
    struct Part {
        first: usize,
        origin: Vec3,
        volume: f64,
        lo: Vec3,
        hi: Vec3,
    }
    let mut parts: Vec<Part> = Vec::new();
    for (t, tri) in triangles.iter().enumerate() {
        let [p, q, r] = tri.map(|i| vertices[i as usize]);
        if label[t] == parts.len() {
            // Measuring from a point on the part keeps the volume sum well conditioned.
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
    let flat: Vec<bool> = parts
        .iter()
        .map(|p| p.volume.abs() <= ZERO_VOLUME * (p.hi - p.lo).norm().powi(3))
        .collect();
    if flat.iter().all(|&f| f) {
        let largest = parts
            .iter()
            .max_by(|a, b| a.volume.abs().total_cmp(&b.volume.abs()))
            .expect("a surface has triangles");
        return Err(SurfaceError::ZeroVolume {
            triangle: largest.first,
            volume: largest.volume,
        });
    }
    let flip: Vec<bool> = parts
        .iter()
        .zip(&flat)
        .map(|(p, &f)| !f && p.volume < 0.0)
        .collect();
    let inward = flip.iter().filter(|&&f| f).count();
    if inward > 0 {
        defects.push(SurfaceDefect::Inward { parts: inward });
        for (t, tri) in triangles.iter_mut().enumerate() {
            if flip[label[t]] {
                tri.swap(1, 2);
            }
        }
    }
    let flat = flat.iter().filter(|&&f| f).count();
    if flat > 0 {
        defects.push(SurfaceDefect::Flat { parts: flat });
    }
    Ok(())
}
