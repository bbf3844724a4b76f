//! Whether a Tick 1* option 2 image (soft shadows and depth of field on `distributed.xml`) is
//! one draw of the course's random process, and if not, of which variant (docs/check.md,
//! "Tick 1*"). No two correct images are alike, so no byte comparison can judge one; but every
//! pixel's distribution is known (`whitted_core::star::expectation`: its expectation and the
//! variance of one draw, in linear radiance before the tone map).
//!
//! The test: each channel's byte y is scored as z = (y - E[y]) / sd[y], where E[y] and sd[y]
//! are the mean and spread of the course's tone map and 8-bit quantisation over a normal of
//! the pixel's expectation and variance (Gauss-Hermite nodes, so the curve's bend, its clamp
//! and the truncation to a byte are in them), widened by the expectation's own estimate error
//! and a floor of a quarter byte squared for arithmetic that differs in the last bit. The
//! statistic is the mean of z^2 over every channel the process spreads by a byte or more: about 1 for a draw of the
//! process, above it for another one. An image whose statistic exceeds [`THRESHOLD`] is not a
//! draw; the variants whitted can render are scored the same way, and the one scoring lowest
//! under the threshold is named, with the tile where the course's score is worst.

use glam::DVec3;

use crate::check::star_prepass;
use crate::check::star_reference::{ReferenceCache, ReferenceKey};
use crate::check::student_png::Rgb8;
use whitted_core::course::Course;
use whitted_core::error::{Error, Result};
use whitted_core::frame::{Frame, FrameSpec};
use whitted_core::scene::{self, Scene};
use whitted_core::star::{
    DepthOfField, Focus, Grid, LightSampling, NoiseFloor, ShadowShare, ShadowedTerms, SoftShadows,
    Star, StarFrame,
};
use whitted_io::output::png::bytes_with;

/// The mean z^2 above which an image is no draw of a distribution. Measured at 160x120 on
/// 2023-24 with our Java Tick 1* (tests/java/tick1star) against the expectation of
/// `whitted_core::star` as merged: 24 seeded draws of the correct program scored 1.03 to 1.25
/// (spread about 0.05), none above the threshold (0 false alarms in 24; 1.45 is four spreads
/// above the highest); each variant's image scored 1.68 (focal distance along the ray) to
/// thousands (not averaged) against the course's process, and 0.97 to 1.28 against its own.
/// Measured again with the eight variants of [`Process`] (seeds 601 and 602 of each of the
/// four added since, 8 fresh seeds of the correct program): the correct program 1.04 to 1.13;
/// light-surface 3.36 against the course and 1.06 against its own, shadows-not-averaged 1461
/// and 1.14, specular-not-scaled 2.07 and 1.09, focal-distance 1.59 (the nearest to the
/// threshold of any variant) and 1.07; no variant's image scored under 1.45 against another's.
/// tests/integration/check_star.rs measures it again on fresh seeds.
pub const THRESHOLD: f64 = 1.45;

/// The expectation's noise floor (linear standard error per channel): about one byte of the
/// tone-mapped image, its error added to each pixel's spread. A quarter of that costs ten
/// times the time and changes no verdict.
const FLOOR: f64 = 0.004;

/// The Sobol scrambling of the expectation: fixed, so that a check is reproducible.
const SEED: u64 = 1;

/// Squared bytes every channel's spread is at least: the last bit of arithmetic done another
/// way (Java's doubles and whitted's agree to it, not beyond).
const BYTE_FLOOR: f64 = 0.25;

/// Squared bytes a channel's spread must reach to be scored: a channel the process hardly
/// moves is the same in every variant and only dilutes the statistic.
const RANDOM: f64 = 1.0;

/// Side in pixels of the tiles the report's region is chosen among.
const TILE: u32 = 16;

