//! A project's zip, opened with limits: at most `MAX_ENTRIES` entries; the Java sources'
//! bytes counted as they expand (never as the zip's headers claim), at most `MAX_EXPANDED`
//! together, so that a zip bomb costs what the limit allows and stops; every other entry
//! (folders, class files, a zip inside) skipped unread. A source is kept by its class's file
//! name alone: the folders an entry names (`../../x`, `/etc`) are never a path here.

use std::io::Read;

use super::upload::{java_name, MAX_ENTRIES, MAX_EXPANDED};

/// The `.java` files of the zip in `bytes`, by name, or why the zip is refused.
pub fn java_files(bytes: &[u8]) -> Result<Vec<(String, Vec<u8>)>, String> {
    let mut archive = zip::ZipArchive::new(std::io::Cursor::new(bytes))
        .map_err(|e| format!("the zip cannot be read ({e})"))?;
    if archive.len() > MAX_ENTRIES {
        return Err(format!(
            "the zip has {} entries; a project has far fewer (at most {MAX_ENTRIES})",
            archive.len()
        ));
    }
    let mut left = MAX_EXPANDED;
    let mut files = Vec::new();
    for i in 0..archive.len() {
        let mut entry = archive
            .by_index(i)
            .map_err(|e| format!("the zip cannot be read ({e})"))?;
        let name = String::from_utf8_lossy(entry.name_raw()).into_owned();
        if entry.is_dir() || !name.ends_with(".java") || name.contains("__MACOSX") {
            continue;
        }
        let name = java_name(&name)?;
        let mut content = Vec::new();
        (&mut entry)
            .take(left + 1)
            .read_to_end(&mut content)
            .map_err(|e| format!("{name} in the zip cannot be read ({e})"))?;
        if content.len() as u64 > left {
            return Err(format!(
                "the zip's sources expand to more than {} MiB; a project's are far smaller",
                MAX_EXPANDED >> 20
            ));
        }
        left -= content.len() as u64;
        files.push((name, content));
    }
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    fn zip_of(entries: &[(&str, &[u8])]) -> Vec<u8> {
        let mut out = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
        let options = zip::write::SimpleFileOptions::default()
            .compression_method(zip::CompressionMethod::Deflated);
        for (name, bytes) in entries {
            out.start_file(*name, options).expect("entry");
            out.write_all(bytes).expect("write");
        }
        out.finish().expect("zip").into_inner()
    }

    #[test]
    fn sources_are_taken_by_class_name_and_the_rest_skipped() {
        let bytes = zip_of(&[
            ("proj/src/uk/ac/cam/Renderer.java", b"class Renderer {}"),
            ("proj/out/Renderer.class", b"\xca\xfe"),
            ("__MACOSX/proj/._Renderer.java", b"junk"),
        ]);
        let files = java_files(&bytes).expect("read");
        assert_eq!(
            files,
            vec![("Renderer.java".to_string(), b"class Renderer {}".to_vec())]
        );
    }

    #[test]
    fn bombs_traversal_and_garbage_are_refused() {
        let bomb = zip_of(&[("Bomb.java", &vec![b' '; (MAX_EXPANDED + 1) as usize])]);
        assert!(bomb.len() < 100_000, "a small zip");
        assert!(java_files(&bomb).expect_err("bomb").contains("expand"));
        let climbing = zip_of(&[("../../../etc/Evil.java", b"class Evil {}")]);
        assert_eq!(
            java_files(&climbing).expect("kept by name")[0].0,
            "Evil.java"
        );
        let badly_named = zip_of(&[("../../.bashrc.java", b"x")]);
        assert!(java_files(&badly_named).is_err());
        assert!(java_files(b"PK\x03\x04 not really").is_err());
        let many: Vec<(String, &[u8])> = (0..=MAX_ENTRIES)
            .map(|i| (format!("d/{i}.txt"), &b""[..]))
            .collect();
        let many: Vec<(&str, &[u8])> = many.iter().map(|(n, b)| (n.as_str(), *b)).collect();
        assert!(java_files(&zip_of(&many))
            .expect_err("many")
            .contains("entries"));
    }
}
