//! How numbers are written for people: compact in tables, exact in error messages.

/// `bytes` in GiB, one decimal, as messages show sizes.
pub fn gib(bytes: u64) -> String {
    format!("{:.1} GiB", bytes as f64 / f64::from(1u32 << 30))
}

/// `v` for JSON, which has no NaN or infinities: `null` for those.
pub fn finite_or_null(v: f64) -> serde_json::Value {
    if v.is_finite() {
        serde_json::json!(v)
    } else {
        serde_json::Value::Null
    }
}

/// A compact, readable number for tables: 4 significant digits, scientific when far from 1.
pub fn compact(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if (1e-3..1e5).contains(&v.abs()) {
        let digits = (3 - v.abs().log10().floor() as i32).max(0) as usize;
        format!("{v:.digits$}")
    } else {
        format!("{v:.3e}")
    }
}

/// A number quoted back in an error message: every digit it has, in scientific notation when
/// tiny or huge, so the user recognises the value they wrote.
pub fn exact(v: f64) -> String {
    if v == 0.0 || (1e-6..1e15).contains(&v.abs()) {
        v.to_string()
    } else {
        format!("{v:e}")
    }
}

/// A number as a person writes it in a sentence (the check's fitted numbers): three
/// significant digits, no trailing zeros, scientific only when tiny or huge.
pub fn plain(x: f64) -> String {
    if x != 0.0 && (x.abs() < 1e-4 || x.abs() >= 1e6) {
        return format!("{x:.2e}").replace(".00e", "e");
    }
    let digits = (2 - x.abs().log10().floor() as i32).clamp(0, 6) as usize;
    let text = format!("{x:.digits$}");
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plain_numbers_read_as_written() {
        assert_eq!(plain(20.0), "20");
        assert_eq!(plain(1.0), "1");
        assert_eq!(plain(0.5), "0.5");
        assert_eq!(plain(0.0001), "0.0001");
        assert_eq!(plain(1e-5), "1e-5");
        assert_eq!(plain(123.456), "123");
        assert_eq!(plain(1.234), "1.23");
    }

    #[test]
    fn compact_numbers_have_four_significant_digits() {
        assert_eq!(compact(0.0), "0");
        assert_eq!(compact(0.12345), "0.1235");
        assert_eq!(compact(12.5), "12.50");
        assert_eq!(compact(1.5e-7), "1.500e-7");
    }

    #[test]
    fn exact_numbers_keep_every_digit() {
        assert_eq!(exact(0.1), "0.1");
        assert_eq!(exact(1e200), "1e200");
        assert_eq!(exact(-2.5e-9), "-2.5e-9");
    }
}
