//! Where a student's code runs: bubblewrap (Debian's `bubblewrap`, what Flatpak uses), with
//! every namespace of its own, so that it sees no network (a loopback of its own only), a
//! read-only system, a private /tmp, and of the files only the directories it is given: no
//! other submission, no OUTDIR, no home. Its processes live in a process namespace of their
//! own, so killing bwrap (`--die-with-parent` for its init) kills every descendant at once,
//! wherever they moved to.
//!
//! The limits, as docs/grade.md asks: a JVM's memory by `-Xmx` (and not `RLIMIT_AS`, which
//! breaks the JVM's reservations) and, where one can be made, a cgroup's memory limit on the
//! whole sandbox (`memory_cgroup.rs`), processes and threads by `RLIMIT_NPROC`, file size by
//! `RLIMIT_FSIZE`, open files by `RLIMIT_NOFILE`, CPU time by `RLIMIT_CPU` as a backstop to
//! the wall-clock timeout. `RLIMIT_NPROC` counts per user, and not at all for root: run as
//! root (a grading server, CI), each slot of `-j` runs as a user of its own (`slot_uid`: one
//! per process and slot), so one student's fork bomb cannot starve another's JVM of threads; as any other
//! user it counts that user's processes, and the limit is set above those already running.
//! The limits are set by util-linux's `setpriv` and `prlimit` (present on every Debian), which
//! exec bwrap: no code of ours runs between fork and exec.

use std::path::{Path, PathBuf};
use std::process::Command;

use super::memory_cgroup::{CgroupRoot, RunCgroup};
use whitted_core::error::{Error, Result};

/// The first user id the slots of `-j` run as, when whitted runs as root: far above the ids
/// systems give to people (Debian's highest range ends at 65534), below `(uid_t)-1`.
const SLOT_UID: u32 = 1_000_000_000;

/// The user id slot `slot` of this process runs student code as: one of its own per process
/// and slot, so that two grading runs on one machine (two Slurm tasks on a node, two tests)
/// never share an `RLIMIT_NPROC` count. 1024 ids per process, processes told apart by their
/// pid modulo 2^21 (ids up to 1e9 + 2^31, below `(uid_t)-1`).
fn slot_uid(slot: usize) -> u32 {
    let pid = std::process::id() % (1 << 21);
    SLOT_UID + pid * 1024 + (slot % 1024) as u32
}
/// Processes and threads one sandbox may have (a JVM with the serial collector uses ~20).
pub const PROCESSES: u32 = 256;
/// Bytes a file the program writes may have: a 640x480 PNG is under 1 MiB.
pub const FILE_SIZE: u64 = 64 << 20;
/// Open files at once.
const OPEN_FILES: u32 = 1024;
/// The private /tmp's size (a tmpfs of bubblewrap's: its files are bounded by the memory
/// cgroup, where there is one, not by a count; the case's own folder has both caps).
const TMP_SIZE: u64 = 64 << 20;
/// A case's writable area: its bytes and its files (the course's program writes one PNG of
/// under 1 MiB; a submission that writes 1 GB or 100,000 files is stopped at these).
pub const AREA_BYTES: u64 = 128 << 20;
pub const AREA_FILES: u64 = 1024;
/// The file the area's wrapper leaves in the case's folder when the area was full.
pub const AREA_FULL: &str = ".whitted-area-full";

