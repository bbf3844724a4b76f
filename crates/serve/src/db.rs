//! A connection per thread: the server's blocking threads and the workers each keep one open
//! (SQLite connections are not shared between threads), opened on first use.

use std::cell::RefCell;
use std::path::{Path, PathBuf};

use super::store::Store;
use whitted_core::error::Result;

thread_local! {
    static CONNECTION: RefCell<Option<(PathBuf, Store)>> = const { RefCell::new(None) };
}

/// Runs `f` on this thread's connection to the database at `path`.
pub fn with<T>(path: &Path, f: impl FnOnce(&mut Store) -> Result<T>) -> Result<T> {
    CONNECTION.with(|cell| {
        let mut slot = cell.borrow_mut();
        if slot.as_ref().is_none_or(|(p, _)| p != path) {
            *slot = Some((path.to_path_buf(), Store::open(path)?));
        }
        let (_, store) = slot.as_mut().expect("opened above");
        f(store)
    })
}
