//! The secrets in the students' and the staff's links, and the forms' CSRF tokens: 128 random
//! bits each (the viewer's token), compared in constant time so that the time an answer takes
//! says nothing of how much of a guess was right.

/// A new secret: 32 hex digits from the system's randomness.
pub fn new() -> String {
    whitted_view::token::new()
}

/// Whether `given` is `expected`, in a time that depends on their lengths only.
pub fn same(given: &str, expected: &str) -> bool {
    let (a, b) = (given.as_bytes(), expected.as_bytes());
    if a.len() != b.len() {
        return false;
    }
    let diff = a.iter().zip(b).fold(0u8, |acc, (x, y)| acc | (x ^ y));
    std::hint::black_box(diff) == 0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn secrets_are_128_bits_of_hex_and_differ() {
        let (a, b) = (new(), new());
        assert_eq!(a.len(), 32);
        assert!(a.bytes().all(|c| c.is_ascii_hexdigit()));
        assert_ne!(a, b);
    }

    #[test]
    fn comparison_needs_every_byte() {
        assert!(same("0123abcd", "0123abcd"));
        assert!(!same("0123abce", "0123abcd"));
        assert!(!same("0123abc", "0123abcd"));
        assert!(!same("", "0123abcd"));
    }
}
