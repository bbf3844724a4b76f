//! The converged Tick 1* references kept on disk (`star_reference.rs` keeps them in memory),
//! so that the second `check --star` of a scene, in another process, costs the statistic and
//! not the minutes of the expectation. A file is trusted only when everything about it checks:
//! its magic, its full key (the reference's every input, written in the file and compared, so
//! a clash of the file names' hash is harmless), its lengths against the image's size, and a
//! checksum of every byte; anything else (a truncated write of another process, a disk error,
//! an older format, a hand-edited file) is ignored and the reference computed again and
//! rewritten. Files are written whole to a temporary name in the same folder and renamed, so
//! a reader never sees half of one. The folder is kept under [`LIMIT_BYTES`] by removing the
//! least recently used files.

use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};

use glam::DVec3;
use whitted_core::star::StarImage;

/// The file format's first bytes; a new layout gets a new version.
const MAGIC: &[u8; 16] = b"whitted-starref1";

/// What the folder may hold: about thirty 640x480 references (about 35 MB each).
pub const LIMIT_BYTES: u64 = 1 << 30;

/// The environment variable naming the cache folder; set but empty, no disk cache is used.
pub const FOLDER_VARIABLE: &str = "WHITTED_CACHE_DIR";

/// The folder references are kept in: `$WHITTED_CACHE_DIR/star-references`, else
/// `$XDG_CACHE_HOME/whitted/star-references`, else `$HOME/.cache/whitted/star-references`;
/// None when `WHITTED_CACHE_DIR` is set empty or no home is known (then references are kept
/// in memory only).
pub fn default_folder() -> Option<PathBuf> {
    let base = match std::env::var_os(FOLDER_VARIABLE) {
        Some(dir) if dir.is_empty() => return None,
        Some(dir) => PathBuf::from(dir),
        None => match std::env::var_os("XDG_CACHE_HOME").filter(|d| !d.is_empty()) {
            Some(dir) => PathBuf::from(dir).join("whitted"),
            None => PathBuf::from(std::env::var_os("HOME").filter(|d| !d.is_empty())?)
                .join(".cache/whitted"),
        },
    };
    Some(base.join("star-references"))
}

/// What this build of whitted is: its version and its executable's size and modification
/// time, so that a rebuilt whitted (whose expectation may differ in the last bit) never
/// trusts a reference of another build.
pub fn build() -> String {
    let exe = std::env::current_exe()
        .ok()
        .and_then(|p| fs::metadata(p).ok());
    let (size, modified) = exe.map_or((0, 0), |m| {
        let modified = m
            .modified()
            .ok()
            .and_then(|t| t.duration_since(std::time::UNIX_EPOCH).ok())
            .map_or(0, |d| d.as_nanos());
        (m.len(), modified)
    });
    format!("{} {size} {modified}", env!("CARGO_PKG_VERSION"))
}

