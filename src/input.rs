//! Reading images back: whitted's own EXRs (or anyone's) and PNGs, as named float channels.

pub mod exr;
pub mod image;
pub mod png;

pub use image::{Channel, Image, Layer};
