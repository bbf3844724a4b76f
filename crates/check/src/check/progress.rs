//! Where the student is in the handout (docs/check.md, "Progress"): each stage done, not
//! written yet, written with a mistake, not reached (an earlier stage still missing hides it),
//! or unknown, read from the explanation that accounts for the images best.

use crate::mistakes::{Bug, Mistakes, Parameter, Stage};
use whitted_core::course::Course;

/// An explanation must reproduce at least this share of the differing pixels for the stages
/// it leaves out to count as done; below it nothing is known.
const TRUSTED: f64 = 0.5;

/// One stage's state.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum StageState {
    /// Nothing wrong found in that stage.
    Done,
    /// Its unfinished-stage entry holds.
    Missing,
    /// Entries (or a number) of that stage hold: their ids or names.
    Mistaken(Vec<String>),
    /// Nothing of it can show, because the stage named is not written yet (no object to
    /// shade, no light to shadow): never called done, whatever its code is.
    NotReached(Stage),
    /// Cannot tell (every case crashed, or nothing explains the images).
    Unknown,
}

impl StageState {
    /// The JSON value of docs/check.md.
    pub fn name(&self) -> &'static str {
        match self {
            StageState::Done => "done",
            StageState::Missing => "missing",
            StageState::Mistaken(_) => "mistaken",
            StageState::NotReached(_) => "not-reached",
            StageState::Unknown => "unknown",
        }
    }
}

/// Every stage's state, in the handout's order.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Stages {
    /// The year whose handout's stages these are.
    pub course: Course,
    pub stages: Vec<(Stage, StageState)>,
}

/// What the progress is read from.
pub enum Evidence {
    /// No image to judge by.
    Nothing,
    /// Every image equals or is within tolerance of the reference, with no entry found.
    AllCorrect,
    /// The best explanation: its entries, perhaps a wrong number, and how much it explains.
    Explained {
        mistakes: Mistakes,
        number: Option<Parameter>,
        explained: f64,
    },
    /// The images differ and nothing explains them.
    Unexplained,
}

impl Stages {
    pub fn of(evidence: &Evidence, course: Course) -> Stages {
        let all = |state: StageState| Stages {
            course,
            stages: Stage::of(course)
                .iter()
                .map(|&s| (s, state.clone()))
                .collect(),
        };
        match *evidence {
            Evidence::Nothing | Evidence::Unexplained => all(StageState::Unknown),
            Evidence::AllCorrect => all(StageState::Done),
            Evidence::Explained { explained, .. } if explained < TRUSTED => {
                all(StageState::Unknown)
            }
            Evidence::Explained {
                mistakes, number, ..
            } => {
                let mut stages: Vec<(Stage, StageState)> = Stage::of(course)
                    .iter()
                    .map(|&stage| (stage, state_of(stage, mistakes, number)))
                    .collect();
                let missing: Vec<Stage> = stages
                    .iter()
                    .filter(|(_, state)| *state == StageState::Missing)
                    .map(|(stage, _)| *stage)
                    .collect();
                for (stage, state) in &mut stages {
                    if *state != StageState::Missing {
                        if let Some(behind) = hidden_behind(*stage, &missing) {
                            *state = StageState::NotReached(behind);
                        }
                    }
                }
                Stages { course, stages }
            }
        }
    }

    /// The first line of a report: "progress: planes done; lights not written yet; ...".
    pub fn sentence(&self) -> String {
        let parts: Vec<String> = self
            .stages
            .iter()
            .map(|(stage, state)| {
                let key = stage.key(self.course);
                match state {
                    StageState::Done => format!("{key} done"),
                    StageState::Missing => format!("{key} not written yet"),
                    StageState::Mistaken(ids) => {
                        format!("{key} done, with a mistake ({})", ids.join(", "))
                    }
                    StageState::NotReached(behind) => format!(
                        "{key} not reached ({} not written yet: nothing of it can show)",
                        behind.key(self.course)
                    ),
                    StageState::Unknown => format!("{key} unknown"),
                }
            })
            .collect();
        format!("progress: {}", parts.join("; "))
    }

