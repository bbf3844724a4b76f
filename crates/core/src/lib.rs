//! whitted-core: the renderer. A scene (and the XML that describes it), the course's model of
//! light for every year, the hierarchy, tracing, the film and its layers, and the tone maps.
//!
//! # What it may depend on
//! Only numeric and parsing crates (glam, quick-xml, rayon, palette, indicatif for the bar,
//! signal-hook for Ctrl-C). Never on clap, hyper, tokio or zip, and never on another whitted
//! crate: everything else is built on this one.
//!
//! # Glossary
//! Symbols follow the course's handout and `docs/rendering.md`:
//! - `P`: a surface point being shaded (world space; the camera sits at the origin).
//! - `N`: the unit surface normal at `P` (never flipped for planes).
//! - `L`: the unit vector from `P` towards a light; `d` the distance to it.
//! - `V`: the unit vector from `P` towards the camera, `(-P)` normalised.
//! - `R`: the mirror of `L` about `N` (built from the clamped `N.L`).
//! - `D`: a ray's direction; `s`: the ray parameter of a hit, `P = O + s D`.
//! - `C`: the diffuse colour of a surface; `I_a`: the ambient light.
//! - `w_k`, `beta_k`: weight and throughput of vertex k of a mirror chain (`sample`).
//!
//! Units: radiance values are linear and unclamped, in the course's arbitrary units where a
//! display white is 1.0. Distances are scene units.
//!
//! # Module map
//! The data path: [`scene`] (and [`scene::xml`], which loads it with located errors) ->
//! [`frame`] (everything checked before anything runs) -> [`render`] (tiles in parallel;
//! [`camera`] rays, [`accel`] over [`geometry`], [`trace`] -> [`sample::Sample`]) ->
//! [`film::Film`] (the layers [`aov`] declares), which [`tonemap`] turns into display values.
//! [`hits`] is the trace's two questions of the geometry, answered by [`accel`] or from a
//! recording of an earlier trace (how `check`'s candidates share the course's searches).
//! [`model`] is the course's shading, a trait every year ([`course`]) and every catalogued
//! mistake overrides in part. [`progress`], [`interrupt`] and [`memory`] keep long renders
//! watchable, stoppable and within the machine.
//!
//! # Inlining across crates
//! The small per-ray functions other crates call per pixel (the shape tests of [`geometry`],
//! [`model::mirror_direction`], [`tonemap::ToneMap::apply`]) carry `#[inline]`: without it
//! rustc does not inline a non-generic function across a crate boundary, and `grade` spent 28%
//! more CPU in the diagnosis's models once they moved to their own crate. Inlining does not
//! change a result: Rust never contracts or reorders floating-point operations.

pub mod accel;
pub mod aov;
pub mod calendar;
pub mod camera;
pub mod course;
pub mod error;
pub mod film;
pub mod fingerprint;
pub mod frame;
pub mod geometry;
pub mod hits;
pub mod interrupt;
pub mod memory;
pub mod model;
pub mod numbers;
pub mod progress;
pub mod render;
pub mod sample;
pub mod scene;
pub mod star;
pub mod suggest;
pub mod tonemap;
pub mod trace;

pub use error::{Error, Result};