/// Runs inside the sandbox, as its first process, where a program's writable area is capped
/// (`Area::Capped`): it mounts the case's folder as a tmpfs of `AREA_BYTES` and `AREA_FILES`
/// over the host's, copies the scene in (and the map a Tick 1* scene reads beside it), runs the program with no capability left, kills
/// whatever it left running, and copies a regular `output.png` back to the host's folder,
/// which the program never sees (its path is covered, and this shell keeps capabilities the
/// program lacks, so the program cannot reach the shell's working directory through /proc).
/// Arguments: the folder, then the program. Only this shell can write into the host's folder,
/// so its marker cannot be forged. A tmpfs rather than a quota: bubblewrap's own `--size` caps
/// bytes but not files, and a tmpfs needs no privilege of whitted's, only the sandbox's user
/// namespace; everything on it is gone with the sandbox.
const AREA_WRAPPER: &str = r#"set -u
dir=$1; shift
cd "$dir" || exit 125
mount -t tmpfs -o "size=$WHITTED_AREA_BYTES,nr_inodes=$WHITTED_AREA_FILES,mode=0777" case "$dir" || exit 125
for f in ./*.xml ./*.png; do [ -f "$f" ] || continue; cp -- "$f" "$dir/" || exit 125; done
full=$WHITTED_AREA_FULL
unset WHITTED_AREA_BYTES WHITTED_AREA_FILES WHITTED_AREA_FULL
(cd "$dir" && exec setpriv --inh-caps=-all --ambient-caps=-all --bounding-set=-all -- "$@")
status=$?
kill -KILL -1 2>/dev/null
set -- $(stat -f -c '%a %d' "$dir")
if [ "$1" -eq 0 ] || [ "$2" -eq 0 ]; then : > "./$full"; fi
if [ -f "$dir/output.png" ] && [ ! -L "$dir/output.png" ]; then cp -- "$dir/output.png" ./output.png; fi
exit $status
"#;

/// What a sandboxed run holds until it has ended: its memory limit's cgroup, and the
/// descriptor its seccomp filter was handed over in.
pub struct RunGuard {
    cgroup: Option<RunCgroup>,
    /// The descriptors bubblewrap reads when it starts: its filter, its options.
    _descriptors: Vec<std::os::fd::OwnedFd>,
}

impl RunGuard {
    /// Whether the kernel killed the run at its cgroup's memory limit.
    pub fn oom_killed(&self) -> bool {
        self.cgroup.as_ref().is_some_and(RunCgroup::oom_killed)
    }
}

/// The seccomp filter (`seccomp.rs`) in a descriptor bubblewrap can read (None on an
/// architecture without one).
fn filter_fd() -> Result<Option<std::os::fd::OwnedFd>> {
    match super::seccomp::program() {
        Some(program) => descriptor("whitted-seccomp", &program).map(Some),
        None => Ok(None),
    }
}

/// `bytes` in a descriptor bubblewrap can read from its start: a memfd, left open across exec
/// (only that way does bwrap get it), closed when the run's guard drops.
fn descriptor(name: &str, bytes: &[u8]) -> Result<std::os::fd::OwnedFd> {
    let fail =
        |e: std::io::Error| Error::Environment(format!("cannot hand bubblewrap its {name}: {e}"));
    let fd = rustix::fs::memfd_create(name, rustix::fs::MemfdFlags::empty())
        .map_err(|e| fail(e.into()))?;
    let mut file = std::fs::File::from(fd);
    std::io::Write::write_all(&mut file, bytes).map_err(fail)?;
    std::io::Seek::seek(&mut file, std::io::SeekFrom::Start(0)).map_err(fail)?;
    Ok(file.into())
}

/// Arguments as `bwrap --args` reads them: each ended by a NUL.
fn nul_separated<'a>(args: impl Iterator<Item = &'a std::ffi::OsStr>) -> Vec<u8> {
    use std::os::unix::ffi::OsStrExt;
    args.flat_map(|a| a.as_bytes().iter().copied().chain([0]))
        .collect()
}

/// What a run may write: its folder as it is (javac's classes), or a capped area (a program's
/// case).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Area {
    Folder,
    Capped,
}

/// How a run shares the CPU with the others, and what its CPU time limit means.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Priority {
    /// A case's program, the warm compiler: the machine's priority, and a CPU time limit of
    /// twice the wall-clock one, a backstop.
    Normal,
    /// A student's javac of their own: it yields the CPU to every other run (`nice -n 19`),
    /// so that a source that makes javac work for a minute does not halve the speed of the
    /// students graded beside it, and its deadline is counted in CPU seconds
    /// (`limits.seconds`, then SIGXCPU; SIGKILL 5 s later), since a yielding javac's wall time
    /// says how busy the machine is, not how slow the source is.
    Background,
}

/// Whether a sandboxed run ended at its CPU time limit: killed by SIGXCPU, which bubblewrap
/// reports as its exit status 128 + SIGXCPU.
pub fn hit_cpu_limit(status: std::process::ExitStatus) -> bool {
    use std::os::unix::process::ExitStatusExt;
    const SIGXCPU: i32 = 24;
    status.signal() == Some(SIGXCPU) || status.code() == Some(128 + SIGXCPU)
}

/// The limits one run gets.
#[derive(Debug, Clone, Copy)]
pub struct Limits {
    /// Memory for the program in MiB: the JVM's heap gets half, the rest is its own.
    pub memory_mib: u64,
    /// Wall-clock seconds; CPU seconds are limited to a little more.
    pub seconds: u64,
}

/// How student code is run: in bubblewrap, or (`--no-sandbox`) as it is.
#[derive(Debug, Clone)]
pub enum Sandbox {
    Bubblewrap {
        bwrap: PathBuf,
        /// The JDK's home, bound read-only when it is not under /usr.
        jdk: Option<PathBuf>,
        /// Whether whitted runs as root: each slot then runs as a user of its own.
        root: bool,
        /// Where each run gets a cgroup with its memory limit, if anywhere.
        cgroups: Option<CgroupRoot>,
    },
    None,
}

impl Sandbox {
    /// Bubblewrap, tried once with `true` inside (in a folder under `scratch`, where the runs'
    /// folders will be) so that a system that forbids it (no user namespaces, a folder its
    /// users cannot reach) says so before any student runs.
    pub fn bubblewrap(java: &Path, scratch: &Path) -> Result<Sandbox> {
        let bwrap = find_in_path("bwrap").ok_or_else(|| {
            Error::Environment(
                "whitted grade runs every student's code in bubblewrap, which is not installed: \
                 `apt install bubblewrap` (or give --no-sandbox, which trusts every submission)"
                    .into(),
            )
        })?;
        let jdk = java
            .canonicalize()
            .ok()
            .and_then(|real| real.parent()?.parent().map(Path::to_path_buf))
            .filter(|home| !home.starts_with("/usr"));
        let sandbox = Sandbox::Bubblewrap {
            bwrap,
            jdk,
            root: rustix::process::geteuid().is_root(),
            cgroups: CgroupRoot::find(),
        };
        let dir = tempfile::tempdir_in(scratch)
            .map_err(|e| Error::io(scratch, "cannot create a directory", e))?;
        let limits = Limits {
            memory_mib: 64,
            seconds: 10,
        };
        let (mut probe, _cgroup) = sandbox.command(
            &[String::from("true")],
            &[],
            dir.path(),
            Area::Capped,
            0,
            limits,
            Priority::Normal,
        )?;
        let out = probe
            .output()
            .map_err(|e| Error::Environment(format!("cannot run bubblewrap: {e}")))?;
        if !out.status.success() {
            return Err(Error::Environment(format!(
                "bubblewrap cannot make a sandbox here ({}); give --no-sandbox to run every \
                 submission unconfined",
                String::from_utf8_lossy(&out.stderr).trim()
            )));
        }
        Ok(sandbox)
    }

    pub fn is_none(&self) -> bool {
        matches!(self, Sandbox::None)
    }

    /// The command that runs `program` (absolute paths or names in /usr/bin) for slot `slot`,
    /// seeing `readable` read-only and `writable` read-write at the same paths, within
    /// `limits`, and the cgroup holding its memory limit where there is one (keep it until the
    /// run has ended). `writable` is handed to the slot's user first.
    // Each argument is a fact of its own about the run, given by every caller.
    #[allow(clippy::too_many_arguments)]
    pub fn command(
        &self,
        program: &[String],
        readable: &[&Path],
        writable: &Path,
        area: Area,
        slot: usize,
        limits: Limits,
        priority: Priority,
    ) -> Result<(Command, RunGuard)> {
        let Sandbox::Bubblewrap {
            bwrap,
            jdk,
            root,
            cgroups,
        } = self
        else {
            let mut command = Command::new(&program[0]);
            command.args(&program[1..]).current_dir(writable);
            let guard = RunGuard {
                cgroup: None,
                _descriptors: Vec::new(),
            };
            return Ok((command, guard));
        };
        let uid = slot_uid(slot);
        if *root {
            std::os::unix::fs::chown(writable, Some(uid), Some(uid))
                .map_err(|e| Error::io(writable, "cannot hand over", e))?;
        }
        let cgroup = cgroups
            .as_ref()
            .and_then(|c| c.child(limits.memory_mib.saturating_mul(1 << 20)));
        let mut command = match &cgroup {
            // The shell enters the cgroup, then becomes setpriv: nothing of the run exists
            // outside it.
            Some(cgroup) => {
                let mut sh = Command::new("/bin/sh");
                sh.args(["-c", "echo 0 > \"$0\" && exec \"$@\""])
                    .arg(cgroup.procs())
                    .arg("setpriv");
                sh
            }
            None => Command::new("setpriv"),
        };
        if *root {
            command.args(["--reuid", &uid.to_string(), "--regid", &uid.to_string()]);
            command.arg("--clear-groups");
        }
        command.arg("--no-new-privs");
        if priority == Priority::Background {
            command.args(["nice", "-n", "19"]);
        }
        command.arg("prlimit");
        let processes = if *root {
            PROCESSES
        } else {
            running_tasks().saturating_add(PROCESSES)
        };
        command.args([
            format!("--nproc={processes}"),
            format!("--fsize={FILE_SIZE}"),
            format!("--nofile={OPEN_FILES}"),
            match priority {
                Priority::Normal => format!(
                    "--cpu={}",
                    limits.seconds.saturating_mul(2).saturating_add(5)
                ),
                Priority::Background => format!(
                    "--cpu={}:{}",
                    limits.seconds,
                    limits.seconds.saturating_add(5)
                ),
            },
            "--core=0".to_string(),
        ]);
        // bubblewrap's own options are handed over through a descriptor (`--args`), not its
        // command line, which a program reads as `/proc/1/cmdline` (bwrap's init is pid 1):
        // the binds, the JDK's place, the filter are nothing a student's report should show.
        let mut options = Command::new("bwrap");
        options.args([
            "--unshare-all",
            "--unshare-user",
            "--die-with-parent",
            "--new-session",
            "--hostname",
            "sandbox",
        ]);
        let filter = filter_fd()?;
        if let Some(fd) = &filter {
            use std::os::fd::AsRawFd;
            options.args(["--seccomp", &fd.as_raw_fd().to_string()]);
        }
        if area == Area::Capped {
            // The wrapper mounts the capped area, then drops every capability before the
            // program runs.
            options.args([
                "--uid",
                "0",
                "--gid",
                "0",
                "--cap-add",
                "CAP_SYS_ADMIN",
                "--cap-add",
                "CAP_SETPCAP",
            ]);
        }
        for dir in ["/bin", "/lib", "/lib64", "/sbin"] {
            system_dir(&mut options, dir);
        }
        options.args(["--ro-bind", "/usr", "/usr"]);
        // What the JDK reads in /etc, and the loader's cache; nothing else of /etc (no passwd).
        for etc in etc_for_java() {
            options.arg("--ro-bind").arg(&etc).arg(&etc);
        }
        if let Some(jdk) = jdk {
            options.arg("--ro-bind").arg(jdk).arg(jdk);
        }
        options.args(["--proc", "/proc", "--dev", "/dev"]);
        options.args(["--size", &TMP_SIZE.to_string(), "--tmpfs", "/tmp"]);
        for dir in readable {
            options.arg("--ro-bind").arg(dir).arg(dir);
        }
        options.arg("--bind").arg(writable).arg(writable);
        // The sandbox's own root and /dev are tmpfs that bubblewrap made: read-only once
        // made, so that a program (the owner of everything there when it runs as the
        // namespace's uid 0) writes only where its limits are, the case's folder and /tmp.
        // Devices are still written through (/dev/null).
        options.args(["--remount-ro", "/dev", "--remount-ro", "/"]);
        options.arg("--chdir").arg(writable);
        let args = descriptor("whitted-bwrap-args", &nul_separated(options.get_args()))?;
        {
            use std::os::fd::AsRawFd;
            command
                .arg(bwrap)
                .arg("--args")
                .arg(args.as_raw_fd().to_string());
        }
        command.arg("--");
        command.env_clear();
        command.envs([
            ("PATH", "/usr/bin:/bin"),
            ("HOME", "/tmp"),
            ("LANG", "C.UTF-8"),
            ("TMPDIR", "/tmp"),
        ]);
        if area == Area::Capped {
            command.args(["/bin/sh", "-c", AREA_WRAPPER, "sh"]);
            command.arg(writable);
            command.envs([
                ("WHITTED_AREA_BYTES", AREA_BYTES.to_string()),
                ("WHITTED_AREA_FILES", AREA_FILES.to_string()),
                ("WHITTED_AREA_FULL", AREA_FULL.to_string()),
            ]);
        }
        command.args(program);
        let guard = RunGuard {
            cgroup,
            _descriptors: filter.into_iter().chain([args]).collect(),
        };
        Ok((command, guard))
    }
}

/// A system directory as it is here: a symbolic link (merged /usr) as the same link, a
/// directory bound read-only, nothing when it is missing.
fn system_dir(command: &mut Command, dir: &str) {
    match std::fs::symlink_metadata(dir) {
        Ok(m) if m.file_type().is_symlink() => {
            if let Ok(target) = std::fs::read_link(dir) {
                command.arg("--symlink").arg(target).arg(dir);
            }
        }
        Ok(m) if m.is_dir() => {
            command.args(["--ro-bind", dir, dir]);
        }
        _ => {}
    }
}

/// What of /etc a JDK reads: its configuration (Debian's /etc/java-*), the alternatives its
/// links in /usr/bin go through, the loader's cache.
fn etc_for_java() -> Vec<PathBuf> {
    let mut found: Vec<PathBuf> = ["/etc/alternatives", "/etc/ld.so.cache"]
        .iter()
        .map(PathBuf::from)
        .filter(|p| p.exists())
        .collect();
    if let Ok(entries) = std::fs::read_dir("/etc") {
        for entry in entries.flatten() {
            if entry.file_name().to_string_lossy().starts_with("java-") {
                found.push(entry.path());
            }
        }
    }
    found.sort();
    found
}

/// The tasks (processes and threads) this user runs now, which `RLIMIT_NPROC` counts.
fn running_tasks() -> u32 {
    let me = rustix::process::getuid().as_raw();
    let Ok(entries) = std::fs::read_dir("/proc") else {
        return 0;
    };
    let mut count = 0u32;
    for entry in entries.flatten() {
        let status = entry.path().join("status");
        let Ok(text) = std::fs::read_to_string(status) else {
            continue;
        };
        let uid = text
            .lines()
            .find_map(|l| l.strip_prefix("Uid:"))
            .and_then(|l| l.split_whitespace().next())
            .and_then(|u| u.parse::<u32>().ok());
        let threads = text
            .lines()
            .find_map(|l| l.strip_prefix("Threads:"))
            .and_then(|t| t.trim().parse::<u32>().ok())
            .unwrap_or(1);
        if uid == Some(me) {
            count = count.saturating_add(threads);
        }
    }
    count
}

/// The executable `name` in PATH, as an absolute path (the which crate).
pub fn find_in_path(name: &str) -> Option<PathBuf> {
    which::which(name).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The exit status of `script` run by sh in the sandbox, with a capped area (the grade
    /// tests need bubblewrap and a JDK; tools/test installs them).
    fn in_sandbox(script: &str) -> std::process::ExitStatus {
        in_sandbox_at(script, 20, Priority::Normal)
    }

    fn in_sandbox_at(script: &str, seconds: u64, priority: Priority) -> std::process::ExitStatus {
        let java = find_in_path("java").expect("a JDK on PATH");
        let dir = tempfile::tempdir().expect("tempdir");
        let sandbox = Sandbox::bubblewrap(&java, dir.path()).expect("bubblewrap");
        let limits = Limits {
            memory_mib: 256,
            seconds,
        };
        let program = ["/bin/sh", "-c", script].map(String::from);
        let (mut command, _run) = sandbox
            .command(&program, &[], dir.path(), Area::Capped, 0, limits, priority)
            .expect("command");
        command.status().expect("runs")
    }

    #[test]
    fn the_sandbox_refuses_user_namespaces_ptrace_and_the_capabilities_of_its_wrapper() {
        assert!(in_sandbox("true").success());
        assert!(in_sandbox("echo x > /dev/null && echo x > /tmp/x && echo x > ./x").success());
        // Threads and processes still start (clone without CLONE_NEWUSER, clone3's ENOSYS).
        assert!(in_sandbox("sh -c true & wait $!").success());
        // The check below can fail only by its ptrace: it passes without the filter.
        let traceme = "import ctypes, sys; sys.exit(ctypes.CDLL(None).ptrace(0, 0, 0, 0))";
        let plain = std::process::Command::new("python3")
            .args(["-c", traceme])
            .status()
            .expect("python3");
        assert!(plain.success());
        for denied in [
            // A user namespace of its own, by unshare(2) and by clone(2).
            "unshare --user true",
            "unshare --map-root-user --fork true",
            // The wrapper's capabilities are gone: no mount, no writing the host's folder.
            "mount -t tmpfs x /tmp",
            // The case's folder is the capped tmpfs.
            "test \"$(stat -f -c %T .)\" != tmpfs",
            // Nothing but the case's folder and /tmp takes a file: not the sandbox's root,
            // not /dev.
            "echo x > /escape",
            "echo x > /dev/escape",
            // ptrace(2), even PTRACE_TRACEME (which needs no permission otherwise).
            "python3 -c 'import ctypes, sys; sys.exit(ctypes.CDLL(None).ptrace(0, 0, 0, 0))'",
        ] {
            assert!(!in_sandbox(denied).success(), "allowed: {denied}");
        }
    }

    #[test]
    fn a_background_run_yields_the_cpu_and_ends_at_its_cpu_seconds() {
        // nice 19 inside (the 19th field of /proc/self/stat), the machine's priority otherwise.
        let nice_is = |n: &str| format!("test \"$(cut -d' ' -f19 /proc/self/stat)\" = {n}");
        assert!(in_sandbox_at(&nice_is("19"), 20, Priority::Background).success());
        assert!(!in_sandbox_at(&nice_is("19"), 20, Priority::Normal).success());
        // A busy loop is stopped by its CPU time limit, 1 s here, and said to be.
        let started = std::time::Instant::now();
        let spin = in_sandbox_at("while :; do :; done", 1, Priority::Background);
        assert!(hit_cpu_limit(spin), "{spin:?}");
        assert!(started.elapsed() < std::time::Duration::from_secs(20));
        assert!(!hit_cpu_limit(in_sandbox("exit 3")));
    }
}
