//! Helpers shared by the integration tests: run the built binary, read PNGs back.

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

/// Writes a scene a test defines inline to `dir/name`; returns its path.
pub fn write_scene(dir: &Path, name: &str, xml: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, xml).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    path
}

/// Runs `whitted` with `args` in `dir`.
pub fn whitted(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_whitted"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the whitted binary runs")
}

/// A path as a command-line argument (the tests' paths are UTF-8).
pub fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
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
    /// Whether the file has an `sRGB`, a `gAMA` and a `cHRM` chunk.
    pub srgb: bool,
    pub gama: bool,
    pub chrm: bool,
}

pub fn read_png(path: &Path) -> Png {
    let file = std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    read_png_from(std::io::BufReader::new(file))
}

fn read_png_from<R: std::io::BufRead + std::io::Seek>(r: R) -> Png {
    let mut reader = png::Decoder::new(r).read_info().expect("a PNG");
    let mut data = vec![0; reader.output_buffer_size().expect("size")];
    let info = reader.next_frame(&mut data).expect("PNG data");
    data.truncate(info.buffer_size());
    let srgb = reader.info().srgb.is_some();
    let gama = reader.info().gama_chunk.is_some();
    let chrm = reader.info().chrm_chunk.is_some();
    Png {
        width: info.width,
        height: info.height,
        color: info.color_type,
        depth: info.bit_depth,
        data,
        srgb,
        gama,
        chrm,
    }
}

/// A tool from the OpenImageIO wheel that `tools/test` installs into `.venv`, or from PATH.
/// Missing tools fail the test: the suite must not pass without checking.
pub fn tool(name: &str) -> PathBuf {
    let local = root().join(".venv/bin").join(name);
    if local.exists() {
        return local;
    }
    if let Some(found) = std::env::var_os("PATH").and_then(|paths| {
        std::env::split_paths(&paths)
            .map(|p| p.join(name))
            .find(|p| p.exists())
    }) {
        return found;
    }
    panic!("`{name}` not found: run tools/test, which installs OpenImageIO into .venv");
}

/// Runs a tool and returns its output; panics with its stderr if it fails to start.
pub fn run_tool(name: &str, args: &[&str], dir: &Path) -> Output {
    Command::new(tool(name))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap_or_else(|e| panic!("{name} did not run: {e}"))
}

/// Renders `scene_file` with extra `args` into `dir/exr_name`, asserting success.
pub fn render_exr(dir: &Path, scene_file: &Path, exr_name: &str, args: &[&str]) -> PathBuf {
    let mut all = vec![
        "render",
        "-q",
        "--no-png",
        "--input",
        scene_file.to_str().expect("utf-8 path"),
        "--exr",
        exr_name,
    ];
    all.extend_from_slice(args);
    let run = whitted(dir, &all);
    assert!(run.status.success(), "render failed: {}", stderr(&run));
    dir.join(exr_name)
}

/// The channel list as `oiiotool --info -v` reports it.
pub fn oiio_channels(path: &Path) -> Vec<String> {
    let out = run_tool(
        "oiiotool",
        &["--info", "-v", path.to_str().expect("utf-8")],
        &root(),
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    let line = text
        .lines()
        .find_map(|l| l.trim().strip_prefix("channel list:"))
        .unwrap_or_else(|| panic!("no channel list in {text}"));
    line.split(',').map(|c| c.trim().to_string()).collect()
}

/// A decoded EXR read with the `exr` crate: channels as f32 planes, and the header.
pub struct Exr {
    pub width: usize,
    pub height: usize,
    pub channels: Vec<(String, exr::prelude::FlatSamples)>,
    pub image: exr::prelude::ImageAttributes,
    pub layer: exr::prelude::LayerAttributes,
}

pub fn read_exr(path: &Path) -> Exr {
    let meta = exr::meta::MetaData::read_from_file(path, false)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(meta.headers.len(), 1, "one part");
    let file = std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let image = whitted_io::openexr::read_first_part(file)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let layer = image.layer_data;
    Exr {
        width: layer.size.0,
        height: layer.size.1,
        channels: layer
            .channel_data
            .list
            .into_iter()
            .map(|c| (c.name.to_string(), c.sample_data))
            .collect(),
        image: image.attributes,
        layer: layer.attributes,
    }
}

impl Exr {
    /// Channel `name` at pixel (x, y) as f32.
    pub fn at(&self, name: &str, x: usize, y: usize) -> f32 {
        let samples = &self
            .channels
            .iter()
            .find(|(n, _)| n == name)
            .unwrap_or_else(|| panic!("no channel {name}"))
            .1;
        samples.value_by_flat_index(y * self.width + x).to_f32()
    }

    pub fn names(&self) -> Vec<String> {
        self.channels.iter().map(|(n, _)| n.clone()).collect()
    }
}

/// Runs OpenImageIO's idiff on `a` and `b` with the AOV tolerance of docs/aovs.md (a value fails
/// when off by more than 1e-6 absolute and 1e-5 relative, for failures and warnings alike).
pub fn idiff_aov(a: &Path, b: &Path) -> Output {
    let (a, b) = (a.to_str().expect("utf-8"), b.to_str().expect("utf-8"));
    let args = [
        "-fail",
        "1e-6",
        "-failrelative",
        "1e-5",
        "-warn",
        "1e-6",
        "-warnrelative",
        "1e-5",
        a,
        b,
    ];
    run_tool("idiff", &args, &root())
}

/// Renders `scene` with the library, as `spec` asks (a panic if the spec is refused).
pub fn render_frame(
    scene: &whitted_core::scene::Scene,
    spec: &whitted_core::frame::FrameSpec,
) -> (whitted_core::film::Film, whitted_core::render::RenderStats) {
    let frame = whitted_core::frame::Frame::new(scene, spec).unwrap_or_else(|e| panic!("{e}"));
    whitted_core::render::render(scene, &frame, &|_| {}).expect("render")
}

/// A small deterministic generator, so that generated scenes are the same on every run.
pub struct Lcg(pub u64);

impl Lcg {
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }

    pub fn colour(&mut self) -> String {
        format!("#{:06X}", (self.next() * f64::from(0xFF_FFFF)) as u32)
    }

    pub fn chance(&mut self, p: f64) -> bool {
        self.next() < p
    }
}

