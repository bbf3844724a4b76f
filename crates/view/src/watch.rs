//! `--watch`: a thread that looks at the source's files every `POLL` and reloads (re-checks, in
//! check mode) when one changed. Polling the files' length and modification time needs no
//! platform watcher, sees a file replaced by rename as well as one rewritten in place, and
//! costs a few `stat` calls a second. A file is read only once it has looked the same for
//! two polls in a row, so that a program still writing it is not caught halfway; a load that
//! fails anyway (a truncated PNG) is reported to the page and the last good image stays.
//!
//! The files are first looked at before the first load starts ([`Baseline`]), so that a
//! change made while a long first load runs is reloaded after it. A file that is not a regular
//! file (a pipe would block the read until a writer comes, a device never ends) is reported,
//! never opened, and watching goes on.

use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, SystemTime};

use super::{Served, Source};
use whitted_core::error::{Error, Result};

const POLL: Duration = Duration::from_millis(250);

/// What a file looked like: whether it is a regular file, its length and modification time,
/// or nothing (not there).
type Stamp = Option<(bool, u64, SystemTime)>;

fn stamp(path: &PathBuf) -> Stamp {
    let metadata = std::fs::metadata(path).ok()?;
    Some((
        metadata.is_file(),
        metadata.len(),
        metadata.modified().ok()?,
    ))
}

/// The watched files as they were before the first load.
pub struct Baseline {
    files: Vec<PathBuf>,
    stamps: Vec<Stamp>,
}

impl Baseline {
    pub fn of(source: &Source) -> Self {
        let files = source.watched();
        let stamps = files.iter().map(stamp).collect();
        Baseline { files, stamps }
    }
}

/// Starts watching `source` for `served` from `baseline`; the thread ends with the process.
pub fn start(source: Source, served: Arc<Served>, baseline: Baseline) -> Result<()> {
    let Baseline { files, stamps } = baseline;
    let mut loaded = stamps;
    let mut last = loaded.clone();
    std::thread::Builder::new()
        .name("watch".into())
        .spawn(move || loop {
            std::thread::sleep(POLL);
            let now: Vec<Stamp> = files.iter().map(stamp).collect();
            let settled = now == last;
            last = now.clone();
            if settled && now != loaded && now.iter().all(Option::is_some) {
                loaded = now.clone();
                let irregular = files
                    .iter()
                    .zip(&now)
                    .find(|(_, s)| s.is_some_and(|(regular, ..)| !regular));
                served.reloaded(match irregular {
                    Some((file, _)) => Err(Error::Usage(format!(
                        "{}: not a regular file (a pipe, device or directory); the last good \
                         image stays until a regular file is there",
                        file.display()
                    ))),
                    None => source.load(),
                });
            }
        })
        .map(drop)
        .map_err(|e| Error::Environment(format!("cannot start the watching thread: {e}")))
}
