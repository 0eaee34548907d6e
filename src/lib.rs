//! The cloth engine's scene layer: scene files and their runs into folders, outputs,
//! fabric presets, the physical validations and batches of patterns, over cloth-core's
//! model and solver, cloth-collide's bodies, cloth-garment's patterns and sewing,
//! cloth-render's pictures and cloth-formats' files, each re-exported here.

pub use cloth_collide as collide;
pub use cloth_core::*;
pub use cloth_formats as formats;
pub use cloth_garment as garment;
pub use cloth_render as render;

// Bottom-up: each module uses only those above it.
pub mod validation;
pub mod presets;
pub mod scene_file;
pub mod output;
pub mod run_folder;
pub mod drape;
pub mod bench;
