//! Relighting from light layers, as compositors do with light groups: because every light's
//! contribution is stored linearly and the layers add up to the beauty (docs/aovs.md,
//! invariant 3), `ambient * a + sum_i g_i * light_i + background * b` is the image the scene
//! would give with light i scaled by `g_i` (per channel), without re-rendering. With every
//! gain 1 it is the beauty, to float rounding.

use glam::DVec3;

use crate::input::Image;
use whitted_core::aov::{self, PerLight};

/// What to change. Lights not named keep gain 1.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RelightSpec {
    /// Light name (the layer suffix: `0` for `light_0`, `key` for `light_key`) and its gain.
    pub lights: Vec<(String, DVec3)>,
    /// Lights shown without their shadows (`unshadowed_<name>` instead of `light_<name>`).
    pub no_shadow: Vec<String>,
    pub ambient: DVec3,
    pub background: DVec3,
}

/// Bytes `relight` holds at its peak for an image of `pixels` pixels: the sum and one layer
/// being added, as f64 RGB.
pub fn working_bytes(pixels: usize) -> u64 {
    (pixels as u64).saturating_mul(2 * std::mem::size_of::<DVec3>() as u64)
}

/// The relit image, row-major, or why it cannot be made from `image`'s layers. Every light
/// layer of the file counts: one that is not a full colour layer is an error, not a term
/// left out of the sum.
pub fn relight(image: &Image, spec: &RelightSpec) -> Result<Vec<DVec3>, String> {
    let layers = image.layers();
    // A layer named like a light's whose light cannot be read (`light_`) is part of the
    // beauty too: leaving it out of the sum would change the image without a word.
    let prefix = PerLight::Shadowed.prefix();
    if let Some(nameless) = layers
        .iter()
        .find(|l| l.name.starts_with(prefix) && aov::light_of_layer(&l.name).is_none())
    {
        return Err(format!(
            "layer `{}` is a light's layer without a light name: it cannot be relit, and \
             leaving it out would change the beauty",
            nameless.name
        ));
    }
    let lights: Vec<String> = layers
        .into_iter()
        .filter_map(|l| aov::light_of_layer(&l.name).map(str::to_string))
        .collect();
    for name in spec.lights.iter().map(|(n, _)| n).chain(&spec.no_shadow) {
        if !lights.contains(name) {
            return Err(format!(
                "no light `{name}` in the file (its lights: {})",
                if lights.is_empty() {
                    "none".to_string()
                } else {
                    lights.join(", ")
                }
            ));
        }
    }
    // ambient + lights in file order + background: the order of invariant 3.
    let mut terms = vec![("ambient".to_string(), spec.ambient)];
    for name in &lights {
        let gain = spec
            .lights
            .iter()
            .rev()
            .find(|(n, _)| n == name)
            .map_or(DVec3::ONE, |(_, g)| *g);
        let layer = if spec.no_shadow.contains(name) {
            PerLight::Unshadowed.layer_name(name)
        } else {
            PerLight::Shadowed.layer_name(name)
        };
        terms.push((layer, gain));
    }
    terms.push(("background".to_string(), spec.background));
    let mut out = vec![DVec3::ZERO; image.width * image.height];
    for (layer, gain) in &terms {
        // One layer at a time: the sum and one layer are all that is held.
        let values = image.colour_layer(layer)?;
        for (o, v) in out.iter_mut().zip(&values) {
            *o += *v * *gain;
        }
    }
    Ok(out)
}
