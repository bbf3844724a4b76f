//! `whitted render` (and the bare `whitted ...` tick command line): scene -> plan -> film ->
//! files. Every check is the plan's; this file runs it and reports.

use std::time::{Duration, Instant};

use crate::cli::RenderArgs;
use crate::error::{Error, Result};
use crate::output::atomic::AtomicFile;
use crate::output::destination::{Destination, STDOUT};
use crate::output::exr::write_exr;
use crate::output::png::encode;
use crate::plan::RenderPlan;
use crate::progress::Progress;
use crate::render::{render, RenderStats};
use crate::render_record;
use crate::scene;

pub fn run(args: &RenderArgs) -> Result<()> {
    let input = scene::load_input(args.input.as_deref())?;
    let scene = &input.scene;
    let plan = RenderPlan::new(&args.request(), scene)?;
    // Open outputs before rendering, so that an unwritable path fails in milliseconds.
    let mut png = plan.png.as_deref().map(Destination::open).transpose()?;
    let mut exr_file = plan.exr.as_deref().map(AtomicFile::create).transpose()?;

    let progress = Progress::new(u64::from(plan.frame.region.height()), args.quiet);
    let started = Instant::now();
    let (film, stats) = with_threads(plan.threads, || {
        render(scene, &plan.frame, &|rows| progress.advance(rows))
    })??;
    progress.finish();
    let render_time = started.elapsed();
    if stats.non_finite > 0 {
        eprintln!(
            "warning: {} non-finite layer values (NaN or infinity) were written as 0",
            stats.non_finite
        );
    }

    // Write everything to temporary files first, then rename: all outputs or none.
    let started = Instant::now();
    if let Some(file) = exr_file.as_mut() {
        let light_names = scene.lights.iter().map(|l| l.name.clone()).collect();
        let metadata = render_record::metadata(&plan, &input.name, &input.bytes, light_names);
        let path = file.target().to_path_buf();
        write_exr(file.file(), &film, plan.exr_options, &metadata)
            .map_err(|msg| Error::Exr { path, msg })?;
    }
    let exr_time = started.elapsed();
    if let Some(png) = png.as_mut() {
        png.write_png(&encode(
            &film.beauty,
            film.width,
            film.height,
            &plan.encoding,
        ))?;
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
        let layers = film.layers.len();
        eprintln!("{}", summary(&plan, &stats, layers, render_time, exr_time));
    }
    Ok(())
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

fn summary(
    plan: &RenderPlan,
    stats: &RenderStats,
    layers: usize,
    render_time: Duration,
    exr_time: Duration,
) -> String {
    let seconds = render_time.as_secs_f64();
    let rate = stats.rays as f64 / seconds.max(1e-9) / 1e6;
    let mut outputs = Vec::new();
    if let Some(exr) = &plan.exr {
        outputs.push(format!(
            "{} ({layers} layers, written in {:.2} s)",
            exr.display(),
            exr_time.as_secs_f64()
        ));
    }
    if let Some(png) = &plan.png {
        outputs.push(if png.as_os_str() == STDOUT {
            "standard output".to_string()
        } else {
            png.display().to_string()
        });
    }
    let target = if outputs.is_empty() {
        String::new()
    } else {
        format!(" -> {}", outputs.join(", "))
    };
    let frame = &plan.frame;
    let bounces = frame.trace.bounces;
    format!(
        "whitted: {}x{}, {} spp, {bounces} bounce{}, {} rays in {seconds:.2} s ({rate:.1} Mrays/s, \
         hierarchy built in {:.2} s){target}",
        frame.region.width(),
        frame.region.height(),
        frame.spp,
        if bounces == 1 { "" } else { "s" },
        stats.rays,
        stats.hierarchy_time.as_secs_f64(),
    )
}
