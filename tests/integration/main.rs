//! whitted's integration tests, one crate with a module per area: the built binary run as a
//! user runs it, and the library rendered against its references.

mod allowance;
mod check;
mod check_courses;
mod check_histories;
mod check_print;
mod check_project;
mod cli_errors;
mod common;
mod courses;
mod determinism;
mod differential;
mod explain;
mod exr_aovs;
mod figures;
mod fuzz_corpus;
mod golden_exr;
mod golden_png;
mod grade;
mod grade_courses;
mod grade_hostile;
mod grade_machine;
mod grade_skeletons;
mod hostile;
mod inspect;
mod properties;
mod readme;
mod regression;
mod relight;
mod scale;
mod scenes;
mod tonemap;
mod view;
mod view_hostile;
mod view_load;
mod view_page;
