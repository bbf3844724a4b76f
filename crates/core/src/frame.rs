//! What one render computes, checked before anything runs: the image and the part of it to
//! render, the samples, the trace options and the layers to fill. The layers are derived from
//! the same bounce count the trace uses, so the two cannot disagree.

pub mod limits;

use crate::aov::{self, Layer};
use crate::camera::Camera;
use crate::course::Course;
use crate::error::{Error, Result};
use crate::scene::Scene;
use crate::trace::TraceOptions;

/// A rectangle of the full image, `[x0, x1) x [y0, y1)`: the part a farm node renders.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Region {
    pub x0: u32,
    pub y0: u32,
    pub x1: u32,
    pub y1: u32,
}

impl Region {
    pub fn full(width: u32, height: u32) -> Self {
        Region {
            x0: 0,
            y0: 0,
            x1: width,
            y1: height,
        }
    }

    pub fn width(&self) -> u32 {
        self.x1 - self.x0
    }

    pub fn height(&self) -> u32 {
        self.y1 - self.y0
    }

    /// Whether this is a non-empty rectangle inside a `width` x `height` image.
    fn fits(&self, width: u32, height: u32) -> bool {
        self.x0 < self.x1 && self.y0 < self.y1 && self.x1 <= width && self.y1 <= height
    }
}

/// The frame split into `parts` bands of whole rows, top to bottom, whose heights differ by at
/// most one row: each farm task gets the same work to within a row. An error when there are
/// more parts than rows.
pub fn balanced_regions(width: u32, height: u32, parts: u32) -> Result<Vec<Region>> {
    if parts == 0 || parts > height {
        return Err(Error::Usage(format!(
            "cannot split {height} rows into {parts} parts (1 to {height} parts)"
        )));
    }
    Ok((0..parts)
        .map(|i| {
            let row = |k: u32| (u64::from(k) * u64::from(height) / u64::from(parts)) as u32;
            Region {
                x0: 0,
                y0: row(i),
                x1: width,
                y1: row(i + 1),
            }
        })
        .collect())
}

/// How nearest hits are found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Acceleration {
    /// The bounding volume hierarchy (the normal path).
    #[default]
    Bvh,
    /// Every object for every ray: the reference the hierarchy is tested against.
    BruteForce,
}

/// What is asked for, unchecked.
#[derive(Debug, Clone, PartialEq)]
pub struct FrameSpec {
    pub width: u32,
    pub height: u32,
    /// The part of the image to render; `None` for all of it.
    pub region: Option<Region>,
    /// Samples per pixel, a square k*k: a fixed stratified grid, no randomness.
    pub spp: u32,
    pub bounces: u32,
    pub shadows: bool,
    /// `--aovs`: `all`, `beauty` or a comma-separated list of layer names.
    pub aovs: String,
    /// The year whose rules render the frame (docs/courses.md).
    pub course: Course,
    pub acceleration: Acceleration,
}

impl Default for FrameSpec {
    /// The course's render: 640x480, 2 bounces, shadows, one sample at each pixel's centre,
    /// every layer.
    fn default() -> Self {
        FrameSpec {
            width: 640,
            height: 480,
            region: None,
            spp: 1,
            bounces: 2,
            shadows: true,
            aovs: "all".into(),
            acceleration: Acceleration::Bvh,
            course: Course::default(),
        }
    }
}

impl FrameSpec {
    /// The tick PNG's frame at this size (the beauty only, one sample at each pixel's centre):
    /// what `check` renders a student's image against and the viewer's ray trees trace.
    pub fn tick(width: u32, height: u32, bounces: u32, shadows: bool) -> Self {
        FrameSpec {
            width,
            height,
            bounces,
            shadows,
            aovs: "beauty".into(),
            ..FrameSpec::default()
        }
    }
}

/// A checked frame: what `render::render` runs. Its fields are private, so that nothing can
/// change a frame after `Frame::new` checked it.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    camera: Camera,
    /// Inside the camera's image and not empty.
    region: Region,
    /// A square k*k >= 1.
    spp: u32,
    trace: TraceOptions,
    /// The layers to fill, in file order; the beauty first. Built for `trace.bounces` and the
    /// scene's lights.
    layers: Vec<Layer>,
    acceleration: Acceleration,
    course: Course,
}