/// The process an image may be a draw of: the course's, or a variant of it whitted renders.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Process {
    /// The handout's: 10 shadow rays to `randomInsideUnitSphere` points of radius 0.4, 50
    /// aperture rays of a square of side 0.2, averaged.
    Course,
    /// The light's points uniform in its ball, not the course's centre-heavy draw.
    UniformSphere,
    /// The light's radius halved (0.4 taken as its diameter).
    LightSize,
    /// The aperture's coordinates span the whole side 0.2 each way (a square of side 0.4).
    ApertureFullSide,
    /// The 50 aperture rays summed, not averaged.
    DofNotAveraged,
    /// The light's points on its sphere's surface: the course's point normalised, times 0.4.
    LightSurface,
    /// The count of unoccluded shadow rays used as the scale, not divided by the 10 cast.
    ShadowsNotAveraged,
    /// The visible share scales the diffuse term only; the specular is added whole.
    SpecularNotScaled,
    /// The focal point `DOF_FOCAL_PLANE` along the pinhole ray, not on the plane z = 3.51805.
    FocalDistance,
    /// The course's soft shadows, and no depth of field: one pinhole ray per pixel.
    NoDepthOfField,
    /// The course's depth of field, and hard shadows: one shadow ray to the light's centre.
    NoSoftShadows,
}

impl Process {
    pub const ALL: [Process; 11] = [
        Process::Course,
        Process::UniformSphere,
        Process::LightSize,
        Process::ApertureFullSide,
        Process::DofNotAveraged,
        Process::LightSurface,
        Process::ShadowsNotAveraged,
        Process::SpecularNotScaled,
        Process::FocalDistance,
        Process::NoDepthOfField,
        Process::NoSoftShadows,
    ];

    /// The JSON value.
    pub fn name(self) -> &'static str {
        match self {
            Process::Course => "course",
            Process::UniformSphere => "uniform-sphere",
            Process::LightSize => "light-size",
            Process::ApertureFullSide => "aperture-full-side",
            Process::DofNotAveraged => "dof-not-averaged",
            Process::LightSurface => "light-surface",
            Process::ShadowsNotAveraged => "shadows-not-averaged",
            Process::SpecularNotScaled => "specular-not-scaled",
            Process::FocalDistance => "focal-distance",
            Process::NoDepthOfField => "no-depth-of-field",
            Process::NoSoftShadows => "no-soft-shadows",
        }
    }

    /// Whether a program drawing from it does what the handout asks: the course's process, or
    /// the aperture over the whole side, which the handout's words allow too
    /// (docs/tick1star.md: "each coordinate ... scaled by the half side; the handout's words
    /// allow the full side too"). Such a draw is named and passes.
    pub fn accepted(self) -> bool {
        matches!(self, Process::Course | Process::ApertureFullSide)
    }

    /// What a program drawing from it does, in words.
    pub fn explanation(self) -> &'static str {
        match self {
            Process::Course => "the handout's soft shadows and depth of field",
            Process::UniformSphere => {
                "the light's points are uniform in its sphere; the course's \
                 Vector3.randomInsideUnitSphere draws radius and angles uniformly (denser at \
                 the centre): use it"
            }
            Process::LightSize => {
                "the light's sphere has radius 0.2: LIGHT_SIZE (0.4) is the radius, scale the \
                 unit sphere's point by it"
            }
            Process::ApertureFullSide => {
                "the aperture's points span [-0.2, 0.2], DOF_AMOUNT each way: the handout's \
                 words allow this reading (its own program takes DOF_AMOUNT as the side, each \
                 coordinate (2 random - 1) times half of it), so it passes"
            }
            Process::DofNotAveraged => {
                "the 50 aperture rays' colours are summed: divide by DOF_RAY_COUNT"
            }
            Process::LightSurface => {
                "the light's points lie on its sphere's surface (the random point normalised): \
                 the handout's point is LIGHT_SIZE times Vector3.randomInsideUnitSphere() as it \
                 comes, inside the sphere; do not normalise it"
            }
            Process::ShadowsNotAveraged => {
                "the light's terms are scaled by the number of shadow rays that reach it: \
                 divide that count by SHADOW_RAY_COUNT before scaling diffuse and specular"
            }
            Process::SpecularNotScaled => {
                "only the diffuse term is scaled by the share of shadow rays that reach the \
                 light: scale the specular term by the same share (highlights show in shadow)"
            }
            Process::FocalDistance => {
                "the focal point is DOF_FOCAL_PLANE along the ray (ray.evaluateAt(3.51805)): \
                 it is where the ray meets the plane z = DOF_FOCAL_PLANE, at \
                 DOF_FOCAL_PLANE / direction.z along it"
            }
            Process::NoDepthOfField => {
                "soft shadows, but every pixel is one pinhole ray (sharp everywhere): option 2 \
                 is both, so average DOF_RAY_COUNT rays from random points of the aperture \
                 through the pixel's point on the plane z = DOF_FOCAL_PLANE"
            }
            Process::NoSoftShadows => {
                "depth of field, but each shadow is one ray to the light's centre (hard \
                 edges): option 2 is both, so cast SHADOW_RAY_COUNT shadow rays to random \
                 points of the light's sphere and scale its diffuse and specular terms by the \
                 share that reach it"
            }
        }
    }

    /// What it renders, and by what its expectation is scaled (a sum of D draws is D times
    /// their mean, its variance D^2 times).
    fn star(self) -> (Star, f64) {
        let mut soft = SoftShadows::default();
        let mut dof = DepthOfField::default();
        let mut scale = 1.0;
        match self {
            Process::Course => {}
            Process::UniformSphere => soft.sampling = LightSampling::Uniform,
            Process::LightSize => soft.light_size /= 2.0,
            Process::ApertureFullSide => dof.side *= 2.0,
            Process::DofNotAveraged => scale = f64::from(dof.rays),
            Process::LightSurface => soft.sampling = LightSampling::Surface,
            Process::ShadowsNotAveraged => soft.share = ShadowShare::Count,
            Process::SpecularNotScaled => soft.scaled = ShadowedTerms::DiffuseOnly,
            Process::FocalDistance => dof.focus = Focus::Distance,
            Process::NoDepthOfField | Process::NoSoftShadows => {}
        }
        let star = Star {
            soft: (self != Process::NoSoftShadows).then_some(soft),
            dof: (self != Process::NoDepthOfField).then_some(dof),
            ..Star::default()
        };
        (star, scale)
    }
}

