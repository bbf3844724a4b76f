//! Progress of a student's grading as it happens, for a caller that shows it live (`whitted
//! serve`'s attempt page: "running case 3 of 5, tick2.xml -b 2"). `whitted grade` itself has
//! its progress bar and watches nothing.

use std::fmt;
use std::sync::Arc;

use whitted_check::check::program::Stage;
use whitted_check::check::suite::{Role, SuiteCase};

/// A step of one student's grading.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Step {
    /// Their files are being compiled against the skeleton.
    Compiling,
    /// Case `index` (from 1) of `of` started running: its name, or "a hidden case" unless
    /// hidden scenes are shown to students.
    Running {
        case: String,
        index: usize,
        of: usize,
    },
    /// The image of a case, the `index`th (from 1) of `of`, is being checked.
    Checking {
        case: String,
        index: usize,
        of: usize,
    },
}

impl Step {
    /// The step of a suite's run, named as a student may read it.
    pub(crate) fn of(stage: Stage<'_>, show_hidden: bool) -> Step {
        let name = |case: &SuiteCase| match (case.role, show_hidden) {
            (Role::Hidden, false) => "a hidden case".to_string(),
            _ => case.name(),
        };
        match stage {
            Stage::Running { case, index, of } => Step::Running {
                case: name(case),
                index: index + 1,
                of,
            },
            Stage::Checking { case, index, of } => Step::Checking {
                case: name(case),
                index: index + 1,
                of,
            },
        }
    }
}

/// Told of each step of each student's grading: the student's id, then the step. Called from
/// the grading threads, so it must be quick (a store into memory or a small file).
#[derive(Clone)]
pub struct Watch(pub Arc<Teller>);

/// What a watch calls: the student's id, then the step.
pub type Teller = dyn Fn(&str, Step) + Send + Sync;

impl Watch {
    pub(crate) fn tell(&self, student: &str, step: Step) {
        (self.0)(student, step);
    }
}

impl fmt::Debug for Watch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("Watch(..)")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use whitted_check::check::suite::cases_of;
    use whitted_core::course::Course;

    #[test]
    fn a_step_counts_from_one_and_hides_a_hidden_cases_name() {
        let suite = cases_of(Course::Y2016);
        let case = &suite[1];
        let running = Step::of(
            Stage::Running {
                case,
                index: 1,
                of: suite.len(),
            },
            false,
        );
        assert_eq!(
            running,
            Step::Running {
                case: case.name(),
                index: 2,
                of: suite.len()
            }
        );
        let mut hidden = case.clone();
        hidden.role = Role::Hidden;
        let checking = Step::of(
            Stage::Checking {
                case: &hidden,
                index: 0,
                of: 3,
            },
            false,
        );
        assert_eq!(
            checking,
            Step::Checking {
                case: "a hidden case".into(),
                index: 1,
                of: 3
            }
        );
        let shown = Step::of(
            Stage::Checking {
                case: &hidden,
                index: 0,
                of: 3,
            },
            true,
        );
        assert!(matches!(shown, Step::Checking { case, .. } if case == hidden.name()));
    }
}
