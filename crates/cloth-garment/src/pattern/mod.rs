//! Sewing patterns: flat panels with curved outlines, a grain line, a fabric and a
//! placement around the body, and the seams that join their edges.
//!
//! Everything here is in metres and radians; the file formats (our TOML, GarmentCode's
//! JSON) convert on reading.

mod curve;
mod error;
mod gather;
mod placement;
mod toml_format;
mod validate;

pub use curve::Curve;
pub use error::PatternError;
pub use gather::{Gather, EASE, MAX_GATHER, SMALL_EXCESS};
pub use placement::{Placement, Wrap};

use cloth_core::math::Vec3;
use nalgebra::Vector2;

pub type Point2 = Vector2<f64>;

/// A garment's pattern: its panels and the seams between their edges.
#[derive(Debug, Clone, PartialEq)]
pub struct Pattern {
    pub name: String,
    pub panels: Vec<Panel>,
    pub seams: Vec<Seam>,
    /// Edges held on one side of where they are placed (see [`AttachedEdge`]).
    pub attachments: Vec<AttachedEdge>,
}

/// One flat piece of fabric.
#[derive(Debug, Clone, PartialEq)]
pub struct Panel {
    pub name: String,
    /// The outline: a closed loop of edges, each starting where the previous one ends.
    pub outline: Vec<Edge>,
    /// Holes cut out of the panel, each a closed loop like the outline.
    pub holes: Vec<Vec<Edge>>,
    /// The warp direction in the panel's 2D coordinates (need not be unit).
    pub grain: Point2,
    /// A fabric preset name; `None` uses the garment's fabric.
    pub fabric: Option<String>,
    pub placement: Placement,
    /// The part of the body the panel dresses, if said (GarmentCode's panel `label`).
    pub dresses: Option<BodyPart>,
}

/// A part of the body a panel dresses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum BodyPart {
    /// The trunk: a bodice, a collar, a waistband (GarmentCode's "body").
    Torso,
    /// The hips and legs: a skirt, trousers (GarmentCode's "leg"). Sewn, such a panel
    /// passes the body's thin parts (the hands and forearms of a body in an A pose hang
    /// beside the hips, inside a wide skirt's panels).
    Legs,
    /// A sleeve or cuff (GarmentCode's "arm").
    Arms,
}

/// One edge of a panel's outline or of a hole, from `start` to `end`.
#[derive(Debug, Clone, PartialEq)]
pub struct Edge {
    /// Name by which seams refer to the edge (its index works too).
    pub name: Option<String>,
    pub start: Point2,
    pub end: Point2,
    pub curve: Curve,
}

/// Which of a panel's edges a seam side is: an outline edge by index.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SeamSide {
    pub panel: usize,
    pub edge: usize,
}

/// An outline edge as a file names it: by its name, or by its index from 0 (GarmentCode's
/// edges have no names).
#[derive(Debug, Clone, PartialEq, Eq, serde::Deserialize)]
#[serde(untagged)]
pub enum EdgeRef {
    Index(usize),
    Name(String),
}

/// How the two sides of a seam run against each other.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SeamOrientation {
    /// Side b's start meets side a's end: two panels facing the same way around a
    /// garment traverse their shared edge in opposite directions.
    #[default]
    Opposite,
    /// Side b's start meets side a's start.
    Same,
    /// Whichever of the two pairs the placed edges closer (a tie goes to `Opposite`).
    Auto,
}

/// Two edges sewn together.
#[derive(Debug, Clone, PartialEq)]
pub struct Seam {
    pub a: SeamSide,
    pub b: SeamSide,
    pub orientation: SeamOrientation,
}

/// An edge held on one side of where it is placed: each of its points moves freely along
/// `direction` but not back past its placed position (see [`cloth_core::Attachment`]).
/// GarmentCode labels the edges its simulator holds so: a lower garment's waist may not
/// sink below the waist (up), a bodice's neckline may not slide out over the shoulders
/// (towards the middle), a strapless top may not sink below the arms (up).
#[derive(Debug, Clone, PartialEq)]
pub struct AttachedEdge {
    pub edge: SeamSide,
    /// Unit vector in the world, pointing to the side the edge is free to move to.
    pub direction: Vec3,
}

impl Pattern {
    /// The panel named `name`.
    pub fn panel_index(&self, name: &str) -> Option<usize> {
        self.panels.iter().position(|p| p.name == name)
    }

    /// "panel 'front', edge 'side' (2)": how errors and reports name an edge.
    pub fn describe(&self, side: &SeamSide) -> String {
        let panel = &self.panels[side.panel];
        match &panel.outline[side.edge].name {
            Some(name) => format!("panel '{}', edge '{}' ({})", panel.name, name, side.edge),
            None => format!("panel '{}', edge {}", panel.name, side.edge),
        }
    }

    /// The outline edge `edge_ref` of the panel named `panel_name`, or why there is none
    /// (listing what there is).
    pub fn find_edge(&self, panel_name: &str, edge_ref: &EdgeRef) -> Result<SeamSide, String> {
        let panel = self.find_panel(panel_name)?;
        let outline = &self.panels[panel].outline;
        let edge = match edge_ref {
            EdgeRef::Index(i) if *i < outline.len() => Some(*i),
            EdgeRef::Index(_) => None,
            EdgeRef::Name(name) => self.panels[panel].edge_index(name),
        };
        let Some(edge) = edge else {
            let known: Vec<String> = outline
                .iter()
                .enumerate()
                .map(|(k, e)| e.name.clone().unwrap_or_else(|| k.to_string()))
                .collect();
            let wanted = match edge_ref {
                EdgeRef::Index(i) => i.to_string(),
                EdgeRef::Name(n) => format!("'{n}'"),
            };
            return Err(format!(
                "panel '{panel_name}' has no edge {wanted} (edges: {})",
                known.join(", ")
            ));
        };
        Ok(SeamSide { panel, edge })
    }

    /// The panel named `panel_name`, or why there is none (listing the panels).
    pub fn find_panel(&self, panel_name: &str) -> Result<usize, String> {
        self.panel_index(panel_name).ok_or_else(|| {
            let known: Vec<&str> = self.panels.iter().map(|p| p.name.as_str()).collect();
            format!("no panel named '{panel_name}' (panels: {})", known.join(", "))
        })
    }
}

impl Panel {
    /// The outline edge with this name, or with this index written as a number.
    pub fn edge_index(&self, name: &str) -> Option<usize> {
        self.outline
            .iter()
            .position(|e| e.name.as_deref() == Some(name))
            .or_else(|| name.parse::<usize>().ok().filter(|&i| i < self.outline.len()))
    }
}

impl Edge {
    /// A straight edge.
    pub fn line(start: Point2, end: Point2) -> Self {
        Self {
            name: None,
            start,
            end,
            curve: Curve::Line,
        }
    }
    pub fn named(mut self, name: impl Into<String>) -> Self {
        self.name = Some(name.into());
        self
    }
    /// The point at parameter `t` in [0, 1].
    pub fn point(&self, t: f64) -> Point2 {
        self.curve.point(self.start, self.end, t)
    }
    /// Arc length.
    pub fn length(&self) -> f64 {
        self.curve.length(self.start, self.end)
    }
    /// How far its direction turns, radians.
    pub fn turning(&self) -> f64 {
        self.curve.turning(self.start, self.end)
    }
    /// `pieces + 1` points at equal arc-length spacing, both ends included.
    pub fn resample(&self, pieces: usize) -> Vec<Point2> {
        self.curve.resample(self.start, self.end, pieces)
    }
}