/// How well an image fits one process.
#[derive(Debug, Clone, PartialEq)]
pub struct Fit {
    pub process: Process,
    /// The mean z^2 over every random channel of the pixels scored.
    pub statistic: f64,
    /// The pixels scored: 1 every pixel; more, the pre-pass's grid alone (the process was not
    /// the best of those scored with it, or too far from the image for the rest to matter).
    pub stride: u32,
}

impl Fit {
    /// The fit of `process` as the pre-pass scored it: its mean, and its grid's stride when it
    /// was not scored on every pixel.
    fn of(process: Process, score: &Score) -> Fit {
        Fit {
            process,
            statistic: score.mean(),
            stride: score.grid.stride,
        }
    }

    /// Whether the image is a draw of the process: scored on every pixel (a grid's score,
    /// its floor coarser, runs low, and is only ever a process too far to matter) and under
    /// the threshold.
    pub fn is_draw(&self) -> bool {
        self.stride == 1 && self.statistic <= THRESHOLD
    }
}

/// The judge's verdict on an option 2 image.
#[derive(Debug, Clone, PartialEq)]
pub struct DrawCheck {
    /// The course's fit, then each variant's that was scored (only when the course's fails).
    pub fits: Vec<Fit>,
    /// The tile (x, y, width, height) where the course's process fits worst.
    pub region: (u32, u32, u32, u32),
}

impl DrawCheck {
    pub fn course(&self) -> &Fit {
        &self.fits[0]
    }

    /// The process the image is a draw of: the course's when it fits, else the variant that
    /// fits best, if any does.
    pub fn drawn_from(&self) -> Option<Process> {
        if self.course().is_draw() {
            return Some(Process::Course);
        }
        self.fits[1..]
            .iter()
            .filter(|f| f.is_draw())
            .min_by(|a, b| a.statistic.total_cmp(&b.statistic))
            .map(|f| f.process)
    }

