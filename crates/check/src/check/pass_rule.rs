//! When a case passes: the one rule `check` and `grade` share. A pixel is *beyond* the
//! tolerance when one of its channels differs from the reference by more than the channel
//! tolerance (2 of 255 by default); a case passes when at most the allowance's pixels are
//! beyond it (none by default). The allowance exists because the course's own tester evidently
//! lets a few pixels through: finished projects handed in as such differ from the course's
//! expected images in tens of pixels by more than 2, and a strict rule fails them all.

use std::fmt;

/// The channel tolerances whose counts of pixels beyond are kept per case (0 to this, in
/// LSB), so that `grade --calibrate` can replay the rule at any of them from the results
/// alone. A tester that allows more than 8 of 255 would pass visible mistakes.
pub const KEPT_TOLERANCES: usize = 9;

/// How many pixels may be beyond the channel tolerance (`--max-beyond`): a count, or a share
/// of the image's pixels.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Allowance {
    /// At most this many pixels.
    Pixels(u64),
    /// At most this share of the image's pixels, in millionths of them (0.1% is 1000): kept
    /// as an integer so that the same percentage allows the same pixels on every machine.
    PerMillion(u64),
}

/// Decimals a percentage may have: 0.0001% is one pixel in a million.
const PERCENT_DECIMALS: usize = 4;

impl Allowance {
    /// No pixel beyond the tolerance: the rule whitted has always had.
    pub const NONE: Allowance = Allowance::Pixels(0);

    /// Reads `N` (a whole number of pixels) or `P%` (a percentage from 0 to 100, at most four
    /// decimals), and nothing else: no sign, no blanks, no exponent, no NaN.
    pub fn parse(text: &str) -> Result<Allowance, String> {
        let expected = || {
            format!(
                "expected a number of pixels (`10`) or a percentage of the image's pixels from 0 \
                 to 100 (`0.1%`), got `{text}`"
            )
        };
        match text.strip_suffix('%') {
            None => digits(text)
                .and_then(|d| d.parse::<u64>().ok())
                .map(Allowance::Pixels)
                .ok_or_else(expected),
            Some(percent) => {
                let (whole, fraction) = match percent.split_once('.') {
                    Some((whole, fraction)) => (whole, Some(fraction)),
                    None => (percent, None),
                };
                let whole = digits(whole)
                    .and_then(|w| w.parse::<u64>().ok())
                    .ok_or_else(expected)?;
                let fraction: u64 = match fraction {
                    None => 0,
                    Some(f) if f.len() <= PERCENT_DECIMALS => digits(f)
                        .and_then(|f| format!("{f:0<PERCENT_DECIMALS$}").parse().ok())
                        .ok_or_else(expected)?,
                    Some(_) => return Err(expected()),
                };
                let per_million = whole
                    .checked_mul(10_000)
                    .and_then(|w| w.checked_add(fraction))
                    .filter(|&p| p <= 1_000_000)
                    .ok_or_else(|| format!("`{text}`: a percentage is at most 100%"))?;
                Ok(Allowance::PerMillion(per_million))
            }
        }
    }

    /// The pixels allowed beyond the tolerance in an image of `pixels` pixels.
    pub fn pixels_of(self, pixels: u64) -> u64 {
        match self {
            Allowance::Pixels(n) => n,
            Allowance::PerMillion(p) => {
                u64::try_from(u128::from(pixels) * u128::from(p) / 1_000_000).unwrap_or(u64::MAX)
            }
        }
    }

    /// Whether no pixel may be beyond the tolerance.
    pub fn is_none(self) -> bool {
        self.pixels_of(u64::MAX) == 0
    }
}

/// `10` or `0.1%`: what `--max-beyond` reads back.
impl fmt::Display for Allowance {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Allowance::Pixels(n) => write!(f, "{n}"),
            Allowance::PerMillion(p) => {
                let fraction = format!("{:04}", p % 10_000);
                let fraction = fraction.trim_end_matches('0');
                match fraction.is_empty() {
                    true => write!(f, "{}%", p / 10_000),
                    false => write!(f, "{}.{fraction}%", p / 10_000),
                }
            }
        }
    }
}

/// `text` when it is one or more ASCII digits.
fn digits(text: &str) -> Option<&str> {
    (!text.is_empty() && text.bytes().all(|b| b.is_ascii_digit())).then_some(text)
}

/// When a case passes: the channel tolerance (`--tolerance`) and the pixel allowance
/// (`--max-beyond`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct PassRule {
    /// The largest difference of a channel, in LSB, that is not beyond.
    pub tolerance: u8,
    pub allowance: Allowance,
}

impl PassRule {
    /// `tolerance` with no pixel allowed beyond it.
    pub const fn strict(tolerance: u8) -> PassRule {
        PassRule {
            tolerance,
            allowance: Allowance::NONE,
        }
    }

    /// Whether an image of `pixels` pixels, `beyond` of them beyond the tolerance, passes.
    pub fn passes(&self, beyond: u64, pixels: u64) -> bool {
        beyond <= self.allowance.pixels_of(pixels)
    }

    /// The rule in words: "2 of 255 in a channel", and with an allowance "2 of 255 in a
    /// channel, but for at most 10 pixels" (or "0.1% of the image's pixels").
    pub fn words(&self) -> String {
        let channel = format!("{} of 255 in a channel", self.tolerance);
        match self.allowance {
            a if a.is_none() => channel,
            Allowance::Pixels(n) => format!(
                "{channel}, but for at most {n} pixel{}",
                if n == 1 { "" } else { "s" }
            ),
            a @ Allowance::PerMillion(_) => {
                format!("{channel}, but for at most {a} of the image's pixels")
            }
        }
    }

