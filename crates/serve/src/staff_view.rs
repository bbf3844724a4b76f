//! The class as the staff page shows it, computed from the students and every attempt: each
//! student's latest attempt, the mistakes ranked by how many students have held each and for
//! how long, the attempts per hour, and who has not started.

use std::collections::BTreeMap;

use super::store::{Attempt, Kind, Status, Student};

pub struct Row {
    pub student: Student,
    pub attempts: usize,
    pub latest: Option<Attempt>,
}

/// A mistake across the class.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Ranked {
    pub id: String,
    /// Students whose finished attempts have named it.
    pub students: usize,
    /// Of them, those whose latest finished attempt still names it.
    pub now: usize,
    /// How long they held it, added up: from the first attempt naming it to the first later
    /// one that does not (or `now`, for those who still have it).
    pub seconds: i64,
}

/// The projects' runs across the class: what the queue holds and what the runs cost.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Programs {
    pub queued: usize,
    pub running: usize,
    pub done: usize,
    /// Of the done, those whose CPU time was measured, and its total (seconds).
    pub measured: usize,
    pub cpu: f64,
    /// The done runs' wall time, added up (seconds, from start to finish).
    pub wall: i64,
}

impl Programs {
    fn of(attempts: &[Attempt]) -> Programs {
        let mut p = Programs::default();
        for a in attempts.iter().filter(|a| a.kind == Kind::Project) {
            match a.status {
                Status::Queued => p.queued += 1,
                Status::Running => p.running += 1,
                Status::Done => {
                    p.done += 1;
                    p.wall += a.finished.zip(a.started).map_or(0, |(f, s)| (f - s).max(0));
                    if let Some(cpu) = a.cpu {
                        p.measured += 1;
                        p.cpu += cpu;
                    }
                }
            }
        }
        p
    }
}

pub struct ClassView {
    pub rows: Vec<Row>,
    pub programs: Programs,
    pub mistakes: Vec<Ranked>,
    /// Attempts received per hour (the hour's first second), oldest first.
    pub per_hour: Vec<(i64, usize)>,
}

impl ClassView {
    /// `attempts` oldest first; `now` in seconds since 1970.
    pub fn of(students: Vec<Student>, attempts: &[Attempt], now: i64) -> ClassView {
        let mut per_hour: BTreeMap<i64, usize> = BTreeMap::new();
        for a in attempts {
            *per_hour
                .entry(a.received - a.received.rem_euclid(3600))
                .or_default() += 1;
        }
        let mut mistakes: BTreeMap<String, Ranked> = BTreeMap::new();
        let rows = students
            .into_iter()
            .map(|student| {
                let mine: Vec<&Attempt> = attempts
                    .iter()
                    .filter(|a| a.student == student.number)
                    .collect();
                for (id, (seconds, held_now)) in held(&mine, now) {
                    let entry = mistakes.entry(id.clone()).or_insert(Ranked {
                        id,
                        students: 0,
                        now: 0,
                        seconds: 0,
                    });
                    entry.students += 1;
                    entry.now += usize::from(held_now);
                    entry.seconds += seconds;
                }
                Row {
                    attempts: mine.len(),
                    latest: mine.last().map(|a| (*a).clone()),
                    student,
                }
            })
            .collect();
        let mut mistakes: Vec<Ranked> = mistakes.into_values().collect();
        mistakes
            .sort_by(|a, b| (b.students, b.seconds, &a.id).cmp(&(a.students, a.seconds, &b.id)));
        ClassView {
            rows,
            programs: Programs::of(attempts),
            mistakes,
            per_hour: per_hour.into_iter().collect(),
        }
    }

    pub fn started(&self) -> usize {
        self.rows.iter().filter(|r| r.attempts > 0).count()
    }

    pub fn passing(&self) -> usize {
        self.rows
            .iter()
            .filter(|r| {
                r.latest
                    .as_ref()
                    .and_then(|a| a.outcome.as_ref())
                    .is_some_and(|o| o.passed)
            })
            .count()
    }

    pub fn not_started(&self) -> impl Iterator<Item = &Row> {
        self.rows.iter().filter(|r| r.attempts == 0)
    }
}

/// Per mistake one student's finished attempts have named: how long they held it, and
/// whether their latest finished attempt still names it.
fn held(attempts: &[&Attempt], now: i64) -> BTreeMap<String, (i64, bool)> {
    let finished: Vec<(i64, Option<&str>)> = attempts
        .iter()
        .filter_map(|a| {
            a.outcome
                .as_ref()
                .map(|o| (a.received, o.mistake.as_deref()))
        })
        .collect();
    let mut out: BTreeMap<String, (i64, bool)> = BTreeMap::new();
    let mut since: Option<(String, i64)> = None;
    for &(at, mistake) in &finished {
        match (&since, mistake) {
            (Some((held, _)), Some(m)) if held == m => {}
            _ => {
                if let Some((held, from)) = since.take() {
                    out.entry(held).or_default().0 += at - from;
                }
                since = mistake.map(|m| (m.to_string(), at));
            }
        }
    }
    if let Some((held, from)) = since {
        let entry = out.entry(held).or_default();
        entry.0 += now - from;
        entry.1 = true;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::store::Outcome;

    fn attempt(id: i64, student: i64, at: i64, mistake: Option<&str>) -> Attempt {
        Attempt {
            id,
            student,
            kind: Kind::Images,
            folder: String::new(),
            files: String::new(),
            status: Status::Done,
            received: at,
            started: None,
            finished: None,
            runs: 1,
            cpu: None,
            job: None,
            outcome: Some(Outcome {
                passed: mistake.is_none(),
                verdict: String::new(),
                mistake: mistake.map(str::to_string),
                finding: String::new(),
                progress: String::new(),
                report: String::new(),
            }),
        }
    }

    fn student(number: i64) -> Student {
        Student {
            number,
            id: format!("s{number}"),
            name: String::new(),
            email: String::new(),
            secret: None,
            csrf: String::new(),
        }
    }

    #[test]
    fn mistakes_are_ranked_by_students_then_time_held() {
        let attempts = [
            attempt(1, 1, 0, Some("no-shadows")),
            attempt(2, 2, 100, Some("no-shadows")),
            attempt(3, 1, 600, Some("no-shadows")),
            attempt(4, 1, 3600, None),
            attempt(5, 2, 3700, Some("flipped-normal")),
        ];
        let view = ClassView::of(vec![student(1), student(2), student(3)], &attempts, 4000);
        assert_eq!(
            view.mistakes,
            vec![
                Ranked {
                    id: "no-shadows".into(),
                    students: 2,
                    now: 0,
                    seconds: 3600 + 3600
                },
                Ranked {
                    id: "flipped-normal".into(),
                    students: 1,
                    now: 1,
                    seconds: 300
                },
            ]
        );
        assert_eq!((view.started(), view.passing()), (2, 1));
        let waiting: Vec<&str> = view.not_started().map(|r| r.student.id.as_str()).collect();
        assert_eq!(waiting, ["s3"]);
        assert_eq!(view.per_hour, vec![(0, 3), (3600, 2)]);
    }
}
