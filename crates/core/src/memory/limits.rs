//! How much memory this process may still use: the least of what the system has free and what
//! the process is allowed (address-space and data limits, its control group's memory limit).
//! Read from Linux's `/proc` and `/sys` text files, so no system-call binding is needed; on
//! other systems every source is simply absent.

use std::fs;
use std::sync::atomic::{AtomicU64, Ordering};

/// A cap set by the program itself (`limit_to`), or `u64::MAX`.
static CAP: AtomicU64 = AtomicU64::new(u64::MAX);

/// Caps what `available_bytes` reports, for a host that enforces a limit the system does not
/// show (a fuzzer's RSS limit).
pub fn limit_to(bytes: u64) {
    CAP.store(bytes, Ordering::Relaxed);
}

/// The least of every limit that applies now, or `None` if none could be read.
pub fn available_bytes() -> Option<u64> {
    let cap = CAP.load(Ordering::Relaxed);
    [
        mem_available(),
        rlimit_headroom("Max address space", "VmSize"),
        rlimit_headroom("Max data size", "VmData"),
        cgroup_headroom(),
        (cap != u64::MAX).then_some(cap),
    ]
    .into_iter()
    .flatten()
    .min()
}

/// Linux `MemAvailable`: what the system can give without swapping.
fn mem_available() -> Option<u64> {
    kib_field(&fs::read_to_string("/proc/meminfo").ok()?, "MemAvailable:")
}

/// A soft resource limit (`ulimit -v`, `ulimit -d`) less what the process already uses of it.
fn rlimit_headroom(limit: &str, usage: &str) -> Option<u64> {
    let limits = fs::read_to_string("/proc/self/limits").ok()?;
    let soft = limits
        .lines()
        .find(|l| l.starts_with(limit))?
        .get(limit.len()..)?
        .split_whitespace()
        .next()?
        .parse::<u64>()
        .ok()?;
    let used = kib_field(
        &fs::read_to_string("/proc/self/status").ok()?,
        &format!("{usage}:"),
    )
    .unwrap_or(0);
    Some(soft.saturating_sub(used))
}

/// The memory limit of the process's control group less its usage (cgroup v2 `memory.max`, or
/// v1 `memory.limit_in_bytes`), as containers and batch schedulers set it.
fn cgroup_headroom() -> Option<u64> {
    let groups = fs::read_to_string("/proc/self/cgroup").ok()?;
    for line in groups.lines() {
        let mut parts = line.splitn(3, ':');
        let (_, controllers, path) = (parts.next()?, parts.next()?, parts.next()?);
        let (limit, usage) = if controllers.is_empty() {
            let dir = format!("/sys/fs/cgroup{path}");
            (format!("{dir}/memory.max"), format!("{dir}/memory.current"))
        } else if controllers.split(',').any(|c| c == "memory") {
            let dir = format!("/sys/fs/cgroup/memory{path}");
            (
                format!("{dir}/memory.limit_in_bytes"),
                format!("{dir}/memory.usage_in_bytes"),
            )
        } else {
            continue;
        };
        let Some(limit) = read_number(&limit) else {
            continue;
        };
        return Some(limit.saturating_sub(read_number(&usage).unwrap_or(0)));
    }
    None
}

/// A file holding one number (`max` or unreadable: no limit).
fn read_number(path: &str) -> Option<u64> {
    fs::read_to_string(path).ok()?.trim().parse().ok()
}

/// `Field:   1234 kB` -> 1234 * 1024.
fn kib_field(text: &str, field: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with(field))?;
    let kib: u64 = line[field.len()..]
        .split_whitespace()
        .next()?
        .parse()
        .ok()?;
    Some(kib.saturating_mul(1024))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_parse_and_the_minimum_is_taken() {
        assert_eq!(
            kib_field("MemAvailable:   2048 kB\n", "MemAvailable:"),
            Some(2 << 20)
        );
        assert_eq!(kib_field("VmSize: x\n", "VmSize:"), None);
        let available = available_bytes().expect("Linux reports memory");
        assert!(available > 0);
        assert!(available <= mem_available().expect("MemAvailable"));
    }
}