/// Our Java Tick 2 (2016-17, `gfx.tick2.Tick2`), compiled once per test process.
pub fn tick2_classes() -> &'static Path {
    static CLASSES: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    CLASSES.get_or_init(|| javac("tests/java/gfx/tick2/Tick2.java", "tick2"))
}

/// Our Java Tick 1 of the later years (`-Dcourse=YEAR`), compiled once per test process.
pub fn tick1_classes() -> &'static Path {
    static CLASSES: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    CLASSES.get_or_init(|| {
        javac(
            "tests/java/uk/ac/cam/cl/gfxintro/whitted/tick1/Tick1.java",
            "tick1",
        )
    })
}

/// One `--program` string running our Java program with the mistakes `bugs` (`-Dbug=`):
/// 2016-17's Tick 2 without a course, the later years' Tick 1 under `-Dcourse=` with one.
pub fn java_program(course: Option<&str>, bugs: &[&str]) -> String {
    java_program_with(course, "", bugs)
}

/// The same with the JVM options `flags`, each ending in a space (`-Dsphere=geometric `).
pub fn java_program_with(course: Option<&str>, flags: &str, bugs: &[&str]) -> String {
    let flag = if bugs.is_empty() {
        String::new()
    } else {
        format!("-Dbug={} ", bugs.join(","))
    };
    let (course, classes, main) = match course {
        None => (String::new(), tick2_classes(), "gfx.tick2.Tick2"),
        Some(year) => (
            format!("-Dcourse={year} "),
            tick1_classes(),
            "uk.ac.cam.cl.gfxintro.whitted.tick1.Tick1",
        ),
    };
    format!(
        "java {course}{flags}{flag}-cp '{}' {main}",
        classes.to_str().expect("utf-8")
    )
}

/// A folder of this test process's named for `tag`, for what the process's tests share (the
/// classes compiled once): under cargo's own scratch folder in `target/`, not `/tmp`, so
/// that what a run leaves goes with `cargo clean` rather than piling up in the system's.
pub fn process_dir(tag: &str) -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("whitted-{tag}-{}", std::process::id()))
}

/// `javac -d DIR SOURCE` for a Java program under `tests/java/`, into a fresh class
/// directory of this process named for `tag`; the directory.
pub fn javac(source: &str, tag: &str) -> PathBuf {
    let dir = process_dir(tag);
    let javac = Command::new("javac")
        .arg("-d")
        .arg(&dir)
        .arg(root().join(source))
        .output()
        .expect("javac runs (tools/test installs default-jdk-headless)");
    assert!(javac.status.success(), "{}", stderr(&javac));
    dir
}

/// Compiles the Java sources `paths` into `classes` (annotation processing off, warnings
/// quiet), which must succeed: the one javac call the Tick 1* program tests share.
pub fn javac_into(classes: &Path, paths: &[PathBuf]) {
    let out = std::process::Command::new("javac")
        .args(["-proc:none", "-nowarn", "-d"])
        .arg(classes)
        .args(paths)
        .output()
        .expect("javac");
    assert!(out.status.success(), "{}", stderr(&out));
}

/// Writes `bytes` to `path`, making its folder first.
pub fn write_file(path: &Path, bytes: impl AsRef<[u8]>) {
    std::fs::create_dir_all(path.parent().expect("parent")).expect("folder");
    std::fs::write(path, bytes).expect("write");
}
