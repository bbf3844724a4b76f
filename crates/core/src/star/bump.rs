//! Tick 1* option 1: the handout's bump mapping (docs/tick1star.md), one implementation whose
//! parametrisation and whose catalogued mistakes are parameters, so `check` renders a
//! student's error with the very code that renders the correct image.
//!
//! The method, for a point P on a sphere with centre C and radius r:
//! 1. n = (P - C) / r, and (u, v) in [0, 1]^2 from the chosen [`Parametrisation`].
//! 2. P_u, P_v: the partial derivatives of the parametrisation's point, normalised.
//! 3. B_u = h[row][col + 1] - h[row][col], B_v = h[row + 1][col] - h[row][col], where
//!    `col = floor(u * width)`, `row = floor(v * height)`, each clamped to the map, and the
//!    neighbour clamped at the right and bottom edges (so the gradient there is 0).
//! 4. n' = normalise(n + B_u (n x P_v) + B_v (n x P_u)).

use std::f64::consts::PI;

use glam::DVec3;

use crate::geometry::normalise;

/// The course's `BUMP_FACTOR`: a texel's height is 5 x blue / 255.
pub const BUMP_FACTOR: f32 = 5.0;

/// A bump map as the course's `BumpySphere` holds it: `float[row][col]`, row 0 the top of
/// the image. Also keeps the colour-as-height field (the whole packed `getRGB` colour, scaled
/// alike), which a student who does not take the blue byte out of it reads instead.
#[derive(Debug, Clone, PartialEq)]
pub struct BumpMap {
    width: usize,
    height: usize,
    /// `BUMP_FACTOR * (blue / 255f)`, in f32 as the course computes it, row by row.
    heights: Vec<f32>,
    /// `BUMP_FACTOR * (rgb / 255f)` with `rgb` the packed `0xRRGGBB` (the alpha byte of
    /// `getRGB` is a constant that no gradient sees): the `ColourAsHeight` mistake's field.
    packed: Vec<f32>,
}

impl BumpMap {
    /// A map from 8-bit RGB texels, row by row: the caller decodes the image (and checks its
    /// size against the image limits). `None` when the texel count does not match or the map
    /// is empty.
    pub fn from_rgb8(width: usize, height: usize, rgb: &[[u8; 3]]) -> Option<BumpMap> {
        if width == 0 || height == 0 || width.checked_mul(height)? != rgb.len() {
            return None;
        }
        let heights = rgb
            .iter()
            .map(|&[_, _, b]| BUMP_FACTOR * (f32::from(b) / 255.0))
            .collect();
        let packed = rgb
            .iter()
            .map(|&[r, g, b]| {
                let colour = (u32::from(r) << 16) | (u32::from(g) << 8) | u32::from(b);
                // Exact: a 24-bit integer fits f32's significand.
                BUMP_FACTOR * (colour as f32 / 255.0)
            })
            .collect();
        Some(BumpMap {
            width,
            height,
            heights,
            packed,
        })
    }

    pub fn width(&self) -> usize {
        self.width
    }

    pub fn height(&self) -> usize {
        self.height
    }

    /// The height of texel (row, col) from the field `source` names.
    fn at(&self, source: HeightSource, row: usize, col: usize) -> f64 {
        let field = match source {
            HeightSource::Blue => &self.heights,
            HeightSource::Packed => &self.packed,
        };
        f64::from(field[row * self.width + col])
    }

    /// The texel (row, col) that (u, v) falls in: `floor(u * width)`, `floor(v * height)`,
    /// clamped to the map (u = 1 or a NaN lands on an edge texel, never outside).
    pub fn texel(&self, u: f64, v: f64) -> (usize, usize) {
        (clamp_index(v, self.height), clamp_index(u, self.width))
    }
}

fn clamp_index(t: f64, n: usize) -> usize {
    let i = (t * n as f64).floor();
    if i.is_nan() || i < 0.0 {
        0
    } else {
        (i as usize).min(n - 1)
    }
}

/// Which field a height is read from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum HeightSource {
    Blue,
    Packed,
}

/// The axis a parametrisation's poles lie on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pole {
    Y,
    Z,
}

