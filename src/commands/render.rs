//! `whitted render` (and the bare `whitted ...` tick command line): scene -> film -> files.

use std::path::Path;
use std::time::{Duration, Instant, SystemTime};

use crate::aov;
use crate::camera::Camera;
use crate::cli::RenderArgs;
use crate::error::{Error, Result};
use crate::film::Film;
use crate::memory;
use crate::output::atomic::AtomicFile;
use crate::output::destination::{same_file, Destination, STDOUT};
use crate::output::exr::{write_exr, ExrMetadata, ExrOptions};
use crate::output::png::encode;
use crate::progress::Progress;
use crate::render::{render, RenderSettings};
use crate::scene::{self, Scene};
use crate::trace::TraceOptions;

/// The name errors and the EXR header use for the scene compiled into the binary.
const EMBEDDED_NAME: &str = "tick2.xml (embedded)";

pub fn run(args: &RenderArgs) -> Result<()> {
    let scene = load_scene(args.input.as_deref())?;
    let light_names: Vec<String> = scene.lights.iter().map(|l| l.name.clone()).collect();
    let available = aov::all_layers(&light_names, args.bounces);
    // Checked even without --exr, so a misspelt layer name is never silently ignored.
    let selected = aov::select(&args.aovs, &available).map_err(Error::Usage)?;
    let layers = if args.exr.is_some() {
        selected
    } else {
        available[..1].to_vec()
    };

    let encoding = args.tone.encoding().map_err(Error::Usage)?;
    let channels: usize = layers.iter().map(|l| l.quantity.channels().len()).sum();
    let (width, height) = args
        .region
        .map_or((args.width, args.height), |r| (r.width(), r.height()));
    memory::check(
        memory::render_bytes(width, height, channels, args.exr.is_some()),
        memory::available_bytes(),
        &format!("a {width}x{height} render with {channels} channels"),
    )?;

    check_outputs(args)?;
    // Open outputs before rendering, so that an unwritable path fails in milliseconds.
    let mut png = (!args.no_png)
        .then(|| Destination::open(&args.output))
        .transpose()?;
    let mut exr_file = args.exr.as_deref().map(AtomicFile::create).transpose()?;

    let camera = Camera::new(args.width, args.height);
    let settings = RenderSettings {
        trace: TraceOptions {
            bounces: args.bounces,
            shadows: !args.no_shadows,
        },
        spp: args.spp,
        region: args.region,
        ..RenderSettings::default()
    };
    let progress = Progress::new(u64::from(height), args.quiet);
    let started = Instant::now();
    let film = with_threads(args.threads, || {
        render(&scene, &camera, settings, layers, &|rows| {
            progress.advance(rows)
        })
    })??;
    progress.finish();
    let render_time = started.elapsed();
    if film.non_finite > 0 {
        eprintln!(
            "warning: {} non-finite layer values (NaN or infinity) were written as 0",
            film.non_finite
        );
    }

    // Write everything to temporary files first, then rename: all outputs or none.
    let started = Instant::now();
    if let Some(file) = exr_file.as_mut() {
        let metadata = exr_metadata(args, &film, &camera, light_names);
        let options = ExrOptions {
            compression: args.compression,
            half: args.half,
        };
        let path = file.target().to_path_buf();
        write_exr(file.file(), &film, options, &metadata)
            .map_err(|msg| Error::Exr { path, msg })?;
    }
    let exr_time = started.elapsed();
    if let Some(png) = png.as_mut() {
        png.write_png(&encode(&film.beauty, film.width, film.height, &encoding))?;
    }
    // Ctrl-C while the files were being written: drop them rather than publish them.
    crate::interrupt::check()?;
    if let Some(file) = exr_file {
        file.commit()?;
    }
    if let Some(png) = png {
        png.commit()?;
    }

    if !args.quiet {
        eprintln!("{}", summary(&film, args, render_time, exr_time));
    }
    Ok(())
}

/// Outputs that cannot all be written as asked: an EXR to stdout, two outputs on one file,
/// or an output over the scene being read.
fn check_outputs(args: &RenderArgs) -> Result<()> {
    let png = (!args.no_png).then_some(args.output.as_path());
    if let Some(exr) = &args.exr {
        if exr.as_os_str() == STDOUT {
            return Err(Error::Usage(
                "--exr cannot write to standard output (an EXR is written with seeks); give a file name"
                    .into(),
            ));
        }
        if png.is_some_and(|png| png.as_os_str() != STDOUT && same_file(png, exr)) {
            return Err(Error::Usage(format!(
                "--output and --exr are both `{}`; give them different paths",
                exr.display()
            )));
        }
    }
    if let Some(input) = &args.input {
        for output in png.into_iter().chain(args.exr.as_deref()) {
            if output.as_os_str() != STDOUT && same_file(output, input) {
                return Err(Error::Usage(format!(
                    "the output `{}` is the scene file being read; give another path",
                    output.display()
                )));
            }
        }
    }
    Ok(())
}

