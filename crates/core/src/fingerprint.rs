//! A stable 64-bit fingerprint of bytes (FNV-1a), for the render identity that `merge` checks.
//! Hand-written on purpose: the value is stored in files and must never change between Rust
//! releases or platforms, which std's `DefaultHasher` does not promise, and it needs no
//! cryptographic strength (it tells renders apart, it does not resist forgery).

const OFFSET_BASIS: u64 = 0xcbf2_9ce4_8422_2325;
const PRIME: u64 = 0x0000_0100_0000_01b3;

/// The FNV-1a hash of `parts`, one after another, as 16 hex digits.
pub fn fingerprint(parts: &[&[u8]]) -> String {
    let hash = parts
        .iter()
        .flat_map(|part| part.iter())
        .fold(OFFSET_BASIS, |hash, &byte| {
            (hash ^ u64::from(byte)).wrapping_mul(PRIME)
        });
    format!("{hash:016x}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_the_published_fnv1a_test_vectors() {
        assert_eq!(fingerprint(&[b""]), "cbf29ce484222325");
        assert_eq!(fingerprint(&[b"a"]), "af63dc4c8601ec8c");
        assert_eq!(fingerprint(&[b"foo", b"bar"]), fingerprint(&[b"foobar"]));
    }
}