/// A spherical-polar parametrisation of the unit sphere, as students write them:
/// `v = acos(n . pole) / pi` (0 at the +pole, which is the map's top row), and
/// `u = frac(shift + sense * atan2(b, a) / (2 pi))`, the azimuth measured in the plane of the
/// other two axes, from axis `a` towards axis `b`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Parametrisation {
    pub name: &'static str,
    pub pole: Pole,
    /// atan2's second argument is n's coordinate along `a`; true when a is the first of the
    /// other two axes in x, y, z order (x for pole y, x for pole z).
    pub a_first: bool,
    /// +1: u increases with the azimuth from a towards b; -1: mirrored.
    pub sense: f64,
    /// Where u = 0 lies, as a fraction of a turn added to the azimuth's: 0.5 is the usual
    /// `0.5 + atan2/(2 pi)`.
    pub shift: f64,
}

/// The named parametrisations `--bump-param` takes; the first is the default. They cover the
/// poles' axis (y, or z the physicists' convention), which pair atan2 reads, the direction of
/// increasing u and where u = 0 lies.
pub const PARAMETRISATIONS: [Parametrisation; 6] = [
    Parametrisation {
        name: "y-zx",
        pole: Pole::Y,
        a_first: true,
        sense: 1.0,
        shift: 0.5,
    },
    Parametrisation {
        name: "y-zx-mirrored",
        pole: Pole::Y,
        a_first: true,
        sense: -1.0,
        shift: 0.5,
    },
    Parametrisation {
        name: "y-xz",
        pole: Pole::Y,
        a_first: false,
        sense: 1.0,
        shift: 0.5,
    },
    Parametrisation {
        name: "y-zx-from-x",
        pole: Pole::Y,
        a_first: true,
        sense: 1.0,
        shift: 0.0,
    },
    Parametrisation {
        name: "z-yx",
        pole: Pole::Z,
        a_first: true,
        sense: 1.0,
        shift: 0.5,
    },
    Parametrisation {
        name: "z-yx-from-x",
        pole: Pole::Z,
        a_first: true,
        sense: 1.0,
        shift: 0.0,
    },
];

/// What each named parametrisation computes, for `--help` and error messages.
pub fn parametrisation_help() -> String {
    PARAMETRISATIONS
        .iter()
        .map(|p| format!("{} ({})", p.name, p.formula()))
        .collect::<Vec<_>>()
        .join("; ")
}

impl Default for Parametrisation {
    fn default() -> Self {
        PARAMETRISATIONS[0]
    }
}

impl Parametrisation {
    /// The parametrisation called `name`, if any.
    pub fn named(name: &str) -> Option<Parametrisation> {
        PARAMETRISATIONS.iter().copied().find(|p| p.name == name)
    }

    /// The formula in the course's words.
    pub fn formula(&self) -> String {
        let (p, a, b) = self.axis_names();
        let sign = if self.sense > 0.0 { "+" } else { "-" };
        format!(
            "u = {} {sign} atan2(n.{b}, n.{a})/2pi, v = acos(n.{p})/pi",
            self.shift
        )
    }

    fn axis_names(&self) -> (char, char, char) {
        match (self.pole, self.a_first) {
            (Pole::Y, true) => ('y', 'x', 'z'),
            (Pole::Y, false) => ('y', 'z', 'x'),
            (Pole::Z, true) => ('z', 'x', 'y'),
            (Pole::Z, false) => ('z', 'y', 'x'),
        }
    }

    /// The unit vectors of the pole, a and b.
    fn axes(&self) -> (DVec3, DVec3, DVec3) {
        let unit = |c: char| match c {
            'x' => DVec3::X,
            'y' => DVec3::Y,
            _ => DVec3::Z,
        };
        let (p, a, b) = self.axis_names();
        (unit(p), unit(a), unit(b))
    }