    /// The allowance in words: "at most 10 pixels beyond ±2", "at most 0.1% of the pixels
    /// beyond ±2".
    pub fn allowance_words(&self) -> String {
        let t = self.tolerance;
        match self.allowance {
            Allowance::Pixels(n) => format!(
                "at most {n} pixel{} beyond ±{t}",
                if n == 1 { "" } else { "s" }
            ),
            a @ Allowance::PerMillion(_) => format!("at most {a} of the pixels beyond ±{t}"),
        }
    }

    /// How a case that passes with pixels beyond the tolerance passes: "5 pixels beyond ±2,
    /// allowed up to 10" (and the percentage it comes from). None when none is beyond.
    pub fn allowed_words(&self, beyond: u64, pixels: u64) -> Option<String> {
        if beyond == 0 {
            return None;
        }
        let allowed = self.allowance.pixels_of(pixels);
        let share = match self.allowance {
            Allowance::PerMillion(_) => format!(" ({})", self.allowance),
            Allowance::Pixels(_) => String::new(),
        };
        Some(format!(
            "{beyond} pixel{} beyond ±{}, allowed up to {allowed}{share}",
            if beyond == 1 { "" } else { "s" },
            self.tolerance
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_a_count_or_a_percentage_and_nothing_else() {
        assert_eq!(Allowance::parse("0"), Ok(Allowance::Pixels(0)));
        assert_eq!(Allowance::parse("57"), Ok(Allowance::Pixels(57)));
        assert_eq!(Allowance::parse("0.1%"), Ok(Allowance::PerMillion(1000)));
        assert_eq!(
            Allowance::parse("100%"),
            Ok(Allowance::PerMillion(1_000_000))
        );
        assert_eq!(Allowance::parse("0.0001%"), Ok(Allowance::PerMillion(1)));
        assert_eq!(Allowance::parse("1.25%"), Ok(Allowance::PerMillion(12_500)));
        for bad in [
            "",
            "-1",
            "+3",
            " 5",
            "5 ",
            "1.5",
            "1e3",
            "NaN",
            "nan%",
            "inf%",
            "%",
            "-1%",
            "100.01%",
            "101%",
            "0.00001%",
            "1.%",
            ".5%",
            "1..2%",
            "abc",
            "5%%",
            "18446744073709551616",
            "99999999999999999999%",
        ] {
            assert!(Allowance::parse(bad).is_err(), "`{bad}` was read");
        }
        assert!(Allowance::parse("101%")
            .unwrap_err()
            .contains("at most 100%"));
    }

    #[test]
    fn prints_what_it_reads() {
        for text in ["0", "10", "0.1%", "1%", "100%", "0.0001%", "2.5%"] {
            let allowance = Allowance::parse(text).expect("an allowance");
            assert_eq!(allowance.to_string(), text);
        }
    }

    #[test]
    fn a_percentage_is_of_the_image_s_pixels_rounded_down() {
        let tenth = Allowance::parse("0.1%").expect("0.1%");
        assert_eq!(tenth.pixels_of(640 * 480), 307);
        assert_eq!(tenth.pixels_of(800 * 600), 480);
        assert_eq!(tenth.pixels_of(999), 0);
        // 0.57% of 10000 is 57 exactly, which floating point would make 56.
        assert_eq!(
            Allowance::parse("0.57%").expect("0.57%").pixels_of(10_000),
            57
        );
        assert_eq!(Allowance::Pixels(5).pixels_of(1), 5);
        assert!(Allowance::parse("0%").expect("0%").is_none());
        assert!(!Allowance::parse("0.0001%").expect("a share").is_none());
    }

    #[test]
    fn a_case_passes_with_at_most_the_allowance_beyond() {
        let strict = PassRule::strict(2);
        assert!(strict.passes(0, 100));
        assert!(!strict.passes(1, 100));
        let ten = PassRule {
            tolerance: 2,
            allowance: Allowance::Pixels(10),
        };
        assert!(ten.passes(10, 100));
        assert!(!ten.passes(11, 100));
        let share = PassRule {
            tolerance: 2,
            allowance: Allowance::parse("1%").expect("1%"),
        };
        assert!(share.passes(3072, 640 * 480));
        assert!(!share.passes(3073, 640 * 480));
    }

    #[test]
    fn says_what_it_allows() {
        assert_eq!(PassRule::strict(2).words(), "2 of 255 in a channel");
        let ten = PassRule {
            tolerance: 2,
            allowance: Allowance::Pixels(10),
        };
        assert_eq!(
            ten.words(),
            "2 of 255 in a channel, but for at most 10 pixels"
        );
        assert_eq!(
            ten.allowed_words(5, 100).as_deref(),
            Some("5 pixels beyond ±2, allowed up to 10")
        );
        assert_eq!(ten.allowed_words(0, 100), None);
        assert_eq!(ten.allowance_words(), "at most 10 pixels beyond ±2");
        let share = PassRule {
            tolerance: 3,
            allowance: Allowance::parse("0.1%").expect("0.1%"),
        };
        assert_eq!(
            share.words(),
            "3 of 255 in a channel, but for at most 0.1% of the image's pixels"
        );
        assert_eq!(
            share.allowed_words(1, 640 * 480).as_deref(),
            Some("1 pixel beyond ±3, allowed up to 307 (0.1%)")
        );
    }
}
