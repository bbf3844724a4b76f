//! The Tick 1* options of `render` (docs/tick1star.md): soft shadows, depth of field, the
//! bump maps' parametrisation, and how the course's random process is sampled.

use clap::{Args, ValueEnum};

use whitted_core::star::bump::{parametrisation_help, Parametrisation};
use whitted_core::star::light::{COURSE_LIGHT_SIZE, COURSE_SHADOW_RAYS};
use whitted_core::star::{DepthOfField, LightSampling, NoiseFloor, Sampling, SoftShadows};

/// How the course's random process is rendered.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum SamplingArg {
    /// One seeded draw with the course's counts (what a student's screenshot is a draw of)
    Course,
    /// The expectation, with Sobol samples to the noise floor (`--noise-floor`)
    Converged,
}

/// How points of the sphere light are drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum LightSamplingArg {
    /// The course's randomInsideUnitSphere: radius, polar angle and azimuth uniform
    Course,
    /// Uniform in the ball's volume
    Uniform,
    /// On the sphere's surface: the course's point normalised (radius always the light's)
    Surface,
}

#[derive(Debug, Clone, Args)]
pub struct StarArgs {
    /// Tick 1* soft shadows: N shadow rays per light towards a sphere light [course: 10]
    #[arg(long, value_name = "N", num_args = 0..=1, default_missing_value = "10",
          value_parser = parse_shadow_rays)]
    pub soft_shadows: Option<u32>,

    /// Radius of the sphere light of `--soft-shadows`
    #[arg(long, value_name = "R", default_value_t = COURSE_LIGHT_SIZE, value_parser = parse_light_size)]
    pub light_size: f64,

    /// How `--soft-shadows` draws points of the light
    #[arg(long, value_name = "HOW", value_enum, default_value_t = LightSamplingArg::Course)]
    pub light_sampling: LightSamplingArg,

    /// Tick 1* depth of field: focal plane z, aperture side, rays per pixel
    #[arg(long, value_name = "Z,SIDE,N", num_args = 0..=1,
          default_missing_value = "3.51805,0.2,50", value_parser = parse_dof)]
    pub dof: Option<DepthOfField>,

    /// `course`: one seeded draw of the course's process; `converged`: its expectation
    #[arg(long, value_name = "HOW", value_enum, default_value_t = SamplingArg::Course)]
    pub sampling: SamplingArg,

    /// Seed of the draw (`--sampling course`) or of the Sobol scrambling (`converged`)
    #[arg(long, value_name = "S", default_value_t = 0)]
    pub seed: u64,

    /// Standard error per channel (linear) at which `--sampling converged` stops
    #[arg(long, value_name = "E", default_value_t = NoiseFloor::default().standard_error,
          value_parser = parse_noise_floor)]
    pub noise_floor: f64,

    /// Parametrisation of `<bumpy-sphere>` maps (see docs/tick1star.md)
    #[arg(long, value_name = "NAME", default_value = "y-zx", value_parser = parse_bump_param,
          long_help = format!("Parametrisation of `<bumpy-sphere>` maps: {}", parametrisation_help()))]
    pub bump_param: Parametrisation,
}

impl StarArgs {
    /// Whether any Tick 1* effect is asked for (bump maps come from the scene).
    pub fn random(&self) -> bool {
        self.soft_shadows.is_some() || self.dof.is_some()
    }

    pub fn soft(&self) -> Option<SoftShadows> {
        self.soft_shadows.map(|rays| SoftShadows {
            rays,
            light_size: self.light_size,
            sampling: match self.light_sampling {
                LightSamplingArg::Course => LightSampling::Course,
                LightSamplingArg::Uniform => LightSampling::Uniform,
                LightSamplingArg::Surface => LightSampling::Surface,
            },
            ..SoftShadows::default()
        })
    }

    pub fn sampling(&self) -> Sampling {
        match self.sampling {
            SamplingArg::Course => Sampling::Course { seed: self.seed },
            SamplingArg::Converged => Sampling::Converged {
                floor: NoiseFloor {
                    standard_error: self.noise_floor,
                    ..NoiseFloor::default()
                },
                seed: self.seed,
            },
        }
    }
}

/// Most shadow rays per light: the course casts 10.
const MAX_SHADOW_RAYS: u32 = 4096;

fn parse_shadow_rays(s: &str) -> Result<u32, String> {
    match s.trim().parse::<u32>() {
        Ok(n) if (1..=MAX_SHADOW_RAYS).contains(&n) => Ok(n),
        _ => Err(format!(
            "expected 1 to {MAX_SHADOW_RAYS} shadow rays (the course casts {COURSE_SHADOW_RAYS}), got `{s}`"
        )),
    }
}

/// A finite number in `range`, or a message naming `what`.
fn number(s: &str, what: &str, range: std::ops::RangeInclusive<f64>) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && range.contains(&v) => Ok(v),
        _ => Err(format!(
            "expected {what} between {} and {}, got `{s}`",
            range.start(),
            range.end()
        )),
    }
}

fn parse_light_size(s: &str) -> Result<f64, String> {
    number(s, "a light radius", 0.0..=1e6)
}

fn parse_noise_floor(s: &str) -> Result<f64, String> {
    number(s, "a standard error", 1e-6..=1.0)
}

fn parse_dof(s: &str) -> Result<DepthOfField, String> {
    let parts: Vec<&str> = s.split(',').collect();
    let [z, side, rays] = parts[..] else {
        return Err(format!(
            "expected Z,SIDE,N (focal plane, aperture side, rays), got `{s}`"
        ));
    };
    Ok(DepthOfField {
        focal_z: number(z, "a focal plane z", 1e-6..=1e6)?,
        side: number(side, "an aperture side", 0.0..=1e6)?,
        rays: parse_shadow_rays(rays).map_err(|_| {
            format!("expected 1 to {MAX_SHADOW_RAYS} depth-of-field rays, got `{rays}`")
        })?,
        ..DepthOfField::default()
    })
}

fn parse_bump_param(s: &str) -> Result<Parametrisation, String> {
    Parametrisation::named(s.trim()).ok_or_else(|| {
        format!(
            "unknown parametrisation `{s}` (one of: {})",
            parametrisation_help()
        )
    })
}
