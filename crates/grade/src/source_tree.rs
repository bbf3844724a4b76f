//! A compilation's sources laid out as javac reads them: each file at its path under a source
//! root (its package's folders). Both compilers write them, the warm one (`warm_javac.rs`) and
//! a student's own (`student.rs`), so it is here rather than in either of them.

use std::path::Path;

use whitted_core::error::{Error, Result};

/// Writes `sources` (paths under the source root, as `student::sources` makes them: a
/// package's folders, never `..`) under `src`, readable by the sandbox's users
/// (`work_area::open_up`); returns their paths.
pub fn write_sources(src: &Path, sources: &[(&str, &[u8])]) -> Result<Vec<String>> {
    let mut paths = Vec::new();
    for (name, bytes) in sources {
        let path = src.join(name);
        if let Some(folder) = path.parent() {
            std::fs::create_dir_all(folder).map_err(|e| Error::io(folder, "cannot create", e))?;
        }
        std::fs::write(&path, bytes).map_err(|e| Error::io(&path, "cannot write", e))?;
        paths.push(path.display().to_string());
    }
    super::work_area::open_up(src)?;
    Ok(paths)
}
