//! Checks of a pattern's geometry and seams, in the order a person should fix them.

use super::{Edge, Pattern, PatternError, Point2};
use crate::meshing::encloses;

/// Two ends of consecutive edges closer than this (m) are the same point.
const CLOSURE: f64 = 1e-6;
/// The most straight pieces (a straight edge is one, a curve [`CURVE_SEGMENTS`]) a panel's
/// outline or hole may have. GarmentCode's panels have hundreds; this bounds the crossing
/// test, whose worst case (every piece overlapping every other in x) is quadratic.
const MAX_LOOP_SEGMENTS: usize = 20_000;
/// Polyline segments per curved edge in the crossing test: a crossing that only a finer
/// polyline would see is within a fraction of a millimetre of a touch, which the mesher
/// would refuse anyway.
const CURVE_SEGMENTS: usize = 48;

impl Pattern {
    /// Checks every panel (closed outlines that do not cross themselves, holes inside,
    /// drawable curves, a grain line, a finite placement) and every seam (sides that exist,
    /// no edge sewn twice, no gather beyond [`MAX_GATHER`](super::gather::MAX_GATHER)).
    /// `file` names the source in the errors.
    pub fn validate(&self, file: &str) -> Result<(), PatternError> {
        if self.panels.is_empty() {
            return Err(PatternError::Pattern {
                file: file.into(),
                reason: "the pattern has no panels".into(),
            });
        }
        for (k, panel) in self.panels.iter().enumerate() {
            if let Some(other) = self.panels[..k].iter().find(|p| p.name == panel.name) {
                return Err(PatternError::panel(
                    file,
                    &other.name,
                    None,
                    "two panels have this name",
                ));
            }
            let fail =
                |edge: Option<String>, reason: String| PatternError::panel(file, &panel.name, edge, reason);
            let name_of = |loop_name: &str, k: usize, e: &Edge| match &e.name {
                Some(n) => format!("'{n}' ({loop_name}{k})"),
                None => format!("{loop_name}{k}"),
            };
            if !(panel.grain.iter().all(|c| c.is_finite()) && panel.grain.norm() > 0.0) {
                return Err(fail(None, format!("grain {:?} is not a direction", panel.grain)));
            }
            let p = &panel.placement;
            if !p.translation.iter().all(|c| c.is_finite()) {
                return Err(fail(None, "placement translation is not finite".into()));
            }
            if let Some(w) = p.wrap {
                if !(w.radius.is_finite() && w.radius > 0.0 && w.centre.is_finite()) {
                    return Err(fail(
                        None,
                        format!("wrap radius {} must be positive and finite", w.radius),
                    ));
                }
            }
            let loops =
                std::iter::once(("", &panel.outline)).chain(panel.holes.iter().map(|h| ("hole edge ", h)));
            let mut polylines = Vec::new();
            for (loop_name, edges) in loops {
                let segments: usize = edges.iter().map(pieces).sum();
                if segments > MAX_LOOP_SEGMENTS {
                    return Err(fail(
                        None,
                        format!(
                            "a loop of {} edges ({segments} straight pieces, counting {CURVE_SEGMENTS} per curve), \
                             more than the {MAX_LOOP_SEGMENTS} pieces a panel's loop may have (is it a mesh \
                             exported as a pattern?)",
                            edges.len()
                        ),
                    ));
                }
                if edges.len() < 2 {
                    return Err(fail(
                        None,
                        format!("a loop of {} edge(s) encloses nothing", edges.len()),
                    ));
                }
                for (k, e) in edges.iter().enumerate() {
                    let name = || Some(name_of(loop_name, k, e));
                    if !(e.start.iter().chain(e.end.iter()).all(|c| c.is_finite())) {
                        return Err(fail(name(), "end points are not finite".into()));
                    }
                    e.curve.check(e.start, e.end).map_err(|r| fail(name(), r))?;
                    let next = &edges[(k + 1) % edges.len()];
                    if (next.start - e.end).norm() > CLOSURE {
                        return Err(fail(
                            name(),
                            format!("ends at {:?} but the next edge starts at {:?}", e.end, next.start),
                        ));
                    }
                    if !(e.length() > CLOSURE) {
                        return Err(fail(name(), "has zero length".into()));
                    }
                }
                let line = polyline(edges);
                if let Some((a, b)) = crossing(&line) {
                    return Err(fail(
                        Some(name_of(loop_name, a, &edges[a])),
                        format!("crosses {} of the same loop", name_of(loop_name, b, &edges[b])),
                    ));
                }
                if signed_area(&line).abs() <= CLOSURE * CLOSURE {
                    return Err(fail(None, "a loop encloses no area".into()));
                }
                polylines.push(line);
            }
            let outline: Vec<Point2> = polylines[0].iter().map(|(p, _)| *p).collect();
            for (h, hole) in polylines.iter().enumerate().skip(1) {
                let inside = hole.iter().all(|(p, _)| encloses(&outline, *p));
                if !inside || crosses(&polylines[0], hole) {
                    return Err(fail(None, format!("hole {} is not inside the outline", h - 1)));
                }
            }
        }
        let mut sewn: Vec<Vec<Option<usize>>> =
            self.panels.iter().map(|p| vec![None; p.outline.len()]).collect();
        for (s, seam) in self.seams.iter().enumerate() {
            for side in [&seam.a, &seam.b] {
                let Some(panel) = self.panels.get(side.panel) else {
                    return Err(PatternError::seam(
                        file,
                        s,
                        format!("panel {} does not exist", side.panel),
                    ));
                };
                if side.edge >= panel.outline.len() {
                    return Err(PatternError::seam(
                        file,
                        s,
                        format!("panel '{}' has no edge {}", panel.name, side.edge),
                    ));
                }
                if let Some(first) = sewn[side.panel][side.edge].replace(s) {
                    return Err(PatternError::seam(
                        file,
                        s,
                        format!("{} is already sewn by seam {first}", self.describe(side)),
                    ));
                }
            }
        }
        for attached in &self.attachments {
            let side = &attached.edge;
            let Some(panel) = self
                .panels
                .get(side.panel)
                .filter(|p| side.edge < p.outline.len())
            else {
                return Err(PatternError::Pattern {
                    file: file.into(),
                    reason: format!(
                        "an attachment names panel {}, edge {}, which does not exist",
                        side.panel, side.edge
                    ),
                });
            };
            let d = attached.direction;
            if !(d.iter().all(|c| c.is_finite()) && (d.norm() - 1.0).abs() < 1e-9) {
                return Err(PatternError::panel(
                    file,
                    &panel.name,
                    Some(side.edge.to_string()),
                    format!(
                        "the edge's attachment direction ({}, {}, {}) is not a unit vector",
                        d.x, d.y, d.z
                    ),
                ));
            }
        }
        if let Some(g) = self.gathers().into_iter().find(super::Gather::excessive) {
            return Err(PatternError::seam(
                file,
                g.seam,
                format!(
                    "{} is {:.1} cm long on one side and {:.1} cm on the other: a gather of {:.1}:1, beyond \
                     the {:.0}:1 a seam can gather (is a side sewn to the wrong edge?)",
                    g.name,
                    100.0 * g.long,
                    100.0 * g.short,
                    g.ratio(),
                    super::gather::MAX_GATHER
                ),
            ));
        }
        Ok(())
    }
}

