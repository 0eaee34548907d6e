//! What a scene loads with that the user should know: the run goes on.

use cloth_collide::SurfaceDefect;
use cloth_garment::{Layers, PlacementWarning, Touching};

/// One thing found while preparing a scene, with what was done about it.
#[derive(Debug, Clone, PartialEq)]
pub enum SceneWarning {
    /// A body's mesh was not watertight as given (`body` names the entry and its file).
    Body { body: String, defect: SurfaceDefect },
    /// A panel starts inside a body.
    Placement(PlacementWarning),
    /// Panels overlap in one plane: they were set apart into layers.
    Layers(Layers),
    /// Panels touch where no seam joins them: they do not collide there while sewn.
    Touching(Touching),
    /// A seam's sides differ in length by more than ease: the longer is gathered.
    Gather(cloth_garment::Gather),
}

impl std::fmt::Display for SceneWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Body { body, defect } => write!(f, "{body}: {defect}"),
            Self::Placement(w) => w.fmt(f),
            Self::Layers(l) => l.fmt(f),
            Self::Touching(t) => t.fmt(f),
            Self::Gather(g) => g.fmt(f),
        }
    }
}