    /// (u, v) of the unit normal `n`, and the unnormalised partial derivatives of the point
    /// `C + r n(u, v)` with respect to u and v.
    pub fn chart(&self, n: DVec3, radius: f64) -> Chart {
        let (pole, a, b) = self.axes();
        let azimuth = n.dot(b).atan2(n.dot(a));
        let u = (self.shift + self.sense * azimuth / (2.0 * PI)).rem_euclid(1.0);
        let theta = n.dot(pole).clamp(-1.0, 1.0).acos();
        let v = theta / PI;
        let (sin_t, cos_t) = theta.sin_cos();
        let (sin_p, cos_p) = azimuth.sin_cos();
        // dphi/du = 2 pi sense; dtheta/dv = pi.
        let p_u = (b * cos_p - a * sin_p) * (radius * sin_t * 2.0 * PI * self.sense);
        let p_v = (a * (cos_t * cos_p) + b * (cos_t * sin_p) - pole * sin_t) * (radius * PI);
        Chart { u, v, p_u, p_v }
    }
}

/// Where a point lies in a parametrisation, and the point's partial derivatives there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Chart {
    pub u: f64,
    pub v: f64,
    pub p_u: DVec3,
    pub p_v: DVec3,
}

/// The mistakes of docs/tick1star.md that hold in every parametrisation, as changes to the
/// one method.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BumpMistake {
    /// The relief inverted: the gradient's sign flipped (H's sunk, L's raised).
    Inverted,
    /// B_u paired with n x P_u and B_v with n x P_v.
    SwappedGradients,
    /// The tangents are the raw partial derivatives, not normalised.
    UnnormalisedTangents,
    /// The perturbed normal is not normalised.
    UnnormalisedResult,
    /// The gradient taken towards the texel to the left and above: h[left] - h[current].
    WrongTexel,
    /// The height read from the whole colour (`getRGB` not masked to its blue byte).
    ColourAsHeight,
    /// "A normal left in object space of another sphere": n taken as P normalised, the
    /// centre not subtracted, so n (and the (u, v) and tangents read from it) is the normal
    /// of the sphere about the origin through P, not of this one.
    NoCentre,
}

impl BumpMistake {
    pub const ALL: [BumpMistake; 7] = [
        BumpMistake::Inverted,
        BumpMistake::SwappedGradients,
        BumpMistake::UnnormalisedTangents,
        BumpMistake::UnnormalisedResult,
        BumpMistake::WrongTexel,
        BumpMistake::ColourAsHeight,
        BumpMistake::NoCentre,
    ];

    /// The name `check` reports.
    pub fn name(self) -> &'static str {
        match self {
            BumpMistake::Inverted => "bump-inverted",
            BumpMistake::SwappedGradients => "bump-swapped-gradients",
            BumpMistake::UnnormalisedTangents => "bump-unnormalised-tangents",
            BumpMistake::UnnormalisedResult => "bump-unnormalised-normal",
            BumpMistake::WrongTexel => "bump-wrong-texel",
            BumpMistake::ColourAsHeight => "bump-colour-as-height",
            BumpMistake::NoCentre => "bump-no-centre",
        }
    }

    /// What the student did, in a sentence.
    pub fn explanation(self) -> &'static str {
        match self {
            BumpMistake::Inverted => {
                "the relief is inverted (raised parts sunk): the sign of B_u, B_v or of n x P is flipped"
            }
            BumpMistake::SwappedGradients => {
                "B_u and B_v are swapped against the tangents: use n + B_u (n x P_v) + B_v (n x P_u)"
            }
            BumpMistake::UnnormalisedTangents => {
                "the tangents P_u, P_v are the raw partial derivatives: normalise them"
            }
            BumpMistake::UnnormalisedResult => "the perturbed normal n' is not normalised",
            BumpMistake::WrongTexel => {
                "the gradient is taken towards the texel left of / above the current one: use the texel to the right / below"
            }
            BumpMistake::ColourAsHeight => {
                "the height is the whole getRGB colour, not its blue byte (getRGB & 0xFF) x 5 / 255"
            }
            BumpMistake::NoCentre => {
                "n is the position normalised, the normal of a sphere at the origin: subtract \
                 the sphere's centre first (position.subtract(getPosition()).normalised(), or \
                 super.getNormalAt(position))"
            }
        }
    }
}