/// Straight pieces of an edge in the crossing test.
fn pieces(e: &Edge) -> usize {
    match e.curve {
        super::Curve::Line => 1,
        _ => CURVE_SEGMENTS,
    }
}

/// The loop as points, each tagged with the edge its following segment belongs to.
fn polyline(edges: &[Edge]) -> Vec<(Point2, usize)> {
    let mut out = Vec::new();
    for (k, e) in edges.iter().enumerate() {
        let n = pieces(e);
        let points = e.curve.resample(e.start, e.end, n);
        out.extend(points[..n].iter().map(|&p| (p, k)));
    }
    out
}

/// Segment `i` of a closed polyline, as its ends.
fn segment(line: &[(Point2, usize)], i: usize) -> (Point2, Point2) {
    (line[i].0, line[(i + 1) % line.len()].0)
}

/// The pairs of segments (index in `a`, index in `b`) whose x ranges overlap, in no
/// particular order but the same every time: a sweep over the segments sorted by their
/// left ends, so that outlines of many short segments are checked in near-linear time.
fn overlapping_in_x(
    a: &[(Point2, usize)],
    b: &[(Point2, usize)],
    mut visit: impl FnMut(usize, usize) -> bool,
) -> bool {
    let span = |line: &[(Point2, usize)], i: usize| {
        let (p, q) = segment(line, i);
        (p.x.min(q.x), p.x.max(q.x))
    };
    // (left, right, which line, index)
    let mut events: Vec<(f64, f64, bool, usize)> = (0..a.len())
        .map(|i| {
            let (l, r) = span(a, i);
            (l, r, false, i)
        })
        .chain((0..b.len()).map(|j| {
            let (l, r) = span(b, j);
            (l, r, true, j)
        }))
        .collect();
    events.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.2.cmp(&y.2)).then(x.3.cmp(&y.3)));
    for (k, &(_, right, from_b, i)) in events.iter().enumerate() {
        for &(left, _, other_b, j) in &events[k + 1..] {
            if left > right {
                break;
            }
            if from_b == other_b {
                continue;
            }
            let (ia, jb) = if from_b { (j, i) } else { (i, j) };
            if visit(ia, jb) {
                return true;
            }
        }
    }
    false
}

