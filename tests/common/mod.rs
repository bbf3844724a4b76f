//! Helpers shared by the integration tests: run the built binary, read PNGs back.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The project root (where `scenes/` and `reference/` live).
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

pub fn scene(name: &str) -> PathBuf {
    root().join("scenes").join(name)
}

pub fn reference(name: &str) -> PathBuf {
    root().join("reference").join(name)
}

/// Runs `whitted` with `args` in `dir`.
pub fn whitted(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_whitted"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the whitted binary runs")
}

pub fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// A decoded PNG: size, channels per pixel, bit depth, and the raw sample bytes.
pub struct Png {
    pub width: u32,
    pub height: u32,
    pub color: png::ColorType,
    pub depth: png::BitDepth,
    pub data: Vec<u8>,
    pub srgb: bool,
}

pub fn read_png(path: &Path) -> Png {
    let file = std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    read_png_from(std::io::BufReader::new(file))
}

pub fn read_png_bytes(bytes: &[u8]) -> Png {
    read_png_from(std::io::Cursor::new(bytes.to_vec()))
}

fn read_png_from<R: std::io::BufRead + std::io::Seek>(r: R) -> Png {
    let mut reader = png::Decoder::new(r).read_info().expect("a PNG");
    let mut data = vec![0; reader.output_buffer_size().expect("size")];
    let info = reader.next_frame(&mut data).expect("PNG data");
    data.truncate(info.buffer_size());
    let srgb = reader.info().srgb.is_some();
    Png {
        width: info.width,
        height: info.height,
        color: info.color_type,
        depth: info.bit_depth,
        data,
        srgb,
    }
}
