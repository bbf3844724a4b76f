//! Readers for files whitted consumes besides scenes.

pub mod exr;
