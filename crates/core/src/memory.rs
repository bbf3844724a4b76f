//! Refusing renders that cannot fit in memory before allocating anything, so a typo in
//! `--width` is a clear message instead of an out-of-memory kill minutes later.

mod limits;

pub use limits::{available_bytes, limit_to};

use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::numbers::gib;

/// Bytes a render of this size needs at its peak, streamed in strips of `strip_rows` rows:
/// two strips of f64 beauty and f32 channels (one rendering, one being written), the EXR
/// blocks of two strips (one compressing in the background while the next is packed: packed
/// and predicted copies, the compressed bytes written over the packed ones; six copies of a
/// strip's f32 values are counted, leaving the allocator some slack) and its
/// offset table, and the PNG's display values and bytes for a strip. The image's height only
/// adds the offset table.
pub fn render_bytes(width: u32, height: u32, channels: usize, exr: bool, strip_rows: u32) -> u64 {
    let channels = channels as u64;
    let strip = u64::from(width).saturating_mul(u64::from(strip_rows.min(height)));
    let film = 2 * (24 + 4 * channels);
    let writing = if exr { 6 * 4 * channels } else { 0 } + 24 + 3;
    let table = if exr { 8 * u64::from(height) } else { 0 };
    strip.saturating_mul(film + writing).saturating_add(table)
}

/// An error if `needed` bytes are more than `available`.
pub fn check(needed: u64, available: Option<u64>, what: &str) -> Result<()> {
    match available {
        Some(available) if needed > available => Err(Error::Allocation {
            what: format!("{what}; {} is available", gib(available)),
            bytes: needed,
        }),
        _ => Ok(()),
    }
}

/// A vector of `len` copies of `value`, or an error instead of an abort when the allocation
/// fails. Filled on every core: for a 4K film, touching the fresh pages is a noticeable
/// serial step otherwise.
pub fn filled<T: Clone + Send + Sync>(len: usize, value: T) -> Result<Vec<T>> {
    let mut v = Vec::new();
    v.try_reserve_exact(len).map_err(|_| Error::Allocation {
        what: format!("{len} values"),
        bytes: (len as u64).saturating_mul(std::mem::size_of::<T>() as u64),
    })?;
    v.par_extend(rayon::iter::repeat_n(value, len));
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn estimates_grow_with_size_and_layers() {
        let small = render_bytes(640, 480, 4, false, 16);
        assert!(small > 640 * 16 * 2 * 24);
        assert!(render_bytes(640, 480, 53, true, 16) > 10 * small);
        // A strip, not the image: a taller image costs only its offset table.
        let tall = render_bytes(640, 480_000, 53, true, 16);
        assert_eq!(
            tall - render_bytes(640, 480, 53, true, 16),
            8 * (480_000 - 480)
        );
        assert!(render_bytes(u32::MAX, u32::MAX, 1000, true, 16) > 1 << 50);
    }

    #[test]
    fn too_large_is_refused_with_numbers() {
        let err = check(10 << 30, Some(1 << 30), "a render")
            .unwrap_err()
            .to_string();
        assert!(err.contains("10.0 GiB") && err.contains("1.0 GiB"), "{err}");
        assert!(check(1, Some(2), "x").is_ok());
        assert!(check(u64::MAX, None, "x").is_ok());
        assert!(available_bytes().is_some_and(|b| b > 0));
    }

    #[test]
    fn impossible_allocations_are_errors() {
        assert!(filled(usize::MAX / 2, 0u64).is_err());
        assert_eq!(filled(3, 7u8).expect("small"), [7, 7, 7]);
    }
}