impl Frame {
    /// Checks `spec` against `scene`: the sides, bounces and samples are within `limits`, the
    /// region lies inside the image, and every named layer exists for this scene and bounce
    /// count.
    pub fn new(scene: &Scene, spec: &FrameSpec) -> Result<Self> {
        let (width, height) = (spec.width, spec.height);
        let usage = |what: &str, e: String| Error::Usage(format!("{what}: {e}"));
        limits::side(i64::from(width)).map_err(|e| usage("the image width", e))?;
        limits::side(i64::from(height)).map_err(|e| usage("the image height", e))?;
        limits::bounces(i64::from(spec.bounces)).map_err(Error::Usage)?;
        limits::samples(i64::from(spec.spp)).map_err(Error::Usage)?;
        let region = spec.region.unwrap_or(Region::full(width, height));
        if !region.fits(width, height) {
            return Err(Error::Usage(format!(
                "the region {},{},{},{} is not a non-empty part of the {width}x{height} image",
                region.x0, region.y0, region.x1, region.y1
            )));
        }
        let light_names: Vec<String> = scene.lights.iter().map(|l| l.name.clone()).collect();
        let catalogue = aov::all_layers(&light_names, spec.bounces);
        let layers = aov::select(&spec.aovs, &catalogue).map_err(Error::Usage)?;
        Ok(Frame {
            camera: Camera::with_rows(width, height, spec.course.row_step()),
            region,
            spp: spec.spp,
            trace: TraceOptions {
                bounces: spec.bounces,
                shadows: spec.shadows,
            },
            layers,
            acceleration: spec.acceleration,
            course: spec.course,
        })
    }

    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    pub fn region(&self) -> Region {
        self.region
    }

    pub fn spp(&self) -> u32 {
        self.spp
    }

    pub fn trace(&self) -> TraceOptions {
        self.trace
    }

    pub fn layers(&self) -> &[Layer] {
        &self.layers
    }

    pub fn acceleration(&self) -> Acceleration {
        self.acceleration
    }

    /// The year whose rules render the frame.
    pub fn course(&self) -> Course {
        self.course
    }

    /// The same frame with no layers to fill (a render to a PNG only needs the beauty, which
    /// every film has).
    pub fn without_layers(self) -> Frame {
        Frame {
            layers: Vec::new(),
            ..self
        }
    }

    /// Values stored per pixel: the channels of every layer.
    pub fn channel_count(&self) -> usize {
        self.layers
            .iter()
            .map(|l| l.quantity.channels().len())
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(spec: FrameSpec) -> Result<Frame> {
        let scene = crate::scene::parse_str("t.xml", "<scene/>").expect("scene");
        Frame::new(&scene, &spec)
    }

    #[test]
    fn regions_must_lie_inside_the_image() {
        for (x0, y0, x1, y1) in [(0, 0, 11, 10), (5, 5, 5, 9), (3, 0, 2, 10)] {
            let spec = FrameSpec {
                width: 10,
                height: 10,
                region: Some(Region { x0, y0, x1, y1 }),
                ..FrameSpec::default()
            };
            assert!(frame(spec).is_err(), "{x0},{y0},{x1},{y1}");
        }
        let spec = FrameSpec {
            width: 10,
            height: 10,
            region: Some(Region {
                x0: 2,
                y0: 3,
                x1: 7,
                y1: 4,
            }),
            ..FrameSpec::default()
        };
        assert_eq!(frame(spec).expect("fits").region.width(), 5);
    }

    #[test]
    fn balanced_regions_tile_the_frame_with_even_bands() {
        let parts = balanced_regions(640, 480, 7).expect("split");
        assert_eq!(parts.len(), 7);
        assert_eq!((parts[0].y0, parts[6].y1), (0, 480));
        for pair in parts.windows(2) {
            assert_eq!(pair[0].y1, pair[1].y0);
        }
        let heights: Vec<u32> = parts.iter().map(Region::height).collect();
        assert!(heights.iter().max().expect("max") - heights.iter().min().expect("min") <= 1);
        assert!(balanced_regions(640, 4, 5).is_err());
    }

    #[test]
    fn layers_follow_the_trace_bounces() {
        let spec = FrameSpec {
            bounces: 3,
            ..FrameSpec::default()
        };
        let frame = frame(spec).expect("frame");
        assert_eq!(frame.trace.bounces, 3);
        assert!(frame.layers.iter().any(|l| l.name == "reflected_3"));
        assert!(!frame.layers.iter().any(|l| l.name == "reflected_4"));
    }

    #[test]
    fn the_limits_hold_for_library_callers_too() {
        for spec in [
            FrameSpec {
                bounces: u32::MAX,
                ..FrameSpec::default()
            },
            FrameSpec {
                width: 0,
                ..FrameSpec::default()
            },
            FrameSpec {
                height: 70_000,
                ..FrameSpec::default()
            },
            FrameSpec {
                spp: 4096,
                ..FrameSpec::default()
            },
        ] {
            assert!(frame(spec.clone()).is_err(), "{spec:?}");
        }
    }

    #[test]
    fn bad_samples_and_layers_are_refused() {
        let spp = FrameSpec {
            spp: 8,
            ..FrameSpec::default()
        };
        assert!(frame(spp).is_err());
        let aovs = FrameSpec {
            aovs: "direct,nope".into(),
            ..FrameSpec::default()
        };
        let err = frame(aovs).unwrap_err().to_string();
        assert!(err.contains("unknown AOV layer `nope`"), "{err}");
    }
}
