//! What can go wrong making, sewing and draping a garment.

use super::ring::{closing_said, Ring};
use crate::meshing::MeshingError;
use crate::pattern::PatternError;
use cloth_core::{MeshError, ParamError, SimError};

#[derive(Debug, thiserror::Error)]
pub enum GarmentError {
    #[error(transparent)]
    Pattern(#[from] PatternError),
    #[error("{file}: panel '{panel}' cannot be meshed: {source}")]
    Meshing {
        file: String,
        panel: String,
        #[source]
        source: MeshingError,
    },
    /// The mesh would be larger than the limit: refused before meshing.
    #[error(
        "{file}: meshing at an edge length of {edge_length} m would make about {triangles:.2e} triangles, \
         over the limit of {limit}; the largest panel, '{panel}', is {width:.3} m by {height:.3} m: check the \
         pattern's units, or raise the edge length or the limit (max_triangles)"
    )]
    TooLarge {
        file: String,
        panel: String,
        width: f64,
        height: f64,
        edge_length: f64,
        triangles: f64,
        limit: usize,
    },
    #[error("{what} are not a valid cloth mesh: {source}")]
    Mesh {
        what: &'static str,
        #[source]
        source: MeshError,
    },
    #[error("{name} = {value} is invalid: expected {expected}")]
    Parameter {
        name: &'static str,
        value: f64,
        expected: &'static str,
    },
    #[error(transparent)]
    Param(#[from] ParamError),
    /// Welding would fold a triangle onto itself: two of its corners are sewn together.
    #[error("welding the seams collapses triangle {triangle} of panel '{panel}': two of its corners are sewn together")]
    Collapse { triangle: usize, panel: String },
    /// The seams did not close within the sewing stage's step limit.
    #[error("the seams did not close in {steps} steps: {seam} is still {gap_mm:.1} mm apart (tolerance {tolerance_mm:.1} mm)")]
    NotSewn {
        steps: u64,
        seam: String,
        gap_mm: f64,
        tolerance_mm: f64,
    },
    /// The seams stopped closing with the pull at its strongest, too far apart to weld
    /// where they stand, with a body between the sides of their open pairs, or cloth
    /// across a gap wider than a weld over it reaches (seams with nothing between are
    /// zipped shut).
    #[error(
        "the seams stopped closing at step {steps}: {seam} is still {gap_mm:.1} mm apart with the \
         pull at {pull_factor} times its strength, too far to weld (over {weld_mm:.1} mm); \
         {held_by}{}{}",
        ring_said(ring),
        others_held_by.of_other_seams()
    )]
    Stalled {
        steps: u64,
        seam: String,
        gap_mm: f64,
        pull_factor: f64,
        weld_mm: f64,
        /// What lies between the sides of the seam named where they are too far apart to
        /// weld where they stand (nearer pairs are welded whatever lies between).
        held_by: HeldOpen,
        /// What lies between the sides of the other seams' pairs too far apart to weld.
        others_held_by: HeldOpen,
        /// The ring round the body through the seam's widest pair (see [`Ring`]): what
        /// closing asks of the cloth round it.
        /// Boxed: the error stays small on the paths that never fail.
        ring: Option<Box<Ring>>,
    },
    /// The observer asked to stop (a user's interrupt, say).
    #[error("{stage} stopped at step {steps}")]
    Stopped { stage: &'static str, steps: u64 },
    #[error("{stage}: {source}")]
    Sim {
        stage: &'static str,
        #[source]
        source: SimError,
    },
}

/// What lies on the straight lines between the two sides of the seams' open pairs when
/// they stopped closing: what the seams would have to go round or through.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum HeldOpen {
    /// Cloth of these panels (named, each once): a layer the seam closed on; such seams
    /// are welded over it when near enough.
    Cloth(Vec<String>),
    /// A body: the cloth between the sides is too short to go round it, or went round it
    /// on the wrong side (GarmentCode's rand_1_035 lays a trouser leg's flounce across the
    /// other shin); the failure's ring says which.
    Body,
    /// Nothing: the cloth round them holds the sides apart (too small for the body it goes
    /// round, or held by its own contact elsewhere, as godets touching at their corners);
    /// such seams are zipped shut.
    Nothing,
}

/// What closing asks of the ring round a seam, as the middle of a sentence about it:
/// empty for no ring.
fn ring_said(ring: &Option<Box<Ring>>) -> String {
    let Some(ring) = ring else {
        return String::new();
    };
    format!(
        "; the way round the body from side to side, through panel {}, is {:.1} cm of cloth, {}",
        quoted(&ring.panels),
        100.0 * ring.rest,
        closing_said(ring.closing_strain())
    )
}

/// Panel names, each in quotes, separated by commas.
fn quoted(panels: &[String]) -> String {
    let names: Vec<String> = panels.iter().map(|p| format!("'{p}'")).collect();
    names.join(", ")
}

impl HeldOpen {
    /// What lies between the sides of seams other than the one named, as the end of a
    /// sentence about it: empty for nothing.
    fn of_other_seams(&self) -> String {
        match self {
            Self::Cloth(panels) => format!(
                "; between the sides of the other seams' pairs too far apart to weld lies cloth of panel {}",
                quoted(panels)
            ),
            Self::Body => {
                "; between the sides of the other seams' pairs too far apart to weld lies the body".into()
            }
            Self::Nothing => String::new(),
        }
    }
}

impl std::fmt::Display for HeldOpen {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Cloth(panels) => write!(f, "cloth of panel {} lies between its sides", quoted(panels)),
            Self::Body => write!(
                f,
                "the body lies between its sides: the garment is too small there to go round it, \
                 or went round it on the wrong side"
            ),
            Self::Nothing => write!(
                f,
                "nothing lies between its sides: the cloth round them holds them apart (too small \
                 for the body there, or held by its own contact elsewhere)"
            ),
        }
    }
}
