//! whitted: the command line over the workspace's crates. The binary parses arguments with clap
//! ([`cli`]), builds each command's settings once and runs it ([`commands`]); everything it runs
//! lives in the library crates below it:
//!
//! - `whitted-core` (crates/core): scenes, the course model for every year, the hierarchy,
//!   tracing, film, AOVs, tone maps.
//! - `whitted-io` (crates/io): EXR and PNG out, images in, compare, stats, merge, sheet, relight.
//! - `whitted-check` (crates/check): the catalogue of mistakes, `check` and `explain`.
//! - `whitted-grade` (crates/grade): a class's submissions, sandboxed, graded, reported.
//! - `whitted-view` (crates/view): the local viewer's server and page.
//!
//! # What it may depend on
//! Every whitted crate, and clap with its man page and completion generators. Nothing depends
//! on this crate: clap stays here, and the libraries take plain settings.

pub mod cli;
pub mod commands;
