//! Why a student is short of full marks, in a word, for `class.csv`'s `reason` column: a 0
//! says `timeout` or `no-files` there, not only 0. Read from the student's `result.json`
//! alone, as every class file is.

use super::result::{StudentResult, TestStatus};
use super::status::StudentStatus;

/// The ways a counted case fails, worst first: the limits and crashes that kept it from an
/// image, then an image of the wrong size, then an image that differs. The worst one a
/// student's failing cases have is their reason.
const WORST_FIRST: [&str; 7] = [
    "timeout",
    "out-of-memory",
    "output-too-large",
    "crashed",
    "no-output",
    "wrong-size",
    "differs",
];

/// The reason of `result`: its status when it was not run (`compile-error`, `no-files`,
/// `error`), else the worst way one of its counted cases failed (a case that ran and wrote an
/// image that is not within tolerance gives its verdict, `differs`), else nothing: every
/// counted case passes.
pub fn reason(result: &StudentResult) -> String {
    let extra = &result.extra;
    if extra.status != StudentStatus::Graded {
        return extra.status.name().to_string();
    }
    let cases = extra
        .check
        .as_ref()
        .and_then(|c| c.get("cases"))
        .and_then(|c| c.as_array());
    let failures: Vec<String> = result
        .tests
        .iter()
        .enumerate()
        .filter(|(_, t)| t.max_score > 0.0 && t.status == TestStatus::Failed)
        .map(|(i, _)| {
            let case = cases.and_then(|c| c.get(i));
            let field = |name: &str| {
                case.and_then(|c| c.get(name))
                    .and_then(|v| v.as_str())
                    .unwrap_or("")
                    .to_string()
            };
            match field("status").as_str() {
                "ok" | "" => field("verdict"),
                // A Tick 1* option's image: its judge's verdict (`bump-unmatched`,
                // `not-a-draw`), which says what failed where the status says only that it
                // was judged.
                "tick1-star" => case
                    .and_then(|c| c["tick1_star"]["verdict"].as_str())
                    .unwrap_or("tick1-star")
                    .to_string(),
                other => other.to_string(),
            }
        })
        .collect();
    let rank = |f: &String| {
        WORST_FIRST
            .iter()
            .position(|w| w == f)
            .unwrap_or(WORST_FIRST.len())
    };
    failures.into_iter().min_by_key(rank).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    /// A graded result whose cases (weight, passed, status, verdict) are as given.
    fn graded(cases: &[(f64, bool, &str, &str)]) -> StudentResult {
        let tests: Vec<serde_json::Value> = cases
            .iter()
            .enumerate()
            .map(|(i, (weight, passed, _, _))| {
                json!({"max_score": weight, "name": format!("case {i}"), "output": "",
                       "score": 0.0, "status": if *passed { "passed" } else { "failed" },
                       "tags": []})
            })
            .collect();
        let checked: Vec<serde_json::Value> = cases
            .iter()
            .map(|(_, _, status, verdict)| json!({"status": status, "verdict": verdict}))
            .collect();
        let result = json!({
            "extra_data": {"cases": cases.len(), "check": {"cases": checked}, "diagnosis": [],
                "failed": false, "feedback": "", "folder": "f", "grade": 0.0, "id": "1",
                "key": "k", "name": "n", "notes": [], "passed": 0, "policy": "", "sandbox": true,
                "skeleton": "", "status": "graded", "tolerance": 2, "warnings": [],
                "whitted": "0"},
            "output": "", "score": 0.0, "tests": tests,
        });
        StudentResult::parse(result.to_string().as_bytes()).expect("a result")
    }

    #[test]
    fn the_worst_failing_counted_case_is_the_reason() {
        let all_pass = graded(&[(1.0, true, "ok", "identical"), (0.0, false, "crashed", "")]);
        assert_eq!(reason(&all_pass), "", "a diagnostic case scores nothing");
        let differs = graded(&[
            (1.0, false, "ok", "differs"),
            (1.0, true, "ok", "identical"),
        ]);
        assert_eq!(reason(&differs), "differs");
        let mixed = graded(&[
            (1.0, false, "ok", "differs"),
            (1.0, false, "crashed", "crashed"),
            (1.0, false, "output-too-large", "output-too-large"),
            (0.0, false, "timeout", "timeout"),
        ]);
        assert_eq!(reason(&mixed), "output-too-large");
        let hidden = graded(&[
            (1.0, false, "timeout", "timeout"),
            (1.0, false, "ok", "differs"),
        ]);
        assert_eq!(reason(&hidden), "timeout");
    }

    #[test]
    fn a_failing_tick1_star_option_gives_its_judge_s_verdict() {
        let mut result = graded(&[
            (1.0, true, "tick1-star", ""),
            (1.0, false, "tick1-star", ""),
        ]);
        let cases = result
            .extra
            .check
            .as_mut()
            .and_then(|c| c["cases"].as_array_mut())
            .expect("cases");
        cases[0]["tick1_star"] = json!({"verdict": "option-not-done"});
        cases[1]["tick1_star"] = json!({"verdict": "not-a-draw"});
        assert_eq!(reason(&result), "not-a-draw");
        let timed_out = graded(&[(1.0, false, "tick1-star", ""), (1.0, false, "timeout", "")]);
        assert_eq!(
            reason(&timed_out),
            "timeout",
            "a limit is worse than a verdict"
        );
    }

    #[test]
    fn a_student_who_was_not_run_has_their_status_as_the_reason() {
        let mut result = graded(&[]);
        for status in [
            StudentStatus::NoFiles,
            StudentStatus::CompileError,
            StudentStatus::Error,
        ] {
            result.extra.status = status;
            assert_eq!(reason(&result), status.name());
        }
    }
}
