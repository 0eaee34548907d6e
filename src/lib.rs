pub use cloth_core::*;
