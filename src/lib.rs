//! The cloth engine: cloth-core's model and solver, cloth-collide's bodies, and ready-made
//! scenes.

pub use cloth_collide as collide;
pub use cloth_core::*;

pub use cloth_garment as garment;
pub mod bench;
pub mod drape;
pub mod obj;
pub mod output;
pub mod presets;
pub mod render;
pub mod scene_file;
pub mod scenes;
#[cfg(test)]
mod scratch;
pub mod validation;