/// The scene file, or the course's tick2 scene compiled into the binary.
fn load_scene(input: Option<&Path>) -> Result<Scene> {
    match input {
        Some(path) => scene::load(path),
        None => scene::parse_str(EMBEDDED_NAME, scene::EMBEDDED_TICK2),
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

fn exr_metadata(
    args: &RenderArgs,
    film: &Film,
    camera: &Camera,
    light_names: Vec<String>,
) -> ExrMetadata {
    let scene_name = args
        .input
        .as_ref()
        .map_or(EMBEDDED_NAME.to_string(), |p| p.display().to_string());
    ExrMetadata {
        software: format!("whitted {}", env!("CARGO_PKG_VERSION")),
        comments: format!(
            "scene: {scene_name}; command: {}",
            render_command(args, &scene_name)
        ),
        bounces: args.bounces,
        spp: film.spp,
        light_names,
        capture_date: args.stamp_date.then(|| capture_date(SystemTime::now())),
        world_to_ndc: camera.world_to_ndc(),
    }
}

/// The command that reproduces these pixels: every option that changes them, in canonical
/// form. Output paths, threads and verbosity are left out, so that the same render written
/// elsewhere, or with another thread count, has the same bytes.
fn render_command(args: &RenderArgs, scene_name: &str) -> String {
    let quote = |a: &str| {
        if a.contains(char::is_whitespace) {
            format!("'{a}'")
        } else {
            a.to_string()
        }
    };
    let mut parts = vec![
        "whitted render".to_string(),
        match &args.input {
            Some(_) => format!("--input {}", quote(scene_name)),
            None => "(embedded tick2.xml)".to_string(),
        },
        format!("--bounces {}", args.bounces),
        format!("--width {} --height {}", args.width, args.height),
        format!("--spp {}", args.spp),
    ];
    if args.no_shadows {
        parts.push("--no-shadows".into());
    }
    parts.push(format!("--aovs {}", quote(&args.aovs)));
    if args.half {
        parts.push("--half".into());
    }
    if let Some(c) = clap::ValueEnum::to_possible_value(&args.compression) {
        parts.push(format!("--compression {}", c.get_name()));
    }
    parts.join(" ")
}

/// `YYYY:MM:DD hh:mm:ss` in UTC, as OpenEXR's `capDate` wants (with `utcOffset` 0).
fn capture_date(now: SystemTime) -> String {
    let secs = now
        .duration_since(SystemTime::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let (days, rest) = (secs / 86_400, secs % 86_400);
    // Civil date from days since 1970-01-01 (Howard Hinnant's algorithm).
    let z = days as i64 + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}:{month:02}:{day:02} {:02}:{:02}:{:02}",
        rest / 3600,
        rest / 60 % 60,
        rest % 60
    )
}

fn summary(film: &Film, args: &RenderArgs, render_time: Duration, exr_time: Duration) -> String {
    let seconds = render_time.as_secs_f64();
    let rate = film.rays as f64 / seconds.max(1e-9) / 1e6;
    let mut outputs = Vec::new();
    if let Some(exr) = &args.exr {
        outputs.push(format!(
            "{} ({} layers, written in {:.2} s)",
            exr.display(),
            film.layers.len(),
            exr_time.as_secs_f64()
        ));
    }
    if !args.no_png {
        outputs.push(if args.output.as_os_str() == STDOUT {
            "standard output".to_string()
        } else {
            args.output.display().to_string()
        });
    }
    let target = if outputs.is_empty() {
        String::new()
    } else {
        format!(" -> {}", outputs.join(", "))
    };
    format!(
        "whitted: {}x{}, {} spp, {} bounce{}, {} rays in {seconds:.2} s ({rate:.1} Mrays/s, \
         hierarchy built in {:.2} s){target}",
        film.width,
        film.height,
        film.spp,
        args.bounces,
        if args.bounces == 1 { "" } else { "s" },
        film.rays,
        film.hierarchy_time.as_secs_f64(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn capture_dates_are_civil_utc() {
        let at = |secs| capture_date(SystemTime::UNIX_EPOCH + Duration::from_secs(secs));
        assert_eq!(at(0), "1970:01:01 00:00:00");
        assert_eq!(at(951_782_400), "2000:02:29 00:00:00");
        assert_eq!(at(1_795_000_000), "2026:11:18 11:06:40");
    }
}
