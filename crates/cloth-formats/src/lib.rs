//! cloth-formats: the files the engine writes, each written atomically.

// Bottom-up: each module uses only those above it.
pub mod atomic;
pub mod obj;