/// The edges of the first pair of non-adjacent segments that cross or touch (the pair
/// with the smallest first segment, then second).
fn crossing(line: &[(Point2, usize)]) -> Option<(usize, usize)> {
    let n = line.len();
    let mut first: Option<(usize, usize)> = None;
    overlapping_in_x(line, line, |i, j| {
        let (i, j) = (i.min(j), i.max(j));
        let adjacent = j <= i + 1 || (i == 0 && j == n - 1);
        if !adjacent && first.is_none_or(|f| (i, j) < f) {
            let ((a, b), (c, d)) = (segment(line, i), segment(line, j));
            if segments_meet(a, b, c, d) {
                first = Some((i, j));
            }
        }
        false
    });
    first.map(|(i, j)| (line[i].1, line[j].1))
}

fn crosses(a: &[(Point2, usize)], b: &[(Point2, usize)]) -> bool {
    overlapping_in_x(a, b, |i, j| {
        let ((p, q), (r, s)) = (segment(a, i), segment(b, j));
        segments_meet(p, q, r, s)
    })
}

fn cross(o: Point2, a: Point2, b: Point2) -> f64 {
    (a - o).perp(&(b - o))
}

/// Closed segments ab and cd share a point.
fn segments_meet(a: Point2, b: Point2, c: Point2, d: Point2) -> bool {
    let (d1, d2) = (cross(c, d, a), cross(c, d, b));
    let (d3, d4) = (cross(a, b, c), cross(a, b, d));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    let on = |p: Point2, q: Point2, r: Point2, side: f64| {
        side == 0.0
            && r.x >= p.x.min(q.x)
            && r.x <= p.x.max(q.x)
            && r.y >= p.y.min(q.y)
            && r.y <= p.y.max(q.y)
    };
    on(c, d, a, d1) || on(c, d, b, d2) || on(a, b, c, d3) || on(a, b, d, d4)
}

fn signed_area(line: &[(Point2, usize)]) -> f64 {
    let n = line.len();
    0.5 * (0..n).map(|i| line[i].0.perp(&line[(i + 1) % n].0)).sum::<f64>()
}