/// FNV-1a, 64 bits: the file names' hash and the payload's checksum (an error check, not a
/// defence: the folder is the user's own).
pub fn fnv(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// The file of the reference whose key is `key` in `folder`.
pub fn path_of(folder: &Path, key: &str) -> PathBuf {
    folder.join(format!("{:016x}.ref", fnv(key.as_bytes())))
}

/// The reference under `key` in `folder`, if a whole, matching file is there.
pub fn load(folder: &Path, key: &str) -> Option<StarImage> {
    let path = path_of(folder, key);
    let bytes = fs::read(&path).ok()?;
    let image = decode(&bytes, key)?;
    // Touched, so that the bound removes the least recently used first.
    if let Ok(file) = fs::File::options().append(true).open(&path) {
        let _ = file.set_modified(std::time::SystemTime::now());
    }
    Some(image)
}

/// Keeps `image` under `key` in `folder` (written whole, then renamed), then trims the folder
/// to its bound. A failure to write loses only the time saved later: it is not an error.
pub fn store(folder: &Path, key: &str, image: &StarImage) {
    let bytes = encode(key, image);
    if fs::create_dir_all(folder).is_err() {
        return;
    }
    let written = tempfile::Builder::new()
        .prefix(".partial-")
        .tempfile_in(folder)
        .and_then(|mut file| {
            file.write_all(&bytes)?;
            file.as_file().sync_all()?;
            Ok(file)
        });
    if let Ok(file) = written {
        let _ = file.persist(path_of(folder, key));
    }
    trim(folder, LIMIT_BYTES);
}

/// Removes the least recently used references of `folder` until it holds at most `limit`
/// bytes (and leftovers of interrupted writes older than an hour).
pub fn trim(folder: &Path, limit: u64) {
    let Ok(entries) = fs::read_dir(folder) else {
        return;
    };
    let now = std::time::SystemTime::now();
    let mut files: Vec<(std::time::SystemTime, u64, PathBuf)> = Vec::new();
    for entry in entries.flatten() {
        let path = entry.path();
        let Ok(meta) = entry.metadata() else {
            continue;
        };
        let modified = meta.modified().unwrap_or(std::time::UNIX_EPOCH);
        let name = entry.file_name().to_string_lossy().into_owned();
        if name.starts_with(".partial-") {
            let old = now
                .duration_since(modified)
                .is_ok_and(|d| d.as_secs() > 3600);
            if old {
                let _ = fs::remove_file(&path);
            }
        } else if name.ends_with(".ref") && meta.is_file() {
            files.push((modified, meta.len(), path));
        }
    }
    let mut total: u64 = files.iter().map(|f| f.1).sum();
    files.sort();
    for (_, len, path) in files {
        if total <= limit {
            break;
        }
        if fs::remove_file(&path).is_ok() {
            total -= len;
        }
    }
}

/// The file's bytes: magic, key, size, the layers, then the checksum of all before it.
pub fn encode(key: &str, image: &StarImage) -> Vec<u8> {
    let mut out = Vec::new();
    out.extend_from_slice(MAGIC);
    put_u64(&mut out, key.len() as u64);
    out.extend_from_slice(key.as_bytes());
    put_u64(&mut out, u64::from(image.width));
    put_u64(&mut out, u64::from(image.height));
    for layer in [
        &image.beauty,
        &image.variance,
        &image.standard_error,
        &image.normal,
    ] {
        put_vectors(&mut out, layer);
    }
    put_u64(&mut out, image.visible.len() as u64);
    for light in &image.visible {
        put_f32s(&mut out, light);
    }
    put_f32s(&mut out, &image.circle_of_confusion);
    put_f32s(&mut out, &image.bump_height);
    put_u64(&mut out, image.paths.len() as u64);
    for p in &image.paths {
        out.extend_from_slice(&p.to_le_bytes());
    }
    let sum = fnv(&out);
    put_u64(&mut out, sum);
    out
}

/// The image in `bytes` if they are a whole file of `key`: None for anything else.
pub fn decode(bytes: &[u8], key: &str) -> Option<StarImage> {
    let (body, sum) = bytes.split_at(bytes.len().checked_sub(8)?);
    if fnv(body) != u64::from_le_bytes(sum.try_into().ok()?) {
        return None;
    }
    let mut r = Reader(body);
    if r.take(MAGIC.len())? != MAGIC {
        return None;
    }
    let key_len = usize::try_from(r.u64()?).ok()?;
    if r.take(key_len)? != key.as_bytes() {
        return None;
    }
    let width = u32::try_from(r.u64()?).ok()?;
    let height = u32::try_from(r.u64()?).ok()?;
    let pixels = (width as usize).checked_mul(height as usize)?;
    let beauty = r.vectors()?;
    let variance = r.vectors()?;
    let standard_error = r.vectors()?;
    let normal = r.vectors()?;
    let lights = usize::try_from(r.u64()?).ok()?;
    let visible = (0..lights.min(1 << 16))
        .map(|_| r.f32s())
        .collect::<Option<Vec<_>>>()?;
    let circle_of_confusion = r.f32s()?;
    let bump_height = r.f32s()?;
    let n = usize::try_from(r.u64()?).ok()?;
    let paths = r
        .take(n.checked_mul(4)?)?
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect::<Vec<_>>();
    // Every layer an expectation has is the image's size (the optional ones may be empty).
    let sized = |len: usize| len == pixels;
    let sized_or_empty = |len: usize| len == pixels || len == 0;
    let whole = r.0.is_empty()
        && visible.len() == lights
        && [
            beauty.len(),
            variance.len(),
            standard_error.len(),
            paths.len(),
        ]
        .into_iter()
        .all(sized)
        && visible.iter().all(|v| sized(v.len()))
        && [normal.len(), circle_of_confusion.len(), bump_height.len()]
            .into_iter()
            .all(sized_or_empty);
    whole.then_some(StarImage {
        width,
        height,
        beauty,
        variance,
        standard_error,
        visible,
        circle_of_confusion,
        normal,
        bump_height,
        paths,
    })
}

fn put_u64(out: &mut Vec<u8>, v: u64) {
    out.extend_from_slice(&v.to_le_bytes());
}

fn put_vectors(out: &mut Vec<u8>, vs: &[DVec3]) {
    put_u64(out, vs.len() as u64);
    for v in vs {
        for c in v.to_array() {
            out.extend_from_slice(&c.to_bits().to_le_bytes());
        }
    }
}

fn put_f32s(out: &mut Vec<u8>, vs: &[f32]) {
    put_u64(out, vs.len() as u64);
    for v in vs {
        out.extend_from_slice(&v.to_bits().to_le_bytes());
    }
}

/// The bytes not read yet; every read is bounded by them (a length field cannot make it
/// allocate more than the file holds).
struct Reader<'a>(&'a [u8]);

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize) -> Option<&'a [u8]> {
        if n > self.0.len() {
            return None;
        }
        let (head, rest) = self.0.split_at(n);
        self.0 = rest;
        Some(head)
    }

    fn u64(&mut self) -> Option<u64> {
        Some(u64::from_le_bytes(self.take(8)?.try_into().ok()?))
    }

    fn vectors(&mut self) -> Option<Vec<DVec3>> {
        let n = usize::try_from(self.u64()?).ok()?;
        let bytes = self.take(n.checked_mul(24)?)?;
        Some(
            bytes
                .chunks_exact(24)
                .map(|c| {
                    let f = |k: usize| {
                        f64::from_bits(u64::from_le_bytes(
                            c[8 * k..8 * k + 8].try_into().unwrap_or([0; 8]),
                        ))
                    };
                    DVec3::new(f(0), f(1), f(2))
                })
                .collect(),
        )
    }

    fn f32s(&mut self) -> Option<Vec<f32>> {
        let n = usize::try_from(self.u64()?).ok()?;
        let bytes = self.take(n.checked_mul(4)?)?;
        Some(
            bytes
                .chunks_exact(4)
                .map(|c| f32::from_bits(u32::from_le_bytes([c[0], c[1], c[2], c[3]])))
                .collect(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image() -> StarImage {
        let v = |k: f64| {
            (0..6)
                .map(|i| DVec3::new(k, f64::from(i), 0.1 * k))
                .collect()
        };
        StarImage {
            width: 3,
            height: 2,
            beauty: v(1.0),
            variance: v(2.0),
            standard_error: v(3.0),
            visible: vec![vec![0.5; 6], vec![0.25; 6]],
            circle_of_confusion: vec![1.5; 6],
            normal: v(-1.0),
            bump_height: Vec::new(),
            paths: vec![7; 6],
        }
    }

    #[test]
    fn a_reference_comes_back_bit_for_bit_and_only_under_its_own_key() {
        let bytes = encode("key a", &image());
        assert_eq!(decode(&bytes, "key a"), Some(image()));
        assert_eq!(decode(&bytes, "key b"), None);
    }

    #[test]
    fn a_truncated_or_corrupt_file_is_never_trusted() {
        let bytes = encode("k", &image());
        for cut in [0, 1, 8, 20, bytes.len() / 2, bytes.len() - 1] {
            assert_eq!(decode(&bytes[..cut], "k"), None, "cut at {cut}");
        }
        for at in [0, 20, bytes.len() / 2, bytes.len() - 1] {
            let mut flipped = bytes.clone();
            flipped[at] ^= 0x10;
            assert_eq!(decode(&flipped, "k"), None, "flipped at {at}");
        }
        // A whole file whose lengths disagree with its size (checksum made to match).
        let mut wrong = image();
        wrong.paths.pop();
        assert_eq!(decode(&encode("k", &wrong), "k"), None);
    }

    #[test]
    fn the_folder_keeps_whole_files_and_stays_within_its_bound() {
        let dir = tempfile::tempdir().expect("tempdir");
        store(dir.path(), "one", &image());
        assert_eq!(load(dir.path(), "one"), Some(image()));
        assert_eq!(load(dir.path(), "two"), None);
        // A truncated file under the key is ignored, then replaced by the next store.
        let path = path_of(dir.path(), "one");
        let len = fs::metadata(&path).expect("stored").len();
        fs::write(&path, &fs::read(&path).expect("read")[..len as usize / 2]).expect("cut");
        assert_eq!(load(dir.path(), "one"), None);
        store(dir.path(), "one", &image());
        assert_eq!(load(dir.path(), "one"), Some(image()));
        // Over the bound, the least recently used goes first.
        std::thread::sleep(std::time::Duration::from_millis(20));
        store(dir.path(), "two", &image());
        trim(dir.path(), len + len / 2);
        assert_eq!(load(dir.path(), "one"), None);
        assert_eq!(load(dir.path(), "two"), Some(image()));
        let names: Vec<_> = fs::read_dir(dir.path())
            .expect("dir")
            .flatten()
            .map(|e| e.file_name())
            .collect();
        assert_eq!(names.len(), 1, "{names:?}");
    }
}
