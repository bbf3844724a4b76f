//! The CPU time (user + system) of everything one project's run started: the compiler, the
//! student's JVMs in the sandbox, and the checks. The sandboxed programs are reaped inside
//! bubblewrap's PID namespace, so their time never reaches this process's
//! `RUSAGE_CHILDREN` (measured: 0.4 s of it for a run whose cgroup counted 6.6 s). A cgroup
//! that counts CPU does see them: the run moves itself into one of its own (cgroup v1's
//! `cpuacct`, whose hierarchy is apart from the memory cgroups grade's sandbox makes per case,
//! or v2's `unified` hierarchy mounted beside v1), and everything it starts stays there.
//! On a pure cgroup v2 machine the run does not move itself: grade's memory cgroups are made
//! under the run's own cgroup, which must then hold no process, and the limit matters more
//! than the count. There, and where no cgroup may be made, the time is not measured (None).

use std::path::{Path, PathBuf};

/// The hierarchies that count CPU, tried in order: (the mount, the file that counts).
const HIERARCHIES: [(&str, Counter); 3] = [
    ("/sys/fs/cgroup/cpuacct", Counter::Nanoseconds),
    ("/sys/fs/cgroup/cpu,cpuacct", Counter::Nanoseconds),
    ("/sys/fs/cgroup/unified", Counter::CpuStat),
];

#[derive(Debug, Clone, Copy)]
enum Counter {
    /// v1: `cpuacct.usage`, nanoseconds.
    Nanoseconds,
    /// v2: `cpu.stat`'s `usage_usec`.
    CpuStat,
}

/// This process inside a cgroup of its own that counts its CPU; it leaves and removes it when
/// dropped.
pub struct Account {
    dir: PathBuf,
    parent: PathBuf,
    counter: Counter,
}

impl Account {
    /// Moves this process into a new counting cgroup, if one can be made here.
    pub fn start() -> Option<Account> {
        HIERARCHIES
            .iter()
            .find_map(|(mount, counter)| Account::under(Path::new(mount), *counter))
    }

    fn under(mount: &Path, counter: Counter) -> Option<Account> {
        let parent = own_cgroup(mount, counter)?;
        let dir = parent.join(format!("whitted-serve-run-{}", std::process::id()));
        std::fs::create_dir(&dir).ok()?;
        let account = Account {
            dir,
            parent,
            counter,
        };
        // Dropped on failure: the empty cgroup is removed.
        std::fs::write(account.dir.join("cgroup.procs"), "0").ok()?;
        account.seconds().map(|_| account)
    }

    /// The CPU seconds counted so far (user + system, every process in it, living or reaped).
    pub fn seconds(&self) -> Option<f64> {
        match self.counter {
            Counter::Nanoseconds => {
                let text = std::fs::read_to_string(self.dir.join("cpuacct.usage")).ok()?;
                text.trim().parse::<u64>().ok().map(|ns| ns as f64 / 1e9)
            }
            Counter::CpuStat => {
                let text = std::fs::read_to_string(self.dir.join("cpu.stat")).ok()?;
                text.lines()
                    .find_map(|l| l.strip_prefix("usage_usec "))
                    .and_then(|n| n.trim().parse::<u64>().ok())
                    .map(|us| us as f64 / 1e6)
            }
        }
    }
}

impl Drop for Account {
    fn drop(&mut self) {
        let _ = std::fs::write(self.parent.join("cgroup.procs"), "0");
        let _ = std::fs::remove_dir(&self.dir);
    }
}

/// This process's cgroup in the hierarchy mounted at `mount`, from `/proc/self/cgroup`.
fn own_cgroup(mount: &Path, counter: Counter) -> Option<PathBuf> {
    if !mount.is_dir() {
        return None;
    }
    let own = std::fs::read_to_string("/proc/self/cgroup").ok()?;
    let path = own.lines().find_map(|line| {
        let mut parts = line.splitn(3, ':');
        let (_, controllers, path) = (parts.next()?, parts.next()?, parts.next()?);
        let wanted = match counter {
            Counter::Nanoseconds => controllers.split(',').any(|c| c == "cpuacct"),
            Counter::CpuStat => controllers.is_empty(),
        };
        wanted.then(|| path.trim_start_matches('/').to_string())
    })?;
    Some(mount.join(path))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_counting_cgroup_counts_the_time_of_what_the_process_starts() {
        // Only where this test may make one (root on cgroup v1 or a hybrid machine).
        let Some(account) = Account::start() else {
            return;
        };
        let before = account.seconds().expect("counted");
        // A grandchild, reaped by the shell.
        let status = std::process::Command::new("sh")
            .args([
                "-c",
                "(i=0; while [ $i -lt 200000 ]; do i=$((i+1)); done) & wait",
            ])
            .status()
            .expect("sh");
        assert!(status.success());
        let after = account.seconds().expect("counted");
        assert!(after - before > 0.05, "{before} -> {after}");
    }
}
