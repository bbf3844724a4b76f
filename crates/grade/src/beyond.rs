//! What a result keeps of each case's difference so that the pass rule can be replayed at
//! another channel tolerance and pixel allowance without the images or a rerun
//! (`grade --calibrate`): the image's pixels, its largest channel difference, and how many
//! pixels are beyond each channel tolerance from 0 to 8. Eleven numbers a case, which a
//! class of hundreds keeps without noticing.

use serde::{Deserialize, Serialize};

use whitted_check::check::pass_rule::PassRule;
use whitted_check::check::program::{CaseOutcome, RunStatus};

/// One case's counts, as `extra_data.beyond[]` of a result.json.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct CaseBeyond {
    /// The case's name, as its test's.
    pub case: String,
    /// How it ended (`ok`, `crashed`, `timeout`, ...): a case that wrote no image to check
    /// fails by any rule, and has no counts.
    pub status: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pixels: Option<u64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_difference: Option<u8>,
    /// `beyond_at[t]`: the pixels with a channel off by more than t, for t from 0.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub beyond_at: Vec<u64>,
}

impl CaseBeyond {
    /// The counts of `outcome`.
    pub fn of(outcome: &CaseOutcome) -> CaseBeyond {
        let mut counts = CaseBeyond {
            case: outcome.name.clone(),
            status: outcome.status.name().to_string(),
            pixels: None,
            max_difference: None,
            beyond_at: Vec::new(),
        };
        if let RunStatus::Ok(report) = &outcome.status {
            let d = &report.difference;
            counts.pixels = Some(d.pixels());
            counts.max_difference = Some(d.max_difference);
            counts.beyond_at = d.beyond_at.to_vec();
        }
        counts
    }

    /// Whether the case passes by `rule`; None when the counts cannot say (a tolerance past
    /// those kept, below the largest difference, or a record without counts).
    pub fn passes(&self, rule: PassRule) -> Option<bool> {
        // `RunStatus::Ok`'s name: every other status wrote no image.
        if self.status != "ok" {
            return Some(false);
        }
        let (pixels, max) = (self.pixels?, self.max_difference?);
        let beyond = match self.beyond_at.get(usize::from(rule.tolerance)) {
            Some(&n) => n,
            None if max <= rule.tolerance => 0,
            None => return None,
        };
        Some(rule.passes(beyond, pixels))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use whitted_check::check::pass_rule::Allowance;

    fn counts(status: &str, max: u8, beyond_at: Vec<u64>) -> CaseBeyond {
        CaseBeyond {
            case: "tick2.xml -b 2".into(),
            status: status.into(),
            pixels: Some(640 * 480),
            max_difference: Some(max),
            beyond_at,
        }
    }

    #[test]
    fn replays_the_rule_at_any_kept_tolerance_and_allowance() {
        // 57 pixels beyond 2, 5 beyond 3, none beyond 4.
        let c = counts("ok", 4, vec![900, 300, 57, 5, 0, 0, 0, 0, 0]);
        let rule = |tolerance, allowance| PassRule {
            tolerance,
            allowance,
        };
        assert_eq!(c.passes(PassRule::strict(2)), Some(false));
        assert_eq!(c.passes(rule(2, Allowance::Pixels(57))), Some(true));
        assert_eq!(c.passes(rule(2, Allowance::Pixels(56))), Some(false));
        assert_eq!(c.passes(rule(3, Allowance::Pixels(5))), Some(true));
        assert_eq!(c.passes(PassRule::strict(4)), Some(true));
        // 0.1% of 307200 is 307: 300 beyond 1 pass.
        let tenth = Allowance::parse("0.1%").expect("0.1%");
        assert_eq!(c.passes(rule(1, tenth)), Some(true));
        assert_eq!(c.passes(rule(0, tenth)), Some(false));
        // Past the kept tolerances the largest difference still answers.
        assert_eq!(c.passes(PassRule::strict(20)), Some(true));
        let far = counts("ok", 30, vec![9; 9]);
        assert_eq!(far.passes(PassRule::strict(20)), None);
        assert_eq!(
            counts("timeout", 0, Vec::new()).passes(PassRule::strict(255)),
            Some(false)
        );
    }

    #[test]
    fn reads_what_it_writes() {
        let c = counts("ok", 4, vec![3, 2, 1, 1, 0, 0, 0, 0, 0]);
        let json = serde_json::to_string(&c).expect("json");
        assert_eq!(
            json,
            r#"{"case":"tick2.xml -b 2","status":"ok","pixels":307200,"max_difference":4,"beyond_at":[3,2,1,1,0,0,0,0,0]}"#
        );
        assert_eq!(serde_json::from_str::<CaseBeyond>(&json).ok(), Some(c));
        let crashed: CaseBeyond =
            serde_json::from_str(r#"{"case":"a","status":"crashed"}"#).expect("crashed");
        assert_eq!(crashed.passes(PassRule::strict(2)), Some(false));
    }
}
