//! Writers that turn a rendered film into files.

pub mod atomic;
pub mod destination;
pub mod exr;
pub mod exr_block;
pub mod exr_header;
pub mod exr_stream;
pub mod png;
pub mod stdout;
pub mod writers;