    /// Whether the image is a draw of what the handout asks (`Process::accepted`).
    pub fn passes(&self) -> bool {
        self.drawn_from().is_some_and(Process::accepted)
    }

    /// The verdict in a line.
    pub fn line(&self) -> String {
        let course = self.course().statistic;
        let (x, y, w, h) = self.region;
        match self.drawn_from() {
            Some(Process::Course) => format!(
                "scores as one draw of the course's distribution does (mean z^2 {course:.2}, at most \
                 {THRESHOLD} passes; another estimator of the same expectation, such as \
                 shading each light sample, scores alike)"
            ),
            Some(variant) if variant.accepted() => format!(
                "a draw of {} (mean z^2 {:.2}; the course's own process {course:.2}): {}",
                variant.name(),
                self.fits
                    .iter()
                    .find(|f| f.process == variant)
                    .map_or(0.0, |f| f.statistic),
                variant.explanation()
            ),
            Some(variant) => format!(
                "not a draw of the course's distribution (mean z^2 {course:.2} > {THRESHOLD}), \
                 but of {} (mean z^2 {:.2}): {}; it shows most at x {x}..{}, y {y}..{}",
                variant.name(),
                self.fits
                    .iter()
                    .find(|f| f.process == variant)
                    .map_or(0.0, |f| f.statistic),
                variant.explanation(),
                x + w,
                y + h
            ),
            None => format!(
                "not a draw of the course's distribution (mean z^2 {course:.2} > {THRESHOLD}) \
                 nor of a variant whitted renders ({}); it differs most at x {x}..{}, y {y}..{}",
                Process::ALL[1..]
                    .iter()
                    .map(|p| p.name())
                    .collect::<Vec<_>>()
                    .join(", "),
                x + w,
                y + h
            ),
        }
    }
}

/// The scene of option 2 as `course` reads it.
pub fn distributed_scene(course: Course) -> Result<Scene> {
    let option = crate::check::star_option::StarOption::Distributed;
    let (scene, _) =
        scene::input::parse_for_course(option.file(), option.xml().as_bytes(), course)?;
    Ok(scene)
}

/// Judges `image` as a draw of option 2 of `scene` rendered under `course` at `bounces`.
/// Each process is scored on the pre-pass's grid first (`star_prepass.rs`): only those near
/// the image are scored on every pixel.
pub fn check(scene: &Scene, image: &Rgb8, bounces: u32, course: Course) -> Result<DrawCheck> {
    let score = |processes: &[Process]| -> Result<Vec<Fit>> {
        let stars: Vec<(Star, f64)> = processes.iter().map(|p| p.star()).collect();
        let scores = star_prepass::scores(scene, &stars, image, bounces, course)?;
        Ok(processes
            .iter()
            .zip(&scores)
            .map(|(process, s)| Fit::of(*process, s))
            .collect())
    };
    let course_score = {
        let (star, scale) = Process::Course.star();
        star_prepass::scores(scene, &[(star, scale)], image, bounces, course)?
    };
    let course_score = course_score
        .first()
        .ok_or_else(|| Error::Usage("no score of the course's process".into()))?;
    let mut fits = vec![Fit::of(Process::Course, course_score)];
    if !fits[0].is_draw() {
        fits.extend(score(&Process::ALL[1..])?);
    }
    Ok(DrawCheck {
        fits,
        region: course_score.worst_tile(image.width, image.height),
    })
}

/// Every scored pixel's z^2, summed over its random channels, and how many it has: of every
/// pixel of the image, or of a pre-pass grid's.
pub(crate) struct Score {
    z2: Vec<f64>,
    random: Vec<u8>,
    /// The pixels scored; `z2[j * columns + i]` is the image's pixel (`grid.at(i)`, `grid.at(j)`).
    pub(crate) grid: Grid,
    columns: u32,
}