/// How normals are perturbed: the parametrisation, and a mistake if rendering one.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BumpMethod {
    pub parametrisation: Parametrisation,
    pub mistake: Option<BumpMistake>,
}

/// The perturbed normal at `point` with smooth unit normal `n` on a sphere of `radius`, and
/// the height of the texel it reads (the `height` layer).
pub fn perturb(
    method: &BumpMethod,
    map: &BumpMap,
    point: DVec3,
    n: DVec3,
    radius: f64,
) -> (DVec3, f64) {
    let mistake = method.mistake;
    let n = if mistake == Some(BumpMistake::NoCentre) {
        normalise(point)
    } else {
        n
    };
    let chart = method.parametrisation.chart(n, radius);
    let (p_u, p_v) = if mistake == Some(BumpMistake::UnnormalisedTangents) {
        (chart.p_u, chart.p_v)
    } else {
        (safe_normalise(chart.p_u), safe_normalise(chart.p_v))
    };
    let source = if mistake == Some(BumpMistake::ColourAsHeight) {
        HeightSource::Packed
    } else {
        HeightSource::Blue
    };
    let (row, col) = map.texel(chart.u, chart.v);
    let here = map.at(source, row, col);
    let (right, below) = if mistake == Some(BumpMistake::WrongTexel) {
        (col.saturating_sub(1), row.saturating_sub(1))
    } else {
        ((col + 1).min(map.width - 1), (row + 1).min(map.height - 1))
    };
    let mut b_u = map.at(source, row, right) - here;
    let mut b_v = map.at(source, below, col) - here;
    if mistake == Some(BumpMistake::Inverted) {
        (b_u, b_v) = (-b_u, -b_v);
    }
    if mistake == Some(BumpMistake::SwappedGradients) {
        (b_u, b_v) = (b_v, b_u);
    }
    let bumped = n + n.cross(p_v) * b_u + n.cross(p_u) * b_v;
    let normal = if mistake == Some(BumpMistake::UnnormalisedResult) {
        bumped
    } else {
        normalise(bumped)
    };
    (normal, here)
}

