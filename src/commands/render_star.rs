//! `whitted render` of a Tick 1* scene or with Tick 1* effects (docs/tick1star.md): bump
//! maps read relative to the scene file, soft shadows and depth of field sampled as
//! `--sampling` says, written by the same PNG and EXR writers as every render.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

use super::render::{outputs, Targets};
use crate::cli::RenderArgs;
use whitted_core::aov;
use whitted_core::error::{Error, Result};
use whitted_core::scene::input::Input;
use whitted_core::star::{star_film, BumpMethod, BumpedSphere, Sampling, Star, StarFrame};
use whitted_io::bump_map;
use whitted_io::plan::RenderPlan;

/// Whether `render` takes this path: a Tick 1* effect is asked for or the scene has bumps.
pub fn wanted(args: &RenderArgs, input: &Input) -> bool {
    args.star.random() || !input.bumps.is_empty()
}

/// The bumped spheres of `input` with their maps, read relative to the scene file's folder
/// (the working directory for the embedded scene); one read per distinct map.
pub fn bumped_spheres(input: &Input, scene_file: Option<&Path>) -> Result<Vec<BumpedSphere>> {
    let folder = scene_file
        .and_then(Path::parent)
        .map_or_else(PathBuf::new, Path::to_path_buf);
    let mut read: HashMap<PathBuf, Arc<whitted_core::star::BumpMap>> = HashMap::new();
    input
        .bumps
        .iter()
        .map(|b| {
            let Some(name) = &b.map else {
                return Err(Error::Usage(format!(
                    "{}: <bumpy-sphere> has no bump-map attribute (the course's needs one)",
                    b.at
                )));
            };
            let path = folder.join(name);
            let map = match read.get(&path) {
                Some(map) => Arc::clone(map),
                None => {
                    let map = Arc::new(bump_map::read(&path, &b.at)?);
                    read.insert(path, Arc::clone(&map));
                    map
                }
            };
            Ok(BumpedSphere {
                object: b.object,
                map,
            })
        })
        .collect()
}

pub fn run(args: &RenderArgs, input: &Input) -> Result<()> {
    if args.region.is_some() || args.spp != 1 {
        return Err(Error::Usage(
            "--region and --spp are not available with Tick 1* (bump maps, --soft-shadows, \
             --dof): each pixel's rays are the course's"
                .into(),
        ));
    }
    let bumps = bumped_spheres(input, args.input.as_deref())?;
    let scene = &input.scene;
    // The tick's layers are chosen below, with Tick 1*'s own among them.
    let mut request = args.request();
    request.frame.aovs = "all".into();
    let plan = RenderPlan::new(&request, scene)?;
    let star = Star {
        soft: args.star.soft(),
        dof: args.star.dof,
        bump: BumpMethod {
            parametrisation: args.star.bump_param,
            mistake: None,
        },
        bumps,
    };
    let sampling = args.star.sampling();
    let converged = matches!(sampling, Sampling::Converged { .. });
    let bounces = plan.frame.trace().bounces;
    let layers = if plan.exr.is_some() {
        let names: Vec<String> = scene.lights.iter().map(|l| l.name.clone()).collect();
        let mut available = aov::all_layers(&names, bounces);
        available.extend(aov::star_layers(
            converged && star.is_random(),
            star.dof.is_some(),
            !star.bumps.is_empty(),
        ));
        aov::select(&args.aovs, &available).map_err(Error::Usage)?
    } else {
        Vec::new()
    };
    let mut targets = Targets::open(&plan)?;
    let frame = StarFrame {
        scene,
        camera: *plan.frame.camera(),
        course: plan.frame.course(),
        trace: plan.frame.trace(),
        star: &star,
    };
    let started = Instant::now();
    let (film, stats) =
        super::render::with_threads(plan.threads, || star_film(&frame, sampling, layers.clone()))??;
    let seconds = started.elapsed().as_secs_f64();
    if stats.non_finite > 0 {
        eprintln!(
            "warning: {} non-finite layer values (NaN or infinity) were written as 0",
            stats.non_finite
        );
    }
    let mut writers = targets.writers(&outputs(&plan, input, &film.layers))?;
    writers.write(&film)?;
    writers.finish()?;
    targets.publish()?;
    let camera = plan.frame.camera();
    if !args.quiet {
        let pixels = f64::from(camera.width) * f64::from(camera.height);
        eprintln!(
            "whitted: Tick 1* {}x{}, {} sampling ({:.1} camera rays a pixel), {bounces} bounce{}, \
             {} rays in {seconds:.2} s",
            camera.width,
            camera.height,
            if converged { "converged" } else { "course" },
            stats.camera_rays as f64 / pixels,
            if bounces == 1 { "" } else { "s" },
            stats.rays,
        );
    }
    Ok(())
}
