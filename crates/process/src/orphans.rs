//! A student's program can start processes that leave its process group (`setsid prog &`, a
//! daemon's double fork), which the group kill at a case's end does not reach. whitted makes
//! itself their "child subreaper" (Linux), so that such orphans are re-parented to it rather
//! than to init, and kills every one it has adopted once no case is running.

/// Adopts the orphans of every program started from now on. Where the system has no
/// subreapers the orphans go to init as before, and only the group kill applies.
pub fn adopt() {
    #[cfg(target_os = "linux")]
    let _ = rustix::process::set_child_subreaper(Some(rustix::process::getpid()));
}

/// Kills and reaps every child of this process: called when no case is running, so every
/// child left is an orphan of a student's program.
pub fn kill_adopted() {
    #[cfg(target_os = "linux")]
    for _ in 0..8 {
        let children = children();
        if children.is_empty() {
            return;
        }
        for pid in children {
            if let Some(pid) = rustix::process::Pid::from_raw(pid) {
                let _ = rustix::process::kill_process(pid, rustix::process::Signal::KILL);
                let _ = rustix::process::waitpid(Some(pid), rustix::process::WaitOptions::empty());
            }
        }
    }
}

/// The process ids whose parent is this process, from `/proc/PID/stat`.
#[cfg(target_os = "linux")]
fn children() -> Vec<i32> {
    let me = rustix::process::getpid().as_raw_nonzero().get();
    let Ok(entries) = std::fs::read_dir("/proc") else {
        return Vec::new();
    };
    entries
        .flatten()
        .filter_map(|e| e.file_name().to_str()?.parse::<i32>().ok())
        .filter(|&pid| parent_of(pid) == Some(me))
        .collect()
}

/// The parent of `pid`: the 4th field of its stat line, read after the name's closing
/// parenthesis (a name can hold spaces and parentheses).
#[cfg(target_os = "linux")]
fn parent_of(pid: i32) -> Option<i32> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    let after_name = &stat[stat.rfind(')')? + 1..];
    after_name.split_whitespace().nth(1)?.parse().ok()
}
