//! The limits of what a frame can ask for, in one place: the command line's parsers call these
//! for their messages, and `Frame::new` calls them again, so that a library caller cannot get
//! past them either (a `Frame` of `u32::MAX` bounces would size billions of layers).

/// Most reflection bounces accepted: each bounce is a layer in the EXR, and past this depth a
/// mirror chain's contribution is far below what a float image can show.
pub const MAX_BOUNCES: u32 = 100;

/// Largest image side accepted.
pub const MAX_SIDE: u32 = 65_535;

/// Most samples per pixel accepted (a 32x32 grid).
pub const MAX_SPP: u32 = 1024;

pub fn bounces(n: i64) -> Result<u32, String> {
    if n < 0 {
        return Err(format!("bounces must be >= 0, got {n}"));
    }
    u32::try_from(n)
        .ok()
        .filter(|&n| n <= MAX_BOUNCES)
        .ok_or_else(|| format!("at most {MAX_BOUNCES} bounces are supported, got {n}"))
}

/// An image side in pixels.
pub fn side(n: i64) -> Result<u32, String> {
    u32::try_from(n)
        .ok()
        .filter(|&n| (1..=MAX_SIDE).contains(&n))
        .ok_or_else(|| format!("must be between 1 and {MAX_SIDE} pixels, got {n}"))
}

/// Samples per pixel: a square k*k.
pub fn samples(n: i64) -> Result<u32, String> {
    u32::try_from(n)
        .ok()
        .filter(|&n| n > 0 && n <= MAX_SPP && n.isqrt() * n.isqrt() == n)
        .ok_or_else(|| {
            format!(
                "samples per pixel must be a square k*k (1, 4, 9, 16, ...) up to {MAX_SPP}, got {n}"
            )
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_are_enforced() {
        assert_eq!(bounces(3), Ok(3));
        assert!(bounces(-1).unwrap_err().contains(">= 0"));
        assert!(bounces(101).is_err());
        assert!(bounces(i64::from(u32::MAX)).is_err());
        assert!(side(0).is_err() && side(70_000).is_err() && side(-5).is_err());
        assert_eq!(side(640), Ok(640));
        assert_eq!(samples(16), Ok(16));
        assert!(samples(8).unwrap_err().contains("square"));
        assert!(samples(0).is_err() && samples(2048).is_err());
    }
}
