//! `--watch`: a thread that looks at the source's files every `POLL` and reloads (re-checks, in
//! check mode) when one changed. Polling the files' length and modification time needs no
//! platform watcher, sees a file replaced by rename as well as one rewritten in place, and
//! costs a few `stat` calls a second. A file is read only once it has looked the same for
//! two polls in a row, so that a program still writing it is not caught halfway; a load that
//! fails anyway (a truncated PNG) is reported to the page and the last good image stays.

use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, SystemTime};

use super::{Served, Source};
use crate::error::{Error, Result};

const POLL: Duration = Duration::from_millis(250);

/// What a file looked like: its length and modification time, or nothing (not there).
type Stamp = Option<(u64, SystemTime)>;

fn stamp(path: &PathBuf) -> Stamp {
    let metadata = std::fs::metadata(path).ok()?;
    Some((metadata.len(), metadata.modified().ok()?))
}

/// Starts watching `source` for `served`; the thread ends with the process.
pub fn start(source: Source, served: Arc<Served>) -> Result<()> {
    let files = source.watched();
    let stamps = |files: &[PathBuf]| -> Vec<Stamp> { files.iter().map(stamp).collect() };
    let mut loaded = stamps(&files);
    let mut last = loaded.clone();
    std::thread::Builder::new()
        .name("watch".into())
        .spawn(move || loop {
            std::thread::sleep(POLL);
            let now = stamps(&files);
            let settled = now == last;
            last = now.clone();
            if settled && now != loaded && now.iter().all(Option::is_some) {
                loaded = now;
                served.reloaded(source.load());
            }
        })
        .map(drop)
        .map_err(|e| Error::Environment(format!("cannot start the watching thread: {e}")))
}
