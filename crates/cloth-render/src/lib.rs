//! Pictures of meshes without a GPU: a z-buffered, supersampled triangle rasteriser with
//! smooth two-sided shading, a perspective camera that frames whatever it is given, bitmap
//! text, figures of titled panels side by side with a strain colour legend, and charts for
//! reports.
//!
//! [`render_run`] is the picture of a finished run; [`figure`] draws anything else, and
//! [`read_render_mesh`] reads OBJ and PLY files to feed it.

// Bottom-up: each module uses only those above it.
pub mod strain_colours;
mod error;
mod mesh;
mod image;
mod camera;
mod shading;
mod raster;
mod text;
mod legend;
mod chart;
mod figure;
mod mesh_read;
mod run;

pub use camera::View;
pub use chart::{charts, Chart, Series, Style};
pub use error::RenderError;
pub use figure::{figure, Panel};
pub use image::{check_image_size, Image, IMAGE_SIDES};
pub use legend::Legend;
pub use mesh::{MeshColours, RenderMesh, NEUTRAL_GREY};
pub use mesh_read::{read_render_mesh, Colouring, LoadedMesh};
pub use run::render_run;
