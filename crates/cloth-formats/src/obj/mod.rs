//! Wavefront OBJ: one reader that keeps the file's numbering, and the writers.

mod read;
mod write;

pub use read::{ObjFace, ObjFile, ObjSyntaxError};
pub use write::{write_cloth_obj, write_cloth_obj_with_uv, write_objects, ClothObj, ObjObject};
