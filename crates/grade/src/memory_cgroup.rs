//! A memory limit the kernel enforces on everything in one sandbox, where one can be had: a
//! cgroup of its own per run, under this process's own cgroup (the v1 memory controller, or v2
//! where the memory controller is delegated here). `-Xmx` bounds only the JVM's heap; memory
//! taken outside it (`Unsafe.allocateMemory`, thread stacks, a native library) is bounded here,
//! and the kernel's OOM killer ends the run, which is then named `out-of-memory`.
//!
//! A run enters its cgroup through `sh -c 'echo 0 > cgroup.procs; exec ...'` in front of the
//! sandbox's command: the shell moves itself before anything of the student's exists, and
//! everything it execs and forks stays inside. Where no cgroup can be made (no controller, no
//! permission) there is none, and `-Xmx` and the other limits stand alone (docs/grade.md).

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// Which cgroup interface the memory controller has here.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Version {
    V1,
    V2,
}

/// Where this process may make cgroups with a memory limit.
#[derive(Debug, Clone)]
pub struct CgroupRoot {
    dir: PathBuf,
    version: Version,
}

/// One run's cgroup, removed when dropped (its processes killed by then).
#[derive(Debug)]
pub struct RunCgroup {
    dir: PathBuf,
    version: Version,
}

impl CgroupRoot {
    /// This process's memory cgroup, if a child with a limit can be made in it.
    pub fn find() -> Option<CgroupRoot> {
        let own = std::fs::read_to_string("/proc/self/cgroup").ok()?;
        let mut found = Vec::new();
        for line in own.lines() {
            let mut parts = line.splitn(3, ':');
            let (_, controllers, path) = (parts.next()?, parts.next()?, parts.next()?);
            let path = path.trim_start_matches('/');
            if controllers.split(',').any(|c| c == "memory") {
                found.push(CgroupRoot {
                    dir: Path::new("/sys/fs/cgroup/memory").join(path),
                    version: Version::V1,
                });
            } else if controllers.is_empty() {
                found.push(CgroupRoot {
                    dir: Path::new("/sys/fs/cgroup").join(path),
                    version: Version::V2,
                });
            }
        }
        found.into_iter().find(|root| root.works())
    }

    /// Whether a child made here gets a memory limit (tried once, with a child of its own).
    fn works(&self) -> bool {
        let probe = self.child_named(&format!("whitted-probe-{}", std::process::id()), 64 << 20);
        probe.is_some()
    }

    /// A cgroup for one run, limited to `bytes`; None when it cannot be made.
    pub fn child(&self, bytes: u64) -> Option<RunCgroup> {
        static NEXT: AtomicU64 = AtomicU64::new(0);
        let n = NEXT.fetch_add(1, Ordering::Relaxed);
        self.child_named(&format!("whitted-{}-{n}", std::process::id()), bytes)
    }

    fn child_named(&self, name: &str, bytes: u64) -> Option<RunCgroup> {
        let dir = self.dir.join(name);
        std::fs::create_dir(&dir).ok()?;
        let cgroup = RunCgroup {
            dir,
            version: self.version,
        };
        let limit = match self.version {
            Version::V1 => "memory.limit_in_bytes",
            Version::V2 => "memory.max",
        };
        std::fs::write(cgroup.dir.join(limit), bytes.to_string()).ok()?;
        // No swap to spill into, where the kernel has it to limit (best effort).
        let _ = match self.version {
            Version::V1 => std::fs::write(
                cgroup.dir.join("memory.memsw.limit_in_bytes"),
                bytes.to_string(),
            ),
            Version::V2 => std::fs::write(cgroup.dir.join("memory.swap.max"), "0"),
        };
        Some(cgroup)
    }
}

impl RunCgroup {
    /// The file a process writes `0` to to enter this cgroup.
    pub fn procs(&self) -> PathBuf {
        self.dir.join("cgroup.procs")
    }

    /// Whether the kernel killed a process of this cgroup for its memory limit.
    pub fn oom_killed(&self) -> bool {
        let file = match self.version {
            Version::V1 => "memory.oom_control",
            Version::V2 => "memory.events",
        };
        std::fs::read_to_string(self.dir.join(file))
            .ok()
            .and_then(|text| {
                text.lines()
                    .find_map(|l| l.strip_prefix("oom_kill "))
                    .and_then(|n| n.trim().parse::<u64>().ok())
            })
            .is_some_and(|n| n > 0)
    }
}

impl Drop for RunCgroup {
    fn drop(&mut self) {
        // Its processes were killed before: the kernel may take a moment to let them go.
        for _ in 0..50 {
            if std::fs::remove_dir(&self.dir).is_ok() || !self.dir.exists() {
                return;
            }
            std::thread::sleep(std::time::Duration::from_millis(10));
        }
    }
}
