//! A Tick 1* student does one option, so one of the two handout scenes is rendered by their
//! Tick 1 renderer: `bump.xml` with a smooth sphere (option 1 not done), or `distributed.xml`
//! with hard shadows and no depth of field (option 2 not done). That image is whitted's Tick 1
//! render of the scene, deterministic, and is recognised as such before it is judged as its
//! option's (where it would read as a wrong bump map or "not a draw").

use crate::check::bump::{render_bump, PIXEL_TOLERANCE};
use crate::check::star_option::StarOption;
use crate::check::student_png::Rgb8;
use whitted_core::course::Course;
use whitted_core::error::Result;
use whitted_core::scene::Scene;
use whitted_core::star::{BumpMethod, Star};

/// Share of pixels that may differ from the Tick 1 render by more than `PIXEL_TOLERANCE`: a
/// few pixels of another rounding at an edge, not a soft shadow or a bump (each moves
/// thousands).
const STRAY: f64 = 0.002;

/// Whether `image` is whitted's Tick 1 render of `scene` (no bumps, hard shadows, pinhole)
/// under `course` at `bounces`, to within `PIXEL_TOLERANCE` on all but [`STRAY`] of pixels.
pub fn is_tick1_render(scene: &Scene, image: &Rgb8, bounces: u32, course: Course) -> Result<bool> {
    let size = (image.width, image.height);
    let tick1 = render_bump(
        scene,
        &Star::default(),
        BumpMethod::default(),
        size,
        bounces,
        course,
    )?;
    if tick1.bytes.len() != image.bytes.len() {
        return Ok(false);
    }
    let off = tick1
        .bytes
        .chunks_exact(3)
        .zip(image.bytes.chunks_exact(3))
        .filter(|(a, b)| {
            a.iter()
                .zip(*b)
                .any(|(x, y)| x.abs_diff(*y) > PIXEL_TOLERANCE)
        })
        .count();
    let pixels = (image.width as usize) * (image.height as usize);
    Ok((off as f64) <= STRAY * pixels as f64)
}

/// Pixels of the sphere's edge left out of the flatness test: depth of field blurs the edge
/// over a few pixels.
const EDGE: usize = 3;

/// Largest spread (standard deviation, in 8-bit steps, per channel) of a sphere shaded flat:
/// a smooth sphere's shading spans tens of steps, a bump map's relief more.
const FLAT: f64 = 1.5;

/// Whether the bumped sphere of `scene` is shaded flat in `image`: where the Tick 1 render
/// shows the sphere (away from its edge), every channel is nearly one value. A
/// `getNormalAt` that returns the zero vector (the skeleton's stub) does that: no diffuse or
/// specular term, whatever the options.
pub fn is_flat_sphere(scene: &Scene, image: &Rgb8, bounces: u32, course: Course) -> Result<bool> {
    let (w, h) = (image.width as usize, image.height as usize);
    let tick1 = render_bump(
        scene,
        &Star::default(),
        BumpMethod::default(),
        (image.width, image.height),
        bounces,
        course,
    )?;
    if tick1.bytes.len() != image.bytes.len() {
        return Ok(false);
    }
    // The sphere: where the Tick 1 render is not the background (its corner's colour).
    let background = &tick1.bytes[..3];
    let lit = |x: usize, y: usize| &tick1.bytes[3 * (y * w + x)..3 * (y * w + x) + 3] != background;
    let inside: Vec<usize> = (EDGE..h.saturating_sub(EDGE))
        .flat_map(|y| (EDGE..w.saturating_sub(EDGE)).map(move |x| (x, y)))
        .filter(|&(x, y)| {
            (y - EDGE..=y + EDGE).all(|yy| (x - EDGE..=x + EDGE).all(|xx| lit(xx, yy)))
        })
        .map(|(x, y)| y * w + x)
        .collect();
    // Too few pixels of sphere to say.
    if inside.len() < 50 {
        return Ok(false);
    }
    let n = inside.len() as f64;
    Ok((0..3).all(|c| {
        let values = inside.iter().map(|&i| f64::from(image.bytes[3 * i + c]));
        let mean = values.clone().sum::<f64>() / n;
        let var = values.map(|v| (v - mean).powi(2)).sum::<f64>() / n;
        var.sqrt() <= FLAT
    }))
}

/// The report's line for an image of `option`'s scene that is the Tick 1 render; `neither`:
/// the other option's image was the Tick 1 render too.
pub fn sentence(option: StarOption, neither: bool) -> String {
    let what = match option {
        StarOption::Bump => {
            "option 1 not done (no bump map on the sphere: it is smooth, or shaded flat as \
             the skeleton's getNormalAt stub leaves it)"
        }
        StarOption::Distributed => {
            "option 2 not done (hard shadows, no depth of field: the image is the Tick 1 render \
             of distributed.xml)"
        }
    };
    match neither {
        false => format!("{what}: fine, one option is enough"),
        true => format!(
            "{what}, and neither is the other option: Tick 1* needs one of bump mapping \
             (BumpySphere.getNormalAt) or soft shadows and depth of field (Renderer)"
        ),
    }
}