impl Score {
    /// The mean z^2 over the random channels of every pixel (where the process spreads a byte
    /// or more: the rest say nothing of it).
    pub(crate) fn mean(&self) -> f64 {
        let channels: u32 = self.random.iter().map(|&n| u32::from(n)).sum();
        self.z2.iter().sum::<f64>() / f64::from(channels.max(1))
    }

    /// The tile of [`TILE`] pixels a side (of the image, whatever the grid) whose mean z^2
    /// over its scored pixels is highest.
    fn worst_tile(&self, width: u32, height: u32) -> (u32, u32, u32, u32) {
        let tiles_x = width.div_ceil(TILE).max(1);
        let tiles = (tiles_x * height.div_ceil(TILE).max(1)) as usize;
        let (mut sum, mut count) = (vec![0.0; tiles], vec![0u32; tiles]);
        for (k, z2) in self.z2.iter().enumerate() {
            let (i, j) = (
                k as u32 % self.columns.max(1),
                k as u32 / self.columns.max(1),
            );
            let (x, y) = (self.grid.at(i), self.grid.at(j));
            let t = ((y / TILE) * tiles_x + x / TILE) as usize;
            if let (Some(s), Some(c)) = (sum.get_mut(t), count.get_mut(t)) {
                *s += z2;
                *c += 1;
            }
        }
        let mut best = (0.0, (0, 0, width.min(TILE), height.min(TILE)));
        for (t, (s, c)) in sum.iter().zip(&count).enumerate() {
            let (tx, ty) = ((t as u32 % tiles_x) * TILE, (t as u32 / tiles_x) * TILE);
            let mean = s / f64::from((*c).max(1));
            if *c > 0 && mean > best.0 {
                best = (mean, (tx, ty, TILE.min(width - tx), TILE.min(height - ty)));
            }
        }
        best.1
    }
}

/// The nodes and weights of 8-point Gauss-Hermite quadrature for a standard normal
/// (probabilists' form: the weights sum to 1).
const NODES: [(f64, f64); 8] = [
    (-4.1445471861258945, 0.00011261453837516037),
    (-2.802485861287542, 0.009635220120788),
    (-1.6365190424351077, 0.1172399076617591),
    (-0.539079811351375, 0.37301225767907725),
    (0.539079811351375, 0.37301225767907725),
    (1.6365190424351077, 0.1172399076617591),
    (2.802485861287542, 0.009635220120788),
    (4.1445471861258945, 0.00011261453837516037),
];

/// What one scoring estimates: at which pixels, and to what noise floor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Pass {
    pub(crate) grid: Grid,
    pub(crate) floor: NoiseFloor,
}

impl Pass {
    /// Every pixel, to the floor [`THRESHOLD`] was measured with.
    pub(crate) fn full() -> Pass {
        Pass {
            grid: Grid::EVERY,
            floor: NoiseFloor {
                standard_error: FLOOR,
                ..NoiseFloor::default()
            },
        }
    }
}