    /// What to do next, in the handout's order, while a stage is still not written: the
    /// diagnosis is ranked by how much each entry explains, which is not the order a student
    /// works in. The earliest stage not written yet, or with a mistake before it, that one:
    /// "next: shading (Renderer.illuminate, not written yet): ...". None when every stage is
    /// written (the diagnosis says all there is) or nothing is known.
    pub fn next(&self) -> Option<String> {
        let later_missing = |i: usize| {
            self.stages[i + 1..]
                .iter()
                .find(|(_, s)| *s == StageState::Missing)
                .map(|(stage, _)| stage.key(self.course))
        };
        let (i, (stage, state)) = self
            .stages
            .iter()
            .enumerate()
            .find(|(_, (_, s))| matches!(s, StageState::Missing | StageState::Mistaken(_)))?;
        let key = stage.key(self.course);
        match state {
            StageState::Missing => {
                let entry = stage
                    .missing_entries()
                    .iter()
                    .find(|b| b.offered_in(self.course))?;
                let then = match later_missing(i) {
                    Some(after) => format!(", then {after}"),
                    None => String::new(),
                };
                let hidden: Vec<&str> = self
                    .stages
                    .iter()
                    .filter(|(_, s)| *s == StageState::NotReached(*stage))
                    .map(|(later, _)| later.key(self.course))
                    .collect();
                let shows = match hidden.as_slice() {
                    [] => String::new(),
                    [one] => format!(" ({one} can show once it is)"),
                    many => format!(" ({} can show once it is)", many.join(", ")),
                };
                Some(format!(
                    "next: {key} ({}, not written yet), the handout's next stage{shows}{then}",
                    entry.place()
                ))
            }
            StageState::Mistaken(ids) => later_missing(i).map(|after| {
                format!(
                    "next: mend {key} ({}) before writing {after}: its mistake shows in every \
                     later stage's image",
                    ids.join(", ")
                )
            }),
            _ => None,
        }
    }
}

/// The stage not written yet (of `missing`) that keeps anything of `stage` from showing, if
/// one does: a fact of the handout and the course's scenes. With neither spheres nor planes
/// only the background shows; without spheres nothing casts a shadow (the course's scenes'
/// planes never shadow one another); without shading (or, in 2016-17, without the lights'
/// terms) there is no light for a shadow to take away.
fn hidden_behind(stage: Stage, missing: &[Stage]) -> Option<Stage> {
    let lacks = |s: Stage| missing.contains(&s);
    let nothing_hit = lacks(Stage::Spheres) && lacks(Stage::Planes);
    match stage {
        Stage::Lights | Stage::Reflection if nothing_hit => Some(Stage::Spheres),
        Stage::Shadows if lacks(Stage::Spheres) => Some(Stage::Spheres),
        Stage::Shadows if lacks(Stage::Lights) => Some(Stage::Lights),
        _ => None,
    }
}

