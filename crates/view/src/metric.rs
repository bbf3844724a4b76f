//! The error metrics the viewer compares an image with its reference by (tev's five, so that
//! numbers read in one viewer mean the same in the other). Evaluated here, on the server, so
//! that the page, the statistics and the tests share one definition (docs/view.md).

/// Added to the reference in the relative metrics, so that a black reference pixel does not
/// divide by zero (tev's 0.01).
pub const RELATIVE_EPSILON: f64 = 0.01;

/// A per-channel comparison of image value `a` with reference value `b`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Metric {
    /// a - b
    Error,
    /// |a - b|
    AbsoluteError,
    /// (a - b)^2
    SquaredError,
    /// |a - b| / (|b| + 0.01)
    RelativeAbsoluteError,
    /// (a - b)^2 / (b^2 + 0.01)
    RelativeSquaredError,
}

impl Metric {
    pub const ALL: [Metric; 5] = [
        Metric::Error,
        Metric::AbsoluteError,
        Metric::SquaredError,
        Metric::RelativeAbsoluteError,
        Metric::RelativeSquaredError,
    ];

    /// The name in requests and on the page.
    pub fn name(self) -> &'static str {
        match self {
            Metric::Error => "error",
            Metric::AbsoluteError => "absolute-error",
            Metric::SquaredError => "squared-error",
            Metric::RelativeAbsoluteError => "relative-absolute-error",
            Metric::RelativeSquaredError => "relative-squared-error",
        }
    }

    pub fn from_name(name: &str) -> Option<Metric> {
        Metric::ALL.into_iter().find(|m| m.name() == name)
    }

    /// The metric of one channel value, in f64 from the stored f32s, stored back as f32 (the
    /// precision of everything else the page is sent). NaN in, NaN out.
    pub fn apply(self, a: f32, b: f32) -> f32 {
        let (a, b) = (f64::from(a), f64::from(b));
        let d = a - b;
        let value = match self {
            Metric::Error => d,
            Metric::AbsoluteError => d.abs(),
            Metric::SquaredError => d * d,
            Metric::RelativeAbsoluteError => d.abs() / (b.abs() + RELATIVE_EPSILON),
            Metric::RelativeSquaredError => d * d / (b * b + RELATIVE_EPSILON),
        };
        value as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_metrics_are_tevs() {
        let at = |m: Metric| m.apply(0.75, 0.25);
        assert_eq!(at(Metric::Error), 0.5);
        assert_eq!(at(Metric::AbsoluteError), 0.5);
        assert_eq!(Metric::Error.apply(0.25, 0.75), -0.5);
        assert_eq!(at(Metric::SquaredError), 0.25);
        assert_eq!(at(Metric::RelativeAbsoluteError), (0.5 / 0.26) as f32);
        assert_eq!(at(Metric::RelativeSquaredError), (0.25 / 0.0725) as f32);
        assert!(Metric::SquaredError.apply(f32::NAN, 0.0).is_nan());
        for m in Metric::ALL {
            assert_eq!(Metric::from_name(m.name()), Some(m));
            assert_eq!(m.apply(1.5, 1.5), 0.0);
        }
    }
}
