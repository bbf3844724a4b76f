//! whitted-check: the diagnosis. The catalogue of mistakes students make ([`mistakes`]), each a
//! variant of the one course model; [`check`], which finds the mistakes that explain a student's
//! image or program; and [`explain`], which says how one pixel got its value.
//!
//! # What it may depend on
//! whitted-core and whitted-io. Never clap, hyper, tokio or zip: the grader and the viewer
//! build on this crate, not the other way round.
//!
//! # Glossary
//! The words the code, the docs and the reports use, one meaning each:
//! - **case**: one scene at one bounce count, checked against its reference. The suite's
//!   definition of it is a [`check::suite::SuiteCase`]; a student image of it prepared for the
//!   diagnosis is a [`check::case::Case`]; what the check says of it is a
//!   [`check::CaseReport`]; how a candidate scores on it is a [`check::score::CaseScore`] (and
//!   a term's fit on it a [`check::terms::TermCase`]); where the suite's explanation shows in it
//!   is a [`check::diagnose::CaseFinding`].
//! - **run**: one start of a student's program on one case, ended as a
//!   [`check::program::RunStatus`] (wrote an image, timed out, crashed, ...); the whole suite's
//!   runs with their checks are a [`check::program::SuiteRun`] of
//!   [`check::program::CaseOutcome`]s.
//! - **verdict**: how an image compares with its reference at the tolerance: identical, within
//!   tolerance, differs ([`check::difference::Verdict`]). A case passes on the first two.
//! - **stage**: a step of the handout (lights, planes, shadows, reflection); where a student is
//!   is the state of every stage, [`check::progress::Stages`], never the progress bar of a long
//!   run (`whitted_core::progress::Bar`).
//! - **mistake**: a catalogue entry ([`mistakes::Bug`]), a way the course's program is
//!   commonly written wrong; a set of them is [`mistakes::Mistakes`].
//! - **candidate**: a program the diagnosis tries, the course's model with some mistakes and
//!   perhaps one number changed ([`mistakes::Variant`]); the ranked candidates that explain the
//!   images are the diagnosis ([`check::diagnose::Diagnosis`]).
//! - **share**: a fraction of the differing pixels a candidate explains
//!   ([`check::score::explained_share`]).
//!
//! A student's standing in a graded class (`whitted_grade`'s `StudentStatus`) is neither a run's
//! status nor a verdict: it says whether the student was graded at all.

pub mod check;
pub mod explain;
pub mod mistakes;
