//! A Tick 1* option's case on the report page (`check --program --report x.html`): its image
//! whatever the verdict (a random image is not seen again by running the program again), and
//! beside an option 1 image the render it was compared with and where they differ, with the
//! worst region enlarged, as a Tick 1 case's block shows them; beside an option 2 image that
//! is no draw of the course's process, the tile where it fits worst, enlarged.

use super::html::trio;
use super::zoom::{worst_region, Region};
use crate::check::bump::PIXEL_TOLERANCE;
use crate::check::report::heat_map;
use crate::check::star_run::{StarImage, StarVerdict};
use whitted_io::html::{escape, image};
use whitted_io::output::png::PngPixels;

/// The option's block: its name and verdict, then its images.
pub fn star_block(name: &str, star: &StarImage) -> String {
    let class = match star.verdict.passes() {
        true => "pass",
        false => "fail",
    };
    let mut out = format!(
        "<section class=\"case\">\n<h2>{}: {}</h2>\n<p class=\"{class}\">{}</p>\n",
        escape(name),
        escape(star.option.what()),
        escape(&star.verdict.line())
    );
    let shown = &star.image;
    let (w, h) = (shown.width, shown.height);
    let yours = image(w, h, shown.bytes.clone(), "your image");
    match (&star.reference, &star.verdict) {
        (Some(reference), StarVerdict::Bump(b)) => {
            let heat = match heat_map(shown, reference, PIXEL_TOLERANCE).pixels {
                PngPixels::Eight(bytes) => bytes,
                PngPixels::Sixteen(_) => Vec::new(),
            };
            let compared = format!(
                "the handout's method under parametrisation {}",
                escape(b.parametrisation)
            );
            out += &trio(&[
                (yours, "your image"),
                (
                    image(w, h, reference.bytes.clone(), "the reference"),
                    &compared,
                ),
                (
                    image(w, h, heat.clone(), "where they differ"),
                    "where they differ",
                ),
            ]);
            if let Some(region) = worst_region(shown, reference) {
                let side = region.shown_side();
                let zoom = |rgb: &[u8], alt: &str| image(side, side, region.enlarged(rgb, w), alt);
                out += &format!("<p>Where they differ most: {}:</p>\n", region.described());
                out += &trio(&[
                    (zoom(&shown.bytes, "your image, enlarged"), "your image"),
                    (
                        zoom(&reference.bytes, "the reference, enlarged"),
                        "the reference",
                    ),
                    (
                        zoom(&heat, "where they differ, enlarged"),
                        "where they differ",
                    ),
                ])
                .replace("class=\"trio\"", "class=\"trio zoom\"");
            }
        }
        (_, StarVerdict::Draw(d)) if !star.verdict.passes() => {
            let (x, y, tw, th) = d.region;
            let region = Region {
                x,
                y,
                size: tw.min(th),
            };
            let side = region.shown_side();
            out += &trio(&[
                (yours, "your image"),
                (
                    image(
                        side,
                        side,
                        region.enlarged(&shown.bytes, w),
                        "your image where the course's process fits worst, enlarged",
                    ),
                    "where the course's process fits worst",
                ),
            ]);
            out += &format!("<p>The enlarged tile: {}.</p>\n", region.described());
        }
        _ => out += &trio(&[(yours, "your image")]),
    }
    out + "</section>\n"
}
