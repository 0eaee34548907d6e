//! What loading found wrong with a mesh and how it was dealt with: the warnings a body
//! loads with. Nothing here is fatal; [`SurfaceError`](super::SurfaceError) is for what
//! gives no inside at all.

/// One kind of imperfection found in a body's mesh, with what was done about it.
#[derive(Debug, Clone, PartialEq)]
pub enum SurfaceDefect {
    /// Vertices on open edges lying within `distance` (m) of each other were joined
    /// (STL repeats every corner; exporters split vertices along texture seams).
    Welded { vertices: usize, distance: f64 },
    /// Zero-area triangles were dropped; `first` is the first one as given.
    Degenerate { triangles: usize, first: usize },
    /// Open edges: `loops` holes bounded by `edges` edges; the largest runs `perimeter` m
    /// round, passing through `at`.
    Holes {
        loops: usize,
        edges: usize,
        perimeter: f64,
        at: [f64; 3],
    },
    /// Edges shared by more than two triangles, one of them at `at`.
    NonManifold { edges: usize, at: [f64; 3] },
    /// Triangles turned round to agree with their neighbours.
    Reoriented { triangles: usize },
    /// Edges along which no orientation agrees on both sides (a Moebius-like part).
    NonOrientable { edges: usize },
    /// Closed parts that faced inward, turned outward.
    Inward { parts: usize },
    /// Parts enclosing no volume (a sheet, a part folded onto itself): they stay as thin
    /// walls, with no inside of their own.
    Flat { parts: usize },
    /// Parts overlapping others (arms through a torso, eyes in a head): `buried`
    /// triangles inside other parts take no part in contact.
    Overlapping { parts: usize, buried: usize },
}

impl SurfaceDefect {
    /// Whether the surface is still watertight with this defect repaired, so that the
    /// nearest triangle alone tells inside from outside.
    pub fn keeps_watertight(&self) -> bool {
        matches!(
            self,
            Self::Welded { .. } | Self::Degenerate { .. } | Self::Reoriented { .. } | Self::Inward { .. }
        )
    }
}

fn at(p: &[f64; 3]) -> String {
    format!("({:.3}, {:.3}, {:.3}) m", p[0], p[1], p[2])
}

impl std::fmt::Display for SurfaceDefect {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Welded { vertices, distance } => write!(
                f,
                "{vertices} vertices on open edges joined to others within {distance:.1e} m, closing the surface"
            ),
            Self::Degenerate { triangles, first } => write!(
                f,
                "{triangles} zero-area triangles dropped (the first is triangle {first})"
            ),
            Self::Holes {
                loops,
                edges,
                perimeter,
                at: p,
            } => write!(
                f,
                "{loops} holes ({edges} open edges; the largest {:.1} cm round, at {}): inside and \
                 outside come from the winding number",
                100.0 * perimeter,
                at(p)
            ),
            Self::NonManifold { edges, at: p } => write!(
                f,
                "{edges} edges shared by more than two triangles (one at {}): inside and outside \
                 come from the winding number",
                at(p)
            ),
            Self::Reoriented { triangles } => {
                write!(f, "{triangles} triangles turned round to face the same way as their neighbours")
            }
            Self::NonOrientable { edges } => write!(
                f,
                "{edges} edges where the two triangles cannot face the same way: inside and outside \
                 come from the winding number"
            ),
            Self::Inward { parts } => write!(f, "{parts} closed parts faced inward and were turned outward"),
            Self::Flat { parts } => write!(
                f,
                "{parts} parts enclose no volume (a sheet, or folded onto themselves): the cloth \
                 meets them as thin walls"
            ),
            Self::Overlapping { parts, buried } => write!(
                f,
                "{parts} parts overlap others: {buried} triangles inside other parts are left out \
                 of contact, and inside and outside come from the winding number"
            ),
        }
    }
}
