//! cloth-garment: garments from flat sewing patterns.
//!
//! The source's three stages: the pattern's panels are discretised (constrained Delaunay
//! refinement, seam edges resampled so their vertices pair one to one), placed around
//! the body and sewn with gravity off (seam forces pull the pairs together, then they
//! are welded into single particles), and draped with gravity on until at rest. Patterns
//! come from our TOML format or GarmentCode's JSON; bodies from the parametric mannequin
//! or any closed mesh.

// `!(x > 0.0)` is how NaN is refused along with the out-of-range values.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod mannequin;
pub mod meshing;
pub mod pattern;
pub mod garment;
pub mod garmentcode;
pub mod sewing;

pub use garment::{Garment, GarmentBuilder, GarmentError, HeldOpen, Layers, PlacementWarning, Touching};
pub use pattern::{
    BodyPart, Curve, Edge, Gather, Panel, Pattern, PatternError, Placement, Seam, SeamOrientation, SeamSide,
    Wrap,
};
