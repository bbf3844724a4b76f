//! whitted: a Whitted ray tracer that reproduces the Cambridge "Introduction to Graphics"
//! Tick 2 image bit for bit, and writes the same render as linear HDR layers.
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
//! [`frame`] and [`plan`] (everything checked before anything runs) -> [`render`] (tiles in
//! parallel; [`camera`] rays, [`accel`] over [`geometry`], [`trace`] -> [`sample::Sample`]) ->
//! [`film::Film`] (the layers [`aov`] declares) -> [`output`] (EXR, and PNG via [`tonemap`]).
//! Reading back: [`input`], [`openexr`]; inspection: [`compare`], [`stats`], [`sheet`],
//! [`merge`], [`numbers`], [`canvas`]; looking closer: [`relight`], [`explain`] and the
//! [`view`]er. The command line: [`cli`] and [`commands`];
//! [`progress`], [`interrupt`] and [`memory`] keep long renders watchable, stoppable and
//! within the machine. The rules are in `docs/`.

pub mod accel;
pub mod aov;
pub mod calendar;
pub mod camera;
pub mod canvas;
pub mod check;
pub mod cli;
pub mod commands;
pub mod compare;
pub mod course;
pub mod error;
pub mod explain;
pub mod film;
pub mod fingerprint;
pub mod frame;
pub mod geometry;
pub mod grade;
pub mod input;
pub mod interrupt;
pub mod memory;
pub mod merge;
pub mod mistakes;
pub mod model;
pub mod numbers;
pub mod openexr;
pub mod output;
pub mod plan;
pub mod progress;
pub mod relight;
pub mod render;
pub mod render_record;
pub mod sample;
pub mod scene;
pub mod sheet;
pub mod stats;
pub mod suggest;
pub mod tonemap;
pub mod trace;
pub mod view;

pub use error::{Error, Result};
