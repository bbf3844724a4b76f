//! whitted: a Whitted ray tracer that reproduces the Cambridge "Introduction to Graphics"
//! Tick 2 image bit for bit, and writes the same render as linear HDR layers.
//!
//! # Glossary
//! Symbols follow the course's handout and `rendering.md`:
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
//! - [`scene`]: plain scene data, and [`scene::xml`] which loads it with located errors.
//! - [`geometry`]: rays, the shapes, intersection; [`accel`]: the BVH that finds the same
//!   nearest hit faster.
//! - [`camera`]: pixel -> primary ray.
//! - [`trace`]: the tick shading model; returns a [`sample::Sample`].
//! - [`render`]: tiles in parallel, k*k samples per pixel, regions -> [`film::Film`].
//! - [`aov`]: the EXR layers and what each holds.
//! - [`tonemap`] and [`output`]: linear film -> display bytes -> files; [`input`] reads
//!   EXRs and PNGs back; [`compare`] and [`canvas`] serve `diff` and `sheet`.
//! - [`cli`] and [`commands`]: the command line; [`progress`], [`interrupt`] and [`memory`]
//!   keep long renders watchable, stoppable and within the machine.

pub mod accel;
pub mod aov;
pub mod camera;
pub mod canvas;
pub mod cli;
pub mod commands;
pub mod compare;
pub mod error;
pub mod film;
pub mod frame;
pub mod geometry;
pub mod input;
pub mod interrupt;
pub mod memory;
pub mod merge;
pub mod numbers;
pub mod openexr;
pub mod output;
pub mod plan;
pub mod progress;
pub mod render;
pub mod render_record;
pub mod sample;
pub mod scene;
pub mod sheet;
pub mod stats;
pub mod suggest;
pub mod tonemap;
pub mod trace;

pub use error::{Error, Result};
