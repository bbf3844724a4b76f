//! `whitted render` (and the bare `whitted ...` tick command line): scene -> film -> files.

use std::io::IsTerminal;
use std::path::Path;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::camera::Camera;
use crate::cli::RenderArgs;
use crate::error::{Error, Result};
use crate::film::Film;
use crate::output::atomic::AtomicFile;
use crate::output::png::{write_png, PngImage, PngPixels};
use crate::render::render;
use crate::scene::{self, Scene};
use crate::tonemap;
use crate::trace::TraceOptions;

/// What `-o -` means: the PNG goes to standard output.
const STDOUT: &str = "-";

/// Images smaller than this finish before a progress bar would be readable.
const PROGRESS_MIN_PIXELS: u64 = 64 * 64;

pub fn run(args: &RenderArgs) -> Result<()> {
    let scene = load_scene(args.input.as_deref())?;
    // Open outputs before rendering, so that an unwritable path fails in milliseconds.
    let png = match () {
        _ if args.no_png => None,
        _ if args.output.as_os_str() == STDOUT => Some(PngOutput::Stdout),
        _ => Some(PngOutput::File(AtomicFile::create(&args.output)?)),
    };

    let camera = Camera::new(args.width, args.height);
    let options = TraceOptions {
        bounces: args.bounces,
        shadows: !args.no_shadows,
    };
    let progress = progress_bar(args, &camera);
    let started = Instant::now();
    let film = with_threads(args.threads, || {
        render(&scene, &camera, options, &|| progress.inc(1))
    })?;
    progress.finish_and_clear();
    let elapsed = started.elapsed();

    let written = match png {
        Some(output) => Some(output.write(&tick_png(&film))?),
        None => None,
    };
    if !args.quiet {
        eprintln!("{}", summary(&film, args, elapsed, written.as_deref()));
    }
    Ok(())
}

/// The scene file, or the course's tick2 scene compiled into the binary.
fn load_scene(input: Option<&Path>) -> Result<Scene> {
    match input {
        Some(path) => scene::load(path),
        None => scene::parse_str("tick2.xml (embedded)", scene::EMBEDDED_TICK2),
    }
}

/// Runs `work` on a pool of `threads` workers, or on rayon's global pool (all cores).
fn with_threads<T: Send>(threads: Option<usize>, work: impl FnOnce() -> T + Send) -> Result<T> {
    match threads {
        None => Ok(work()),
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .map(|pool| pool.install(work))
            .map_err(|e| Error::Usage(format!("cannot start {n} worker threads: {e}"))),
    }
}

/// A bar over image rows on stderr, shown only to a person watching a render that takes a
/// moment.
fn progress_bar(args: &RenderArgs, camera: &Camera) -> ProgressBar {
    let pixels = u64::from(camera.width) * u64::from(camera.height);
    if args.quiet || !std::io::stderr().is_terminal() || pixels < PROGRESS_MIN_PIXELS {
        return ProgressBar::hidden();
    }
    let bar =
        ProgressBar::with_draw_target(Some(u64::from(camera.height)), ProgressDrawTarget::stderr());
    if let Ok(style) =
        ProgressStyle::with_template("{spinner} rendering [{bar:40}] {pos}/{len} rows, {eta} left")
    {
        bar.set_style(style.progress_chars("=> "));
    }
    bar
}

/// The course's PNG: the beauty through the `tick` tone map, 8-bit RGB, no colour metadata.
fn tick_png(film: &Film) -> PngImage {
    PngImage {
        width: film.width,
        height: film.height,
        pixels: PngPixels::Eight(
            film.beauty
                .iter()
                .flat_map(|&v| tonemap::tick_bytes(v))
                .collect(),
        ),
        srgb: false,
    }
}

/// Where the PNG goes.
enum PngOutput {
    Stdout,
    File(AtomicFile),
}

impl PngOutput {
    /// Encodes and writes `image`; returns the name written to, for the summary.
    fn write(self, image: &PngImage) -> Result<String> {
        match self {
            PngOutput::Stdout => {
                let stdout = std::io::stdout().lock();
                write_png(std::io::BufWriter::new(stdout), image).map_err(|e| Error::Png {
                    path: STDOUT.into(),
                    msg: e.to_string(),
                })?;
                Ok("standard output".into())
            }
            PngOutput::File(file) => {
                let name = file.target().display().to_string();
                let path = file.target().to_path_buf();
                file.write_with(|w| {
                    write_png(w, image).map_err(|e| Error::Png {
                        path,
                        msg: e.to_string(),
                    })
                })?;
                Ok(name)
            }
        }
    }
}

fn summary(film: &Film, args: &RenderArgs, elapsed: Duration, written: Option<&str>) -> String {
    let seconds = elapsed.as_secs_f64();
    let rate = film.rays as f64 / seconds.max(1e-9) / 1e6;
    let target = written.map_or(String::new(), |w| format!(" -> {w}"));
    format!(
        "whitted: {}x{}, {} bounce{}, {} rays in {seconds:.2} s ({rate:.1} Mrays/s){target}",
        film.width,
        film.height,
        args.bounces,
        if args.bounces == 1 { "" } else { "s" },
        film.rays,
    )
}
