//! One file per subcommand: each turns parsed arguments into work and outputs.

pub mod diff;
pub mod info;
pub mod merge;
pub mod render;
pub mod sheet;
pub mod tonemap;