/// A tangent normalised, or zero at a pole where it vanishes (the method then adds nothing
/// along it, where the course's division would give NaN: whitted keeps the pixel finite).
fn safe_normalise(t: DVec3) -> DVec3 {
    let length = t.length();
    if length > 0.0 {
        t / length
    } else {
        DVec3::ZERO
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn map(width: usize, height: usize, blue: impl Fn(usize, usize) -> u8) -> BumpMap {
        let rgb: Vec<[u8; 3]> = (0..height)
            .flat_map(|r| (0..width).map(move |c| (r, c)))
            .map(|(r, c)| [((r * 11 + c * 5) % 256) as u8, 9, blue(r, c)])
            .collect();
        BumpMap::from_rgb8(width, height, &rgb).expect("map")
    }

    #[test]
    fn heights_are_five_times_blue_over_255_in_f32() {
        let m = map(2, 1, |_, c| [51, 255][c]);
        assert_eq!(
            m.at(HeightSource::Blue, 0, 0),
            f64::from(5.0f32 * (51.0f32 / 255.0))
        );
        assert_eq!(m.at(HeightSource::Blue, 0, 1), 5.0);
        assert!(BumpMap::from_rgb8(2, 2, &[[0; 3]; 3]).is_none());
    }

    #[test]
    fn texels_floor_and_clamp() {
        let m = map(4, 2, |_, _| 0);
        assert_eq!(m.texel(0.0, 0.0), (0, 0));
        assert_eq!(m.texel(0.2499, 0.5), (1, 0));
        assert_eq!(m.texel(0.25, 0.49), (0, 1));
        assert_eq!(m.texel(1.0, 1.0), (1, 3));
        assert_eq!(m.texel(-0.1, f64::NAN), (0, 0));
    }

    #[test]
    fn charts_match_finite_differences_of_the_point() {
        for p in PARAMETRISATIONS {
            let n = normalise(DVec3::new(0.3, -0.5, -0.8));
            let chart = p.chart(n, 0.7);
            // Invert the chart numerically by stepping u and v and re-reading them.
            let point = |u: f64, v: f64| {
                let (pole, a, b) = p.axes();
                let phi = (u - p.shift) * 2.0 * PI / p.sense;
                let theta = v * PI;
                (a * (theta.sin() * phi.cos()) + b * (theta.sin() * phi.sin()) + pole * theta.cos())
                    * 0.7
            };
            let back = p.chart(point(chart.u, chart.v) / 0.7, 0.7);
            assert!((back.u - chart.u).abs() < 1e-12, "{}", p.name);
            assert!(
                (point(chart.u, chart.v) / 0.7 - n).length() < 1e-12,
                "{}",
                p.name
            );
            let h = 1e-6;
            let du = (point(chart.u + h, chart.v) - point(chart.u - h, chart.v)) / (2.0 * h);
            let dv = (point(chart.u, chart.v + h) - point(chart.u, chart.v - h)) / (2.0 * h);
            assert!(
                (du - chart.p_u).length() < 1e-6,
                "{} {du} {}",
                p.name,
                chart.p_u
            );
            assert!(
                (dv - chart.p_v).length() < 1e-6,
                "{} {dv} {}",
                p.name,
                chart.p_v
            );
        }
    }

    #[test]
    fn a_flat_map_leaves_the_normal_and_a_ramp_tilts_it_by_the_formula() {
        let n = normalise(DVec3::new(0.2, 0.3, -0.9));
        let flat = map(8, 8, |_, _| 100);
        let method = BumpMethod::default();
        let (same, _) = perturb(&method, &flat, n, n, 1.0);
        assert!((same - n).length() < 1e-15);
        // Blue rises by 51 per column: B_u = 5 * 51/255 = 1 (in f32), B_v = 0.
        let ramp = map(5, 5, |_, c| (c * 51) as u8);
        let chart = method.parametrisation.chart(n, 1.0);
        let (row, col) = ramp.texel(chart.u, chart.v);
        assert!(col < 4, "not at the right edge");
        let b_u = ramp.at(HeightSource::Blue, row, col + 1) - ramp.at(HeightSource::Blue, row, col);
        assert!((b_u - 1.0).abs() < 1e-6);
        let expected = normalise(n + n.cross(chart.p_v.normalize()) * b_u);
        let (got, height) = perturb(&method, &ramp, n, n, 1.0);
        assert!((got - expected).length() < 1e-15, "{got} {expected}");
        assert_eq!(height, ramp.at(HeightSource::Blue, row, col));
    }

    #[test]
    fn without_the_centre_the_normal_is_the_origin_sphere_s() {
        let flat = map(8, 8, |_, _| 100);
        let centre = DVec3::new(0.0, 0.0, 3.5);
        let n = normalise(DVec3::new(0.3, 0.4, -0.8));
        let point = centre + n * 0.7;
        let method = BumpMethod {
            mistake: Some(BumpMistake::NoCentre),
            ..BumpMethod::default()
        };
        // A flat map adds nothing: what is left is P / |P|, far from the true normal.
        let (got, _) = perturb(&method, &flat, point, n, 0.7);
        assert!((got - point / point.length()).length() < 1e-15, "{got}");
        assert!(got.dot(n) < 0.0, "{got} faces away from the camera's side");
    }

    #[test]
    fn every_mistake_changes_the_normal_of_a_bumpy_map() {
        let bumpy = map(16, 16, |r, c| ((r * 37 + c * 91) % 256) as u8);
        let n = normalise(DVec3::new(-0.4, 0.2, -0.85));
        // On a sphere of radius 0.7 about (0, 0, 3.5), as bump.xml's.
        let point = DVec3::new(0.0, 0.0, 3.5) + n * 0.7;
        let (right, _) = perturb(&BumpMethod::default(), &bumpy, point, n, 0.7);
        for mistake in BumpMistake::ALL {
            let method = BumpMethod {
                mistake: Some(mistake),
                ..BumpMethod::default()
            };
            let (wrong, _) = perturb(&method, &bumpy, point, n, 0.7);
            assert!((wrong - right).length() > 1e-3, "{mistake:?}");
        }
    }
}
