//! How big a garment's mesh will be, known before anything is resampled or meshed, so that
//! a pattern in the wrong units (a panel 100 km wide) is refused at once instead of
//! filling the memory.

use crate::pattern::{Edge, Panel, Pattern};

/// The default largest mesh, in triangles: about 60 times a dress at 1.2 cm.
pub const DEFAULT_MAX_TRIANGLES: usize = 2_000_000;

/// Polyline pieces per curved edge in the area estimate.
const CURVE_PIECES: usize = 16;

/// Triangles per `h^2` of panel area. Refinement's area limit is the equilateral
/// triangle's, `sqrt(3)/4 h^2` (2.31 per `h^2`); the triangles it leaves average about 0.7
/// of that (measured on the 60 shared GarmentCode designs at 1.5 cm: the estimate below,
/// with 2.31, came to 0.66-0.88 of the count).
const TRIANGLES_PER_AREA: f64 = 3.2;

/// About how many triangles refinement to edge length `h` puts in a flat region of `area`
/// m^2 (its boundary row aside).
pub fn triangles_in(area: f64, h: f64) -> f64 {
    TRIANGLES_PER_AREA * area / (h * h)
}

/// The panel's area enclosed by its outline less its holes, m^2.
fn area(panel: &Panel) -> f64 {
    let loop_area = |edges: &[Edge]| {
        let mut points = Vec::new();
        for e in edges {
            let pieces = if matches!(e.curve, crate::pattern::Curve::Line) {
                1
            } else {
                CURVE_PIECES
            };
            let p = e.resample(pieces);
            points.extend_from_slice(&p[..p.len() - 1]);
        }
        let n = points.len();
        0.5 * (0..n)
            .map(|i| points[i].perp(&points[(i + 1) % n]))
            .sum::<f64>()
            .abs()
    };
    let holes: f64 = panel.holes.iter().map(|h| loop_area(h)).sum();
    (loop_area(&panel.outline) - holes).max(0.0)
}

/// An estimate of the triangles meshing `panel` at edge length `h` gives: its area's worth
/// plus a row along its outline (long thin panels are all boundary). Over-estimates a
/// little, never by orders of magnitude.
pub(super) fn panel_triangles(panel: &Panel, h: f64) -> f64 {
    let perimeter: f64 = panel
        .outline
        .iter()
        .chain(panel.holes.iter().flatten())
        .map(Edge::length)
        .sum();
    triangles_in(area(panel), h) + perimeter / h
}

/// The panel's extent in its own plane, m, for messages.
pub(super) fn extent(panel: &Panel) -> (f64, f64) {
    let points = panel.outline.iter().flat_map(|e| [e.start, e.end]);
    let (mut lo, mut hi) = (
        nalgebra::Vector2::repeat(f64::INFINITY),
        nalgebra::Vector2::repeat(f64::NEG_INFINITY),
    );
    for p in points {
        lo = lo.inf(&p);
        hi = hi.sup(&p);
    }
    (hi.x - lo.x, hi.y - lo.y)
}

impl Pattern {
    /// The triangles meshing the pattern at edge length `h` would give, about, and the panel
    /// that would give the most.
    pub fn estimated_triangles(&self, h: f64) -> (f64, usize) {
        let per_panel: Vec<f64> = self.panels.iter().map(|p| panel_triangles(p, h)).collect();
        let largest = (0..per_panel.len())
            .max_by(|&a, &b| per_panel[a].total_cmp(&per_panel[b]))
            .unwrap_or(0);
        (per_panel.iter().sum(), largest)
    }
}
