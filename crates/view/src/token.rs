//! The per-run token in the viewer's URL: 128 random bits from the system.

use std::io::Read;

/// 32 hex digits from /dev/urandom; where that cannot be read, from the clock and the process
/// id (still unguessable from another origin, which cannot read the URL).
pub fn new() -> String {
    let mut bytes = [0u8; 16];
    let random = std::fs::File::open("/dev/urandom").and_then(|mut f| f.read_exact(&mut bytes));
    if random.is_err() {
        let nanos = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos());
        let seed = format!("{nanos}:{}", std::process::id());
        let a = whitted_core::fingerprint::fingerprint(&[seed.as_bytes()]);
        let b = whitted_core::fingerprint::fingerprint(&[a.as_bytes(), seed.as_bytes()]);
        return format!("{a}{b}");
    }
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}
