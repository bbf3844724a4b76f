//! `whitted render` (and the bare `whitted ...` tick command line): scene -> plan -> strips
//! -> files (`output/writers.rs`). Every check is the plan's; this file runs it and reports.

use std::time::{Duration, Instant};

use crate::cli::RenderArgs;
use whitted_core::error::{Error, Result};
use whitted_core::progress::Bar;
use whitted_core::render::{render_strips, RenderStats};
use whitted_core::scene;
use whitted_io::output::atomic::AtomicFile;
use whitted_io::output::destination::{Destination, STDOUT};
use whitted_io::output::exr::Placement;
use whitted_io::output::writers::{Outputs, Writers};
use whitted_io::plan::RenderPlan;
use whitted_io::render_record;

pub fn run(args: &RenderArgs) -> Result<()> {
    let started = Instant::now();
    let input = scene::input::load_input(args.input.as_deref(), args.frame.course.course())?;
    if super::render_star::wanted(args, &input) {
        input.report_warnings_applying_bumps();
        return super::render_star::run(args, &input);
    }
    input.report_warnings();
    let load_time = started.elapsed();
    let scene = &input.scene;
    let plan = RenderPlan::new(&args.request(), scene)?;
    let mut targets = Targets::open(&plan)?;

    let progress = Bar::new(u64::from(plan.frame.region().height()), args.quiet);
    let started = Instant::now();
    // Both writers take each strip as it is finished, into temporary files: then rename, so
    // that there are all outputs or none.
    let (stats, exr_time) = with_threads(plan.threads, || -> Result<(RenderStats, Duration)> {
        let mut writers = targets.writers(&outputs(&plan, &input, plan.frame.layers()))?;
        let stats = render_strips(
            scene,
            &plan.frame,
            plan.strip_rows,
            &|n| progress.advance(n),
            &mut |strip| writers.write(strip),
        )?;
        let exr_time = writers.finish()?;
        Ok((stats, exr_time))
    })??;
    progress.finish();
    let render_time = started.elapsed();
    if stats.non_finite > 0 {
        eprintln!(
            "warning: {} non-finite layer values (NaN or infinity) were written as 0",
            stats.non_finite
        );
    }
    targets.publish()?;

    if !args.quiet {
        let layers = plan.frame.layers().len();
        let times = Times {
            load: load_time,
            render: render_time,
            exr: exr_time,
        };
        eprintln!("{}", summary(&plan, &stats, layers, times));
    }
    Ok(())
}

/// Runs `work` on a pool of `threads` workers, or on rayon's global pool (all cores).
pub(crate) fn with_threads<T: Send>(
    threads: Option<usize>,
    work: impl FnOnce() -> T + Send,
) -> Result<T> {
    match threads {
        None => Ok(work()),
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .map(|pool| pool.install(work))
            .map_err(|e| Error::Environment(format!("cannot start {n} worker threads: {e}"))),
    }
}

/// How long the phases of a render took, for the summary line.
struct Times {
    load: Duration,
    /// Hierarchy build, tracing and writing, which overlap.
    render: Duration,
    /// Packing, compressing and writing EXR blocks, summed over the threads that did it
    /// (alongside the render, so it can exceed the render's wall time).
    exr: Duration,
}

fn summary(plan: &RenderPlan, stats: &RenderStats, layers: usize, times: Times) -> String {
    let seconds = times.render.as_secs_f64();
    let rate = stats.rays as f64 / seconds.max(1e-9) / 1e6;
    let mut outputs = Vec::new();
    if let Some(exr) = &plan.exr {
        outputs.push(format!(
            "{} ({layers} layers, {:.2} s of CPU to write)",
            exr.display(),
            times.exr.as_secs_f64()
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
    let bounces = frame.trace().bounces;
    format!(
        "whitted: {}x{}, {} spp, {bounces} bounce{}, {} rays in {seconds:.2} s ({rate:.1} Mrays/s, \
         scene loaded in {:.2} s, hierarchy built in {:.2} s){target}",
        frame.region().width(),
        frame.region().height(),
        frame.spp(),
        if bounces == 1 { "" } else { "s" },
        stats.rays,
        times.load.as_secs_f64(),
        stats.hierarchy_time.as_secs_f64(),
    )
}

/// The files a render writes: opened before it renders, so that an unwritable path fails in
/// milliseconds, written into temporary files and published together at the end, so that
/// there are all outputs or none. Every render (the tick's and Tick 1*'s) goes through it.
pub(crate) struct Targets {
    png: Option<Destination>,
    exr: Option<AtomicFile>,
}

impl Targets {
    pub(crate) fn open(plan: &RenderPlan) -> Result<Self> {
        Ok(Targets {
            png: plan.png.as_deref().map(Destination::open).transpose()?,
            exr: plan.exr.as_deref().map(AtomicFile::create).transpose()?,
        })
    }

    /// The PNG and EXR writers over these files.
    pub(crate) fn writers<'a>(&'a mut self, outputs: &Outputs) -> Result<Writers<'a>> {
        Writers::open(outputs, self.png.as_mut(), self.exr.as_mut())
    }

    /// Renames the finished files into place, unless Ctrl-C came while they were being
    /// written: then they are dropped rather than published.
    pub(crate) fn publish(self) -> Result<()> {
        whitted_core::interrupt::check()?;
        if let Some(file) = self.exr {
            file.commit()?;
        }
        if let Some(png) = self.png {
            png.commit()?;
        }
        Ok(())
    }
}

/// What the writers are to write for `plan`: `layers` over the plan's region. The EXR's header
/// metadata (the render record) is built here, with the rest of the plan's facts, so that
/// `output/` knows nothing of plans or scenes.
pub(crate) fn outputs<'a>(
    plan: &RenderPlan,
    input: &scene::input::Input,
    layers: &'a [whitted_core::aov::Layer],
) -> Outputs<'a> {
    let (region, camera) = (plan.frame.region(), plan.frame.camera());
    let metadata = plan.exr.is_some().then(|| {
        let lights = input.scene.lights.iter().map(|l| l.name.clone()).collect();
        render_record::metadata(plan, &input.name, &input.bytes, lights)
    });
    Outputs {
        placement: Placement {
            size: (region.width() as usize, region.height() as usize),
            origin: (region.x0 as i32, region.y0 as i32),
            display: ((0, 0), (camera.width as usize, camera.height as usize)),
        },
        layers,
        encoding: plan.encoding,
        exr_options: plan.exr_options,
        metadata,
    }
}