/// `image` scored at `pass`'s pixels against the distribution of `star` on `scene` (any Tick
/// 1* render: a bumped scene's too), its expectation scaled by `scale` and estimated to
/// `pass`'s floor (whose error widens each pixel's spread).
pub(crate) fn score_star(
    scene: &Scene,
    star: &Star,
    (scale, Pass { grid, floor }): (f64, Pass),
    image: &Rgb8,
    bounces: u32,
    course: Course,
) -> Result<Score> {
    let mut spec = FrameSpec::tick(image.width, image.height, bounces, true);
    spec.course = course;
    let frame = Frame::new(scene, &spec)?;
    let star_frame = StarFrame {
        scene,
        camera: *frame.camera(),
        course,
        trace: frame.trace(),
        star,
    };
    // Kept in memory and on disk: the next image of the scene costs the statistic only.
    let key = ReferenceKey::of_frame(&star_frame, floor, SEED).on(grid);
    let expected = ReferenceCache::shared().get_or_compute(key, &star_frame, floor, SEED)?;
    let (columns, rows) = (grid.count(image.width), grid.count(image.height));
    let pixels = (columns * rows) as usize;
    if expected.beauty.len() != pixels || expected.variance.len() != pixels {
        return Err(Error::Usage(
            "the expectation's size is not the image's".into(),
        ));
    }
    // Every pixel's quadrature points (and the points one standard error either side), tone
    // mapped and quantised by the course's own bytes in one call.
    let per_pixel = NODES.len() + 2;
    let mut points = Vec::with_capacity(pixels * per_pixel);
    for i in 0..pixels {
        let mean = expected.beauty[i] * scale;
        let sd = (expected.variance[i] * scale * scale)
            .max(DVec3::ZERO)
            .to_array()
            .map(f64::sqrt);
        let se = expected.standard_error[i] * scale;
        for (x, _) in NODES {
            points.push(mean + DVec3::from(sd.map(|s| s * x)));
        }
        points.push(mean - se);
        points.push(mean + se);
    }
    let bytes = bytes_with(course.tonemap(), &points);
    let (z2, random): (Vec<f64>, Vec<u8>) = (0..pixels)
        .map(|i| {
            let at = |k: usize, c: usize| f64::from(bytes[3 * (i * per_pixel + k) + c]);
            let (x, y) = (grid.at(i as u32 % columns), grid.at(i as u32 / columns));
            let student = 3 * (y * image.width + x) as usize;
            (0..3)
                .map(|c| {
                    let mean: f64 = NODES
                        .iter()
                        .enumerate()
                        .map(|(k, (_, w))| w * at(k, c))
                        .sum();
                    let square: f64 = NODES
                        .iter()
                        .enumerate()
                        .map(|(k, (_, w))| w * at(k, c).powi(2))
                        .sum();
                    let spread = (square - mean * mean).max(0.0);
                    let estimate = ((at(NODES.len() + 1, c) - at(NODES.len(), c)) / 2.0).powi(2);
                    let y = f64::from(image.bytes[student + c]);
                    match spread >= RANDOM {
                        true => ((y - mean).powi(2) / (spread + estimate + BYTE_FLOOR), 1),
                        false => (0.0, 0),
                    }
                })
                .fold((0.0, 0), |(z, n), (dz, dn)| (z + dz, n + dn))
        })
        .unzip();
    Ok(Score {
        z2,
        random,
        grid,
        columns,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_quadrature_is_a_standard_normal() {
        let total: f64 = NODES.iter().map(|(_, w)| w).sum();
        let variance: f64 = NODES.iter().map(|(x, w)| w * x * x).sum();
        let fourth: f64 = NODES.iter().map(|(x, w)| w * x.powi(4)).sum();
        assert!((total - 1.0).abs() < 1e-9, "{total}");
        assert!((variance - 1.0).abs() < 1e-9, "{variance}");
        assert!((fourth - 3.0).abs() < 1e-9, "{fourth}");
    }

    #[test]
    fn the_worst_tile_is_where_the_score_is() {
        let (w, h) = (40, 20);
        let mut s = vec![0.0; (w * h) as usize];
        s[(18 * w + 35) as usize] = 30.0;
        let every = Score {
            z2: s,
            random: vec![3; (w * h) as usize],
            grid: Grid::EVERY,
            columns: w,
        };
        assert_eq!(every.worst_tile(w, h), (32, 16, 8, 4));
        // On a grid of stride 3 (pixels 1, 4, 7, ...), the pixel (37, 19) is grid (12, 6).
        let grid = Grid { stride: 3 };
        let (columns, rows) = (grid.count(w), grid.count(h));
        let mut z2 = vec![0.0; (columns * rows) as usize];
        z2[(6 * columns + 12) as usize] = 30.0;
        let sparse = Score {
            z2,
            random: vec![3; (columns * rows) as usize],
            grid,
            columns,
        };
        assert_eq!(sparse.worst_tile(w, h), (32, 16, 8, 4));
    }
}
