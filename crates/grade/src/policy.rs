//! What a grade is made of (docs/grade.md, "What counts"): which cases count and how much, how
//! the counted verdicts become a grade out of 100, and the rule a case passes by (the channel
//! tolerance and the pixel allowance, `pass_rule.rs` of whitted-check). By default
//! the course's own scenes and every `--scenes` case count, one each, and whitted's diagnostic
//! scenes inform the diagnosis and the report but score nothing; `--count-diagnostic` counts
//! them too, and a rubric file weighs each case as the course wishes.

use std::path::Path;

use whitted_check::check::pass_rule::PassRule;
use whitted_check::check::suite::{Role, SuiteCase};
use whitted_core::error::{Error, Result};

/// How the counted cases become a grade (`--grade`), out of 100.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Grading {
    /// 100 when every counted case passes, else 0.
    PassFail,
    /// The weighted share of counted cases passed.
    Fraction,
}

impl Grading {
    pub fn name(self) -> &'static str {
        match self {
            Grading::PassFail => "pass-fail",
            Grading::Fraction => "fraction",
        }
    }
}

/// A class's grading policy: one weight per suite case (0: it informs, scores nothing).
#[derive(Debug, Clone, PartialEq)]
pub struct Policy {
    pub grading: Grading,
    /// When a case passes: the channel tolerance and the pixels allowed beyond it.
    pub rule: PassRule,
    pub weights: Vec<f64>,
    /// Where the weights come from, in words.
    pub source: String,
}

/// A rubric file's size limit: a rubric is a few lines.
const MAX_RUBRIC: u64 = 64 << 10;

impl Policy {
    /// The policy for `suite`: the default weights (course and hidden scenes 1, diagnostic
    /// scenes 0, or 1 with `count_diagnostic`), or a rubric's.
    pub fn new(
        suite: &[SuiteCase],
        grading: Grading,
        rule: PassRule,
        count_diagnostic: bool,
        rubric: Option<&Path>,
    ) -> Result<Policy> {
        let (weights, source) = match rubric {
            Some(path) => (
                read_rubric(path, suite)?,
                format!("the rubric {}", path.display()),
            ),
            None => {
                let weights = suite
                    .iter()
                    .map(|c| match c.role {
                        Role::Diagnostic if !count_diagnostic => 0.0,
                        _ => 1.0,
                    })
                    .collect();
                let source = match count_diagnostic {
                    true => "every case, 1 each".to_string(),
                    false => "the course's scenes and any hidden scenes, 1 each; whitted's \
                              diagnostic scenes inform only"
                        .to_string(),
                };
                (weights, source)
            }
        };
        if weights.iter().all(|w| *w == 0.0) {
            return Err(Error::Usage(
                "the grading policy counts no case: give at least one a weight above 0".into(),
            ));
        }
        Ok(Policy {
            grading,
            rule,
            weights,
            source,
        })
    }

    /// Whether case `i` counts towards the grade.
    pub fn counts(&self, i: usize) -> bool {
        self.weights.get(i).is_some_and(|w| *w > 0.0)
    }

    /// The grade out of 100 of a student whose cases passed as `passes` (suite order); a
    /// student whose program never ran has no passes and gets 0.
    pub fn grade(&self, passes: &[bool]) -> f64 {
        let total: f64 = self.weights.iter().sum();
        if passes.len() != self.weights.len() || total <= 0.0 {
            return 0.0;
        }
        let earned: f64 = self
            .weights
            .iter()
            .zip(passes)
            .filter(|(_, p)| **p)
            .map(|(w, _)| w)
            .sum();
        match self.grading {
            Grading::PassFail if self.counted_all(passes) => 100.0,
            Grading::PassFail => 0.0,
            Grading::Fraction => (10000.0 * earned / total).round() / 100.0,
        }
    }

    /// Whether every counted case passed.
    pub fn counted_all(&self, passes: &[bool]) -> bool {
        passes.len() == self.weights.len()
            && (0..passes.len()).all(|i| !self.counts(i) || passes[i])
    }

    /// The policy in one sentence, for the class page and every result.
    pub fn describe(&self) -> String {
        let counted = (0..self.weights.len()).filter(|&i| self.counts(i)).count();
        format!(
            "{} over {counted} counted case{} ({}); a case passes when identical or within {}",
            self.grading.name(),
            if counted == 1 { "" } else { "s" },
            self.source,
            self.rule.words()
        )
    }

    /// What of the policy decides a result, for the result's key. No allowance adds nothing,
    /// so that the results graded before there was one keep their key.
    pub fn key_bytes(&self) -> Vec<u8> {
        let weights: Vec<String> = self.weights.iter().map(|w| w.to_string()).collect();
        let allowance = match self.rule.allowance.is_none() {
            true => String::new(),
            false => format!(" beyond {}", self.rule.allowance),
        };
        format!(
            "{} {}{allowance} {}",
            self.grading.name(),
            self.rule.tolerance,
            weights.join(",")
        )
        .into_bytes()
    }
}

