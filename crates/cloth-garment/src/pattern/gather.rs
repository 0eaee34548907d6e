//! Seams whose sides differ in length: the longer side is gathered onto the shorter, as
//! GarmentCode and pattern CAD write skirts into waistbands, sleeves into cuffs, ruffles.

use super::{Pattern, SeamSide};

/// Sides differing by up to this fraction of the longer are ease, sewn without comment.
pub const EASE: f64 = 0.10;
/// The largest gather, longer side over shorter, that a seam may have. GarmentCode's design
/// space gathers at most 3:1 by one parameter (a sleeve cuff's `top_ruffle`), and its 60
/// sampled designs gather at most 2.4:1 (sleeves into cuffs); a seam beyond 5:1 is far
/// more likely a side sewn to the wrong edge than a ruffle, and would pack five layers of
/// cloth into every cell along the seam.
pub const MAX_GATHER: f64 = 5.0;
/// A gather whose longer side exceeds the shorter by less than this (m) is a drafting
/// detail (GarmentCode pairs 1 mm edges that differ by half a millimetre) that a mesh cell
/// absorbs: never refused, whatever its ratio.
pub const SMALL_EXCESS: f64 = 0.01;

/// A seam whose longer side is gathered onto the shorter.
#[derive(Debug, Clone, PartialEq)]
pub struct Gather {
    /// The seam's number in the pattern (from 0, in file order).
    pub seam: usize,
    /// "panel 'skirt', edge 3 to panel 'waistband', edge 1".
    pub name: String,
    /// Arc lengths of the longer and the shorter side, m.
    pub long: f64,
    pub short: f64,
}

impl Gather {
    /// Longer side over shorter.
    pub fn ratio(&self) -> f64 {
        self.long / self.short
    }
    /// Whether the gather is beyond what a seam can be ([`MAX_GATHER`], with a longer side
    /// more than [`SMALL_EXCESS`] over the shorter).
    pub fn excessive(&self) -> bool {
        self.long > MAX_GATHER * self.short && self.long - self.short > SMALL_EXCESS
    }
}

impl std::fmt::Display for Gather {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "seam {} ({}) gathers {:.1} cm onto {:.1} cm ({:.2}:1)",
            self.seam,
            self.name,
            100.0 * self.long,
            100.0 * self.short,
            self.ratio()
        )
    }
}

impl Pattern {
    /// The seams whose sides differ by more than [`EASE`], in seam order. The sides must
    /// exist (as [`Pattern::validate`] checks).
    pub fn gathers(&self) -> Vec<Gather> {
        let length = |side: &SeamSide| self.panels[side.panel].outline[side.edge].length();
        self.seams
            .iter()
            .enumerate()
            .filter_map(|(seam, s)| {
                let (a, b) = (length(&s.a), length(&s.b));
                let (long, short) = (a.max(b), a.min(b));
                (long - short > EASE * long).then(|| Gather {
                    seam,
                    name: format!("{} to {}", self.describe(&s.a), self.describe(&s.b)),
                    long,
                    short,
                })
            })
            .collect()
    }
}
