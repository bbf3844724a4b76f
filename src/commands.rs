//! One file per subcommand: each turns parsed arguments into work and outputs.

pub mod render;
pub mod tonemap;
