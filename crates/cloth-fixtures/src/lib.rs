//! cloth-fixtures: ready-made contact scenes. The engine's integration tests check them, its
//! examples run them and its benchmarks time them; they are not part of the published
//! library. Each is a parameter struct with sensible defaults whose `build` gives a
//! [`ContactScene`].

// Bottom-up: each module uses only those above it.
mod contact_scene;
mod sheets;
mod cube_corner;
mod falling_plate;
mod folding_strip;
mod sheet_onto_sheet;
mod sphere_drop;
mod stacked_sheets;
mod tablecloth;
mod tilted_plane;
mod turning_sphere;

pub use contact_scene::{ContactScene, ContactSceneError};
pub use cube_corner::CubeCorner;
pub use falling_plate::FallingPlate;
pub use folding_strip::FoldingStrip;
pub use sheet_onto_sheet::SheetOntoSheet;
pub use sheets::scene_fabric;
pub use sphere_drop::SphereDrop;
pub use stacked_sheets::StackedSheets;
pub use tablecloth::Tablecloth;
pub use tilted_plane::TiltedPlane;
pub use turning_sphere::TurningSphere;