/// A rubric: one line per case or scene, `CASE WEIGHT`, where CASE is a case's name
/// (`tick2.xml -b 2`) or a scene's file (`tick2.xml`: every case of it), and `#` starts a
/// comment. A case the rubric does not name scores nothing.
fn read_rubric(path: &Path, suite: &[SuiteCase]) -> Result<Vec<f64>> {
    let size = std::fs::metadata(path)
        .map_err(|e| Error::io(path, "cannot read the rubric", e))?
        .len();
    if size > MAX_RUBRIC {
        return Err(Error::Usage(format!(
            "{}: a rubric of {size} bytes (at most {MAX_RUBRIC})",
            path.display()
        )));
    }
    let text =
        std::fs::read_to_string(path).map_err(|e| Error::io(path, "cannot read the rubric", e))?;
    parse_rubric(&text, suite)
        .map_err(|(line, msg)| Error::Usage(format!("{}:{line}: {msg}", path.display())))
}

/// The weights `text` gives `suite`'s cases, or the line and what is wrong with it.
fn parse_rubric(text: &str, suite: &[SuiteCase]) -> std::result::Result<Vec<f64>, (usize, String)> {
    let mut weights = vec![0.0; suite.len()];
    for (n, raw) in text.lines().enumerate() {
        let line = raw.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let (case, weight) = line
            .rsplit_once(char::is_whitespace)
            .ok_or((n + 1, format!("`{line}`: expected a case and its weight")))?;
        let case = case.trim();
        let weight: f64 = weight
            .parse()
            .ok()
            .filter(|w: &f64| w.is_finite() && *w >= 0.0 && *w <= 1e6)
            .ok_or((
                n + 1,
                format!("`{weight}`: a weight is a number from 0 to 1000000"),
            ))?;
        let matching: Vec<usize> = (0..suite.len())
            .filter(|&i| suite[i].name() == case || suite[i].file == case)
            .collect();
        if matching.is_empty() {
            let names: Vec<String> = suite.iter().map(SuiteCase::name).collect();
            return Err((
                n + 1,
                format!("`{case}` is no case of the suite ({})", names.join(", ")),
            ));
        }
        for i in matching {
            weights[i] = weight;
        }
    }
    Ok(weights)
}

#[cfg(test)]
mod tests {
    use super::*;
    use whitted_check::check::pass_rule::Allowance;
    use whitted_check::check::suite::cases;

    #[test]
    fn by_default_the_course_s_scenes_count_and_the_diagnostic_ones_inform() {
        let suite = cases();
        let policy = Policy::new(&suite, Grading::PassFail, PassRule::strict(2), false, None)
            .expect("policy");
        let counted: Vec<String> = (0..suite.len())
            .filter(|&i| policy.counts(i))
            .map(|i| suite[i].name())
            .collect();
        assert_eq!(
            counted,
            [
                "tick2.xml -b 0",
                "tick2.xml -b 1",
                "tick2.xml -b 2",
                "tick2.xml -b 3",
                "specular_test.xml -b 2"
            ]
        );
        // Failing only the diagnostic scenes still passes.
        let passes = [true, true, true, true, true, false, false];
        assert_eq!(policy.grade(&passes), 100.0);
        let fraction = Policy::new(&suite, Grading::Fraction, PassRule::strict(2), false, None)
            .expect("policy");
        assert_eq!(
            fraction.grade(&[true, false, true, true, true, false, false]),
            80.0
        );
        let all = Policy::new(&suite, Grading::PassFail, PassRule::strict(2), true, None)
            .expect("policy");
        assert_eq!(all.grade(&passes), 0.0);
        assert!(policy
            .describe()
            .starts_with("pass-fail over 5 counted cases"));
    }

    #[test]
    fn a_rubric_weighs_cases_and_scenes() {
        let suite = cases();
        let weights = parse_rubric(
            "# the course's weights\ntick2.xml -b 2  3\nspecular_test.xml 1 # all of it\n",
            &suite,
        )
        .expect("rubric");
        assert_eq!(weights, [0.0, 0.0, 3.0, 0.0, 1.0, 0.0, 0.0]);
        let policy = Policy {
            grading: Grading::Fraction,
            rule: PassRule::strict(2),
            weights,
            source: "test".into(),
        };
        assert_eq!(
            policy.grade(&[false, false, true, false, false, true, true]),
            75.0
        );
        assert_eq!(
            parse_rubric("tick3.xml 2", &suite).map_err(|(l, _)| l),
            Err(1)
        );
        assert_eq!(
            parse_rubric("\n\ntick2.xml -2", &suite).map_err(|(l, _)| l),
            Err(3)
        );
        assert_eq!(
            parse_rubric("tick2.xml", &suite).map_err(|(l, _)| l),
            Err(1)
        );
    }

    #[test]
    fn the_allowance_is_named_and_decides_the_key() {
        let suite = cases();
        let strict = Policy::new(&suite, Grading::PassFail, PassRule::strict(2), false, None)
            .expect("policy");
        assert!(strict
            .describe()
            .ends_with("a case passes when identical or within 2 of 255 in a channel"));
        // No allowance keeps the key results had before there was one.
        assert!(String::from_utf8_lossy(&strict.key_bytes()).starts_with("pass-fail 2 1,"));
        let rule = PassRule {
            tolerance: 2,
            allowance: Allowance::Pixels(10),
        };
        let allowing = Policy::new(&suite, Grading::PassFail, rule, false, None).expect("policy");
        assert!(
            allowing
                .describe()
                .ends_with("within 2 of 255 in a channel, but for at most 10 pixels"),
            "{}",
            allowing.describe()
        );
        assert_ne!(allowing.key_bytes(), strict.key_bytes());
    }
}
