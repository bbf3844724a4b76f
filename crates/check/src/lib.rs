//! whitted-check: the diagnosis. The catalogue of mistakes students make ([`mistakes`]), each a
//! variant of the one course model; [`check`], which finds the mistakes that explain a student's
//! image or program; and [`explain`], which says how one pixel got its value.
//!
//! # What it may depend on
//! whitted-core and whitted-io. Never clap, hyper, tokio or zip: the grader and the viewer
//! build on this crate, not the other way round.

pub mod check;
pub mod explain;
pub mod mistakes;
