//! The course's classes a submission compiles against: by default whitted's clean-room
//! `skeleton/gfx/tick2` (compiled into the binary), or the course's own sources with
//! `--skeleton DIR`. Never a submission's: only Plane.java and Renderer.java come from there.

use std::path::{Path, PathBuf};

use super::archive::{MAX_SOURCE, WANTED};
use whitted_core::error::{Error, Result};

/// The skeleton's files: (name, bytes), sorted by name.
#[derive(Debug, Clone)]
pub struct Skeleton {
    pub files: Vec<(String, Vec<u8>)>,
    /// Where it came from, for the reports.
    pub source: String,
}

macro_rules! ours {
    ($($name:literal),*) => {
        [$(($name, include_bytes!(concat!("../skeleton/gfx/tick2/", $name)).as_slice())),*]
    };
}

/// whitted's own: the API of docs/grade.md, the arithmetic of docs/rendering.md.
const CLEAN_ROOM: [(&str, &[u8]); 10] = ours!(
    "Camera.java",
    "PointLight.java",
    "Ray.java",
    "RaycastHit.java",
    "Scene.java",
    "SceneLoader.java",
    "SceneObject.java",
    "Sphere.java",
    "Tick2.java",
    "Vector3.java"
);

impl Skeleton {
    pub fn clean_room() -> Skeleton {
        Skeleton {
            files: CLEAN_ROOM
                .iter()
                .map(|(name, bytes)| (name.to_string(), bytes.to_vec()))
                .collect(),
            source: "whitted's clean-room skeleton".into(),
        }
    }

    /// The `.java` files of `dir` (or of its `gfx/tick2` or `src/gfx/tick2`), but the two a
    /// submission gives.
    pub fn from_dir(dir: &Path) -> Result<Skeleton> {
        let package = ["src/gfx/tick2", "gfx/tick2", ""]
            .iter()
            .map(|sub| dir.join(sub))
            .find(|d| d.join("Tick2.java").is_file())
            .ok_or_else(|| {
                Error::Usage(format!(
                    "--skeleton {}: no Tick2.java there, nor in gfx/tick2 or src/gfx/tick2",
                    dir.display()
                ))
            })?;
        let mut files = Vec::new();
        let entries =
            std::fs::read_dir(&package).map_err(|e| Error::io(&package, "cannot read", e))?;
        let mut paths: Vec<PathBuf> = entries.flatten().map(|e| e.path()).collect();
        paths.sort();
        for path in paths {
            let name = path
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            if !name.ends_with(".java") || WANTED.contains(&name.as_str()) || !path.is_file() {
                continue;
            }
            let len = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
            if len > MAX_SOURCE {
                return Err(Error::Usage(format!(
                    "{}: larger than {MAX_SOURCE} bytes",
                    path.display()
                )));
            }
            let bytes = std::fs::read(&path).map_err(|e| Error::io(&path, "cannot read", e))?;
            files.push((name, bytes));
        }
        Ok(Skeleton {
            files,
            source: package.display().to_string(),
        })
    }
}
