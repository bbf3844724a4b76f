//! Writers that turn a rendered film into files.

pub mod atomic;
pub mod png;