fn state_of(stage: Stage, mistakes: Mistakes, number: Option<Parameter>) -> StageState {
    let here: Vec<Bug> = mistakes
        .bugs()
        .into_iter()
        .filter(|b| b.stage() == stage)
        .collect();
    if here.iter().any(|b| b.is_unfinished()) {
        return StageState::Missing;
    }
    let mut names: Vec<String> = here.iter().map(|b| b.id().to_string()).collect();
    names.extend(
        number
            .filter(|p| p.stage() == stage)
            .map(|p| p.name().to_string()),
    );
    if names.is_empty() {
        StageState::Done
    } else {
        StageState::Mistaken(names)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_stage_is_read_from_the_explanation() {
        let p = Stages::of(
            &Evidence::Explained {
                mistakes: Mistakes::of(&[
                    Bug::ReflectUnclamped,
                    Bug::NoShadows,
                    Bug::ReflectionMissing,
                ]),
                number: None,
                explained: 1.0,
            },
            Course::Y2016,
        );
        assert_eq!(
            p.sentence(),
            "progress: planes done; lights done, with a mistake (reflect-unclamped); \
             shadows not written yet; reflection not written yet"
        );
        let states: Vec<&str> = p.stages.iter().map(|(_, s)| s.name()).collect();
        assert_eq!(states, ["done", "mistaken", "missing", "missing"]);
        // The earliest stage with a mistake comes before the unwritten ones.
        assert_eq!(
            p.next().as_deref(),
            Some(
                "next: mend lights (reflect-unclamped) before writing shadows: its mistake \
                 shows in every later stage's image"
            )
        );
        let unknown = Stages::of(&Evidence::Nothing, Course::Y2016);
        assert!(unknown
            .stages
            .iter()
            .all(|(_, s)| *s == StageState::Unknown));
        let weak = Stages::of(
            &Evidence::Explained {
                mistakes: Mistakes::of(&[Bug::NoAmbient]),
                number: None,
                explained: 0.03,
            },
            Course::Y2016,
        );
        assert!(weak.stages.iter().all(|(_, s)| *s == StageState::Unknown));
        let number = Stages::of(
            &Evidence::Explained {
                mistakes: Mistakes::NONE,
                number: Some(Parameter::Epsilon),
                explained: 0.99,
            },
            Course::Y2016,
        );
        assert_eq!(
            number.stages[2].1,
            StageState::Mistaken(vec!["epsilon".into()])
        );
    }

    fn states(mistakes: &[Bug], course: Course) -> Vec<&'static str> {
        let p = Stages::of(
            &Evidence::Explained {
                mistakes: Mistakes::of(mistakes),
                number: None,
                explained: 1.0,
            },
            course,
        );
        p.stages.iter().map(|(_, s)| s.name()).collect()
    }

    #[test]
    fn a_stage_an_unwritten_one_hides_is_not_reached() {
        // The zip as shipped: only the background, so nothing after it can show.
        let p = Stages::of(
            &Evidence::Explained {
                mistakes: Mistakes::of(&[Bug::SpheresMissing, Bug::PlanesMissing]),
                number: None,
                explained: 1.0,
            },
            Course::Y2019,
        );
        assert_eq!(
            p.sentence(),
            "progress: spheres not written yet; \
             shading not reached (spheres not written yet: nothing of it can show); \
             planes not written yet; \
             shadows not reached (spheres not written yet: nothing of it can show); \
             reflection not reached (spheres not written yet: nothing of it can show)"
        );
        assert_eq!(
            p.next().as_deref(),
            Some(
                "next: spheres (Sphere.intersectionWith, not written yet), the handout's next \
                 stage (shading, shadows, reflection can show once it is), then planes"
            )
        );
        // Half-way through 2023-24's handout: shading before planes, whatever the diagnosis
        // ranks first.
        let half = Stages::of(
            &Evidence::Explained {
                mistakes: Mistakes::of(&[
                    Bug::ShadingMissing,
                    Bug::PlanesMissing,
                    Bug::ReflectionIgnored,
                ]),
                number: None,
                explained: 1.0,
            },
            Course::Y2023,
        );
        let next = half.next().expect("a next stage");
        assert!(
            next.starts_with("next: shading (Renderer.illuminate(..., O), not written yet)")
                && next.contains("then planes"),
            "{next}"
        );
        // Every stage written: the diagnosis says the rest.
        let done = Stages::of(&Evidence::AllCorrect, Course::Y2023);
        assert_eq!(done.next(), None);
        // Flat spheres, no planes: the reflection shows, no shadow can.
        assert_eq!(
            states(
                &[
                    Bug::ShadingMissing,
                    Bug::PlanesMissing,
                    Bug::ReflectionIgnored
                ],
                Course::Y2019
            ),
            ["done", "missing", "missing", "not-reached", "missing"]
        );
        // Planes alone are shaded and reflect, but nothing casts a shadow on them.
        assert_eq!(
            states(&[Bug::SpheresMissing], Course::Y2023),
            ["missing", "done", "done", "not-reached", "done"]
        );
        // 2016-17: no light's terms, so no shadow to take away.
        assert_eq!(
            states(&[Bug::LightsMissing], Course::Y2016),
            ["done", "missing", "not-reached", "done"]
        );
        // A missing stage hides nothing before it.
        assert_eq!(
            states(&[Bug::NoShadows, Bug::ReflectionIgnored], Course::Y2021),
            ["done", "done", "done", "missing", "missing"]
        );
    }
}
