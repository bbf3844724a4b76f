//! whitted-io: files in and out. Writing a render (EXR layers, PNG through a tone map, atomically,
//! never clobbering on failure), reading images back (EXR, PNG, JPEG, TIFF, HDR) with bounded
//! allocation, and the tools over them: comparison, statistics, merging farm parts, contact
//! sheets, relighting, the plan that checks a render's outputs before it runs, and what HTML
//! pages need ([`html`]).
//!
//! # What it may depend on
//! whitted-core, and the image crates (exr, png, image, zlib-rs). Never clap, hyper, tokio or
//! zip.
//!
//! # Module map
//! Writing: [`plan`] (every output checked before rendering) -> [`output`] (EXR via [`openexr`],
//! PNG) and [`render_record`] (the command that made a file). Reading: [`input`]. Over images:
//! [`compare`], [`stats`], [`merge`], [`sheet`] (drawn on a [`canvas`]), [`relight`].

pub mod bump_map;
pub mod canvas;
pub mod compare;
pub mod html;
pub mod input;
pub mod merge;
pub mod openexr;
pub mod output;
pub mod plan;
pub mod relight;
pub mod render_record;
pub mod sheet;
pub mod stats;
