//! One file per subcommand: each turns parsed arguments into work and outputs.

pub mod check;
pub mod completions;
pub mod diff;
pub mod explain;
pub mod grade;
pub mod info;
pub mod man;
pub mod merge;
pub mod regions;
pub mod relight;
pub mod render;
pub mod render_star;
pub mod serve;
pub mod sheet;
pub mod tonemap;
pub mod view;
