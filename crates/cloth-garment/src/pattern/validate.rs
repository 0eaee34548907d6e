//! Checks of a pattern's geometry and seams, in the order a person should fix them.

use super::{Edge, Pattern, PatternError, Point2};
use crate::meshing::encloses;

/// Two ends of consecutive edges closer than this (m) are the same point.
const CLOSURE: f64 = 1e-6;
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

/// The loop as points, each tagged with the edge its following segment belongs to.
fn polyline(edges: &[Edge]) -> Vec<(Point2, usize)> {
    let mut out = Vec::new();
    for (k, e) in edges.iter().enumerate() {
        let pieces = match e.curve {
            super::Curve::Line => 1,
            _ => CURVE_SEGMENTS,
        };
        let points = e.curve.resample(e.start, e.end, pieces);
        out.extend(points[..pieces].iter().map(|&p| (p, k)));
    }
    out
}

/// The edges of the first pair of non-adjacent segments that cross or touch.
fn crossing(line: &[(Point2, usize)]) -> Option<(usize, usize)> {
    let n = line.len();
    for i in 0..n {
        for j in i + 2..n {
            if i == 0 && j == n - 1 {
                continue;
            }
            let (a, b) = (line[i].0, line[(i + 1) % n].0);
            let (c, d) = (line[j].0, line[(j + 1) % n].0);
            if segments_meet(a, b, c, d) {
                return Some((line[i].1, line[j].1));
            }
        }
    }
    None
}

fn crosses(a: &[(Point2, usize)], b: &[(Point2, usize)]) -> bool {
    (0..a.len()).any(|i| {
        (0..b.len()).any(|j| segments_meet(a[i].0, a[(i + 1) % a.len()].0, b[j].0, b[(j + 1) % b.len()].0))
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
