//! The AOV layers of docs/aovs.md: which layers a render can write, what each one holds, and how
//! `--aovs` selects them. The film stores what this module declares; the EXR writer names the
//! channels the way it says.

use crate::sample::Sample;
use crate::suggest;

/// `Z` where the camera ray misses: "far", as Cycles writes it, so depth-based compositing puts
/// the sky behind everything (docs/aovs.md). The EXR header records it as `render/zMiss`.
pub const Z_MISS: f64 = 1e10;

/// What a layer measures. A closed set, so the mapping from a `Sample` is one `match`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// `R G B A`: the tick renderer's value, alpha 1.
    Beauty,
    Direct,
    /// Everything through at least one mirror.
    Reflected,
    /// Exactly k reflections, k >= 1.
    ReflectedBounce(u32),
    Ambient,
    Diffuse,
    Specular,
    Background,
    /// Light i's shadowed diffuse + specular.
    Light(usize),
    /// Light i's diffuse + specular with visibility forced to 1.
    Unshadowed(usize),
    /// 1 where the primary hit is in light i's shadow.
    Shadow(usize),
    /// Planar camera-space depth of the primary hit.
    Depth,
    Normal,
    Position,
    Albedo,
    /// 1-based index of the primary hit's object.
    ObjectId,
    /// Tick 1*: the variance of one course draw of the pixel (linear radiance squared).
    Variance,
    /// Tick 1*: the side in pixels of the square depth of field spreads the pinhole hit over.
    CircleOfConfusion,
    /// Tick 1*: the bump map's height at the pinhole hit.
    Height,
}

/// How a layer may be stored and shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Linear radiance: may be stored as half, tone-mapped for display.
    Colour,
    /// A fraction in [0, 1].
    Mask,
    /// Geometry or ids: always float, never tone-mapped.
    Data,
}

/// How samples within a pixel combine.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reduction {
    /// The mean over the pixel's samples.
    Mean,
    /// The value of the sample nearest the pixel centre: depth, positions and ids must never
    /// be blended across an edge into values that exist nowhere in the scene.
    NearestCentre,
}

/// One named layer of the AOV file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Layer {
    /// The layer name (`direct`, `light_key`, ...); empty for the beauty's bare channels and
    /// `Z` for the bare depth channel.
    pub name: String,
    pub quantity: Quantity,
}

impl Quantity {
    /// Channel suffixes, in storage order.
    pub fn channels(self) -> &'static [&'static str] {
        match self {
            Quantity::Beauty => &["R", "G", "B", "A"],
            Quantity::Shadow(_) | Quantity::CircleOfConfusion | Quantity::Height => &["Y"],
            Quantity::Depth => &["Z"],
            Quantity::Normal | Quantity::Position => &["X", "Y", "Z"],
            Quantity::ObjectId => &["X"],
            _ => &["R", "G", "B"],
        }
    }

    pub fn kind(self) -> Kind {
        match self {
            Quantity::Shadow(_) => Kind::Mask,
            Quantity::Depth
            | Quantity::Normal
            | Quantity::Position
            | Quantity::Albedo
            | Quantity::ObjectId
            | Quantity::Variance
            | Quantity::CircleOfConfusion
            | Quantity::Height => Kind::Data,
            _ => Kind::Colour,
        }
    }

    pub fn reduction(self) -> Reduction {
        match self {
            Quantity::Depth | Quantity::Position | Quantity::ObjectId => Reduction::NearestCentre,
            _ => Reduction::Mean,
        }
    }

    /// This quantity's values for one sample, one per channel, into `out`.
    pub fn values(self, s: &Sample, out: &mut [f64]) {
        let rgb = |out: &mut [f64], v: glam::DVec3| out[..3].copy_from_slice(&v.to_array());
        let hit = s.primary.as_ref();
        match self {
            Quantity::Beauty => {
                rgb(out, s.beauty);
                out[3] = 1.0;
            }
            Quantity::Direct => rgb(out, s.direct),
            Quantity::Reflected => rgb(out, s.reflected()),
            Quantity::ReflectedBounce(k) => rgb(out, s.reflected_by_bounce[k as usize - 1]),
            Quantity::Ambient => rgb(out, s.ambient),
            Quantity::Diffuse => rgb(out, s.diffuse),
            Quantity::Specular => rgb(out, s.specular),
            Quantity::Background => rgb(out, s.background),
            Quantity::Light(i) => rgb(out, s.lights[i].shadowed),
            Quantity::Unshadowed(i) => rgb(out, s.lights[i].unshadowed),
            Quantity::Shadow(i) => out[0] = s.lights[i].shadowed_at_primary,
            Quantity::Depth => out[0] = hit.map_or(Z_MISS, |h| h.position.z),
            Quantity::Normal => rgb(out, hit.map_or(glam::DVec3::ZERO, |h| h.normal)),
            Quantity::Position => rgb(out, hit.map_or(glam::DVec3::ZERO, |h| h.position)),
            Quantity::Albedo => rgb(out, hit.map_or(glam::DVec3::ZERO, |h| h.albedo)),
            Quantity::ObjectId => out[0] = hit.map_or(0.0, |h| (h.object + 1) as f64),
            Quantity::Variance => rgb(out, s.star.variance),
            Quantity::CircleOfConfusion => out[0] = s.star.circle_of_confusion,
            Quantity::Height => out[0] = s.star.height,
        }
    }
}

impl Layer {
    fn new(name: impl Into<String>, quantity: Quantity) -> Self {
        Layer {
            name: name.into(),
            quantity,
        }
    }

    /// Full EXR channel names: bare for the beauty and depth, `layer.C` otherwise.
    pub fn channel_names(&self) -> Vec<String> {
        self.quantity
            .channels()
            .iter()
            .map(|c| match self.quantity {
                Quantity::Beauty | Quantity::Depth => (*c).to_string(),
                _ => format!("{}.{c}", self.name),
            })
            .collect()
    }

    /// The name a user selects this layer by (`beauty` for the bare RGBA).
    pub fn selection_name(&self) -> &str {
        match self.quantity {
            Quantity::Beauty => BEAUTY,
            _ => &self.name,
        }
    }
}

/// The layer a stored channel belongs to: `direct.R` -> `direct`; the beauty's bare `R G B A`
/// -> `beauty`; other bare names (`Z`) are their own layer. The inverse of
/// [`Layer::channel_names`], for files from whitted or anyone else.
pub fn layer_of_channel(channel: &str) -> &str {
    match channel.rsplit_once('.') {
        Some((layer, _)) => layer,
        None if Quantity::Beauty.channels().contains(&channel) => BEAUTY,
        None => channel,
    }
}

/// What a stored layer is, for showing it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// Linear radiance.
    Colour,
    /// A fraction in [0, 1] (`shadow_<name>`).
    Mask,
    /// Unit vectors (`N`).
    Normal,
    /// Integer object ids (`objectid`).
    ObjectId,
    /// Anything else measured: depth, positions, albedo.
    Data,
}

/// The three layers every light has, each named `<prefix><light name>`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PerLight {
    /// `light_<name>`: its shadowed diffuse + specular.
    Shadowed,
    /// `unshadowed_<name>`: the same with visibility 1.
    Unshadowed,
    /// `shadow_<name>`: the shadow mask at the primary hit.
    Mask,
}

impl PerLight {
    const ALL: [PerLight; 3] = [PerLight::Shadowed, PerLight::Unshadowed, PerLight::Mask];

    /// What every layer name of this kind starts with.
    pub fn prefix(self) -> &'static str {
        match self {
            PerLight::Shadowed => "light_",
            PerLight::Unshadowed => "unshadowed_",
            PerLight::Mask => "shadow_",
        }
    }

    /// The layer's name for the light called `light`.
    pub fn layer_name(self, light: &str) -> String {
        format!("{}{light}", self.prefix())
    }

    /// The quantity for light `index`.
    fn quantity(self, index: usize) -> Quantity {
        match self {
            PerLight::Shadowed => Quantity::Light(index),
            PerLight::Unshadowed => Quantity::Unshadowed(index),
            PerLight::Mask => Quantity::Shadow(index),
        }
    }
}

/// A layer name read back: a quantity of the whole image, or one of a light's layers with
/// the light's name (a file names its lights, it does not number them).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LayerName<'a> {
    Image(Quantity),
    Light(PerLight, &'a str),
}

/// The names of the quantities that are not per light; `ReflectedBounce` is `reflected_<k>`.
fn fixed_name(q: Quantity) -> Option<&'static str> {
    Some(match q {
        Quantity::Beauty => BEAUTY,
        Quantity::Direct => "direct",
        Quantity::Reflected => "reflected",
        Quantity::Ambient => "ambient",
        Quantity::Diffuse => "diffuse",
        Quantity::Specular => "specular",
        Quantity::Background => "background",
        Quantity::Depth => "Z",
        Quantity::Normal => "N",
        Quantity::Position => "P",
        Quantity::Albedo => "albedo",
        Quantity::ObjectId => "objectid",
        Quantity::Variance => "variance",
        Quantity::CircleOfConfusion => "coc",
        Quantity::Height => "height",
        Quantity::ReflectedBounce(_)
        | Quantity::Light(_)
        | Quantity::Unshadowed(_)
        | Quantity::Shadow(_) => return None,
    })
}

/// Every quantity that has a fixed name, for parsing.
const FIXED: [Quantity; 15] = [
    Quantity::Beauty,
    Quantity::Direct,
    Quantity::Reflected,
    Quantity::Ambient,
    Quantity::Diffuse,
    Quantity::Specular,
    Quantity::Background,
    Quantity::Depth,
    Quantity::Normal,
    Quantity::Position,
    Quantity::Albedo,
    Quantity::ObjectId,
    Quantity::Variance,
    Quantity::CircleOfConfusion,
    Quantity::Height,
];

impl Quantity {
    /// The one spelling of this quantity's layer name, for a scene whose lights are called
    /// `light_names` (the beauty is `beauty`, though its channels are stored bare).
    pub fn name(self, light_names: &[String]) -> String {
        let light = |i: usize| light_names.get(i).map_or("?", String::as_str);
        match self {
            Quantity::ReflectedBounce(k) => format!("reflected_{k}"),
            Quantity::Light(i) => PerLight::Shadowed.layer_name(light(i)),
            Quantity::Unshadowed(i) => PerLight::Unshadowed.layer_name(light(i)),
            Quantity::Shadow(i) => PerLight::Mask.layer_name(light(i)),
            fixed => fixed_name(fixed).unwrap_or_default().to_string(),
        }
    }

    /// What `role` a layer of this quantity plays, from its kind.
    pub fn role(self) -> Role {
        match (self.kind(), self) {
            (Kind::Colour, _) => Role::Colour,
            (Kind::Mask, _) => Role::Mask,
            (Kind::Data, Quantity::Normal) => Role::Normal,
            (Kind::Data, Quantity::ObjectId) => Role::ObjectId,
            (Kind::Data, _) => Role::Data,
        }
    }
}

/// A layer name as `Quantity::name` spells it, read back; `None` for a name whitted never
/// writes.
pub fn parse_layer_name(name: &str) -> Option<LayerName<'_>> {
    if let Some(q) = FIXED.into_iter().find(|&q| fixed_name(q) == Some(name)) {
        return Some(LayerName::Image(q));
    }
    if let Some(k) = name.strip_prefix("reflected_") {
        // Only as `name` writes it: `reflected_1`, not `reflected_01` or `reflected_+1`.
        let bounce = k
            .parse::<u32>()
            .ok()
            .filter(|b| *b >= 1 && b.to_string() == k)?;
        return Some(LayerName::Image(Quantity::ReflectedBounce(bounce)));
    }
    PerLight::ALL.into_iter().find_map(|per| {
        let light = name.strip_prefix(per.prefix())?;
        (!light.is_empty()).then_some(LayerName::Light(per, light))
    })
}

/// The light a `light_<name>` layer is of.
pub fn light_of_layer(name: &str) -> Option<&str> {
    match parse_layer_name(name)? {
        LayerName::Light(PerLight::Shadowed, light) => Some(light),
        _ => None,
    }
}

/// The group a layer is shown in (the viewer's thumbnails): `beauty`, `effects` (the beauty's
/// split into terms), `lights`, `bounces`, `masks` or `data`; `None` for a name whitted never
/// writes.
pub fn group_of_layer(name: &str) -> Option<&'static str> {
    Some(match parse_layer_name(name)? {
        LayerName::Image(Quantity::Beauty) => "beauty",
        LayerName::Image(Quantity::Reflected | Quantity::ReflectedBounce(_)) => "bounces",
        LayerName::Light(PerLight::Shadowed | PerLight::Unshadowed, _) => "lights",
        LayerName::Light(PerLight::Mask, _) => "masks",
        LayerName::Image(q) if q.role() == Role::Colour => "effects",
        LayerName::Image(_) => "data",
    })
}

/// The role of a layer named as whitted names them, or `None` for a name it never writes.
pub fn role_of_layer(name: &str) -> Option<Role> {
    Some(match parse_layer_name(name)? {
        LayerName::Image(q) => q.role(),
        LayerName::Light(per, _) => per.quantity(0).role(),
    })
}

/// The name the bare `R G B A` channels go by.
pub const BEAUTY: &str = "beauty";

/// Every layer a render of a scene with these lights and bounces can write, in file order:
/// beauty, the radiance split, per-light layers, shadow masks, then the data layers.
pub fn all_layers(light_names: &[String], bounces: u32) -> Vec<Layer> {
    let lights = |per: PerLight| (0..light_names.len()).map(move |i| per.quantity(i));
    let quantities = [Quantity::Beauty, Quantity::Direct, Quantity::Reflected]
        .into_iter()
        .chain((1..=bounces).map(Quantity::ReflectedBounce))
        .chain([Quantity::Ambient])
        .chain(lights(PerLight::Shadowed))
        .chain(lights(PerLight::Unshadowed))
        .chain([Quantity::Diffuse, Quantity::Specular, Quantity::Background])
        .chain(lights(PerLight::Mask))
        .chain([
            Quantity::Depth,
            Quantity::Normal,
            Quantity::Position,
            Quantity::Albedo,
            Quantity::ObjectId,
        ]);
    quantities
        .map(|q| match q {
            // Stored as the bare R G B A, so its layer has no name.
            Quantity::Beauty => Layer::new("", q),
            q => Layer::new(q.name(light_names), q),
        })
        .collect()
}

/// The layers a Tick 1* render adds after `all_layers`: the variance of one course draw
/// (when the estimate is converged and random), the circle of confusion (with depth of
/// field) and the bump height (with bumped spheres). Its shadow masks are then fractions.
pub fn star_layers(variance: bool, dof: bool, bumps: bool) -> Vec<Layer> {
    [
        (variance, Quantity::Variance),
        (dof, Quantity::CircleOfConfusion),
        (bumps, Quantity::Height),
    ]
    .into_iter()
    .filter(|(wanted, _)| *wanted)
    .map(|(_, q)| Layer::new(q.name(&[]), q))
    .collect()
}

/// The canonical `--aovs` of `selected` (as `select` returns them from `available`): `all`
/// for every layer, `beauty` for the beauty alone, else the other layers' names in file
/// order, whatever order and spelling they were asked in.
pub fn selection_spec(selected: &[Layer], available: &[Layer]) -> String {
    if selected == available {
        return "all".into();
    }
    let names: Vec<&str> = selected
        .iter()
        .filter(|l| l.quantity != Quantity::Beauty)
        .map(Layer::selection_name)
        .collect();
    if names.is_empty() {
        BEAUTY.into()
    } else {
        names.join(",")
    }
}

/// The layers `--aovs` asks for: `all`, `beauty`, or a comma-separated list of layer names
/// (the beauty is always written). Keeps file order; an unknown name is an error that lists
/// the valid names for this scene.
pub fn select(spec: &str, available: &[Layer]) -> Result<Vec<Layer>, String> {
    match spec.trim() {
        "all" => return Ok(available.to_vec()),
        "beauty" => return Ok(available[..1].to_vec()),
        _ => {}
    }
    let names: Vec<&str> = available.iter().map(Layer::selection_name).collect();
    let mut wanted = vec!["beauty"];
    for name in spec.split(',').map(str::trim).filter(|n| !n.is_empty()) {
        if !names.contains(&name) {
            let hint = suggest::nearest(name, &names)
                .map_or(String::new(), |s| format!("did you mean `{s}`? "));
            return Err(format!(
                "unknown AOV layer `{name}` ({hint}valid layers for this scene: all, {})",
                names.join(", ")
            ));
        }
        wanted.push(name);
    }
    Ok(available
        .iter()
        .filter(|l| wanted.contains(&l.selection_name()))
        .cloned()
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layers_fall_into_the_viewer_s_groups_by_what_they_are() {
        let groups = [
            ("beauty", Some("beauty")),
            ("direct", Some("effects")),
            ("specular", Some("effects")),
            ("reflected", Some("bounces")),
            ("reflected_2", Some("bounces")),
            ("light_key", Some("lights")),
            ("unshadowed_0", Some("lights")),
            ("shadow_key", Some("masks")),
            ("Z", Some("data")),
            ("objectid", Some("data")),
            ("light_", None),
            ("reflectedness", None),
        ];
        for (name, group) in groups {
            assert_eq!(group_of_layer(name), group, "{name}");
        }
    }

    fn names(layers: &[Layer]) -> Vec<String> {
        layers.iter().flat_map(Layer::channel_names).collect()
    }

    #[test]
    fn every_layer_name_is_built_from_its_quantity_and_parses_back() {
        let lights: Vec<String> = vec!["key".into(), "0".into()];
        for layer in all_layers(&lights, 3) {
            let name = layer.quantity.name(&lights);
            if layer.quantity != Quantity::Beauty {
                assert_eq!(name, layer.name);
            }
            let parsed = parse_layer_name(&name).unwrap_or_else(|| panic!("{name}"));
            let back = match parsed {
                LayerName::Image(q) => q,
                LayerName::Light(per, light) => {
                    let index = lights.iter().position(|l| l == light).expect("light");
                    per.quantity(index)
                }
            };
            assert_eq!(back, layer.quantity, "{name}");
            assert_eq!(role_of_layer(&name), Some(layer.quantity.role()), "{name}");
        }
        for name in ["reflected_0", "reflected_01", "light_", "sky", "Zed"] {
            assert_eq!(parse_layer_name(name), None, "{name}");
        }
        assert_eq!(light_of_layer("light_key"), Some("key"));
        assert_eq!(light_of_layer("unshadowed_key"), None);
    }

    #[test]
    fn a_selection_has_one_canonical_spelling() {
        let available = all_layers(&["key".into()], 2);
        let spec = |s: &str| selection_spec(&select(s, &available).expect("select"), &available);
        assert_eq!(spec("Z,direct"), "direct,Z");
        assert_eq!(spec(" direct , Z,,"), "direct,Z");
        assert_eq!(spec("all"), "all");
        assert_eq!(spec("beauty"), "beauty");
        assert_eq!(spec("beauty,"), "beauty");
    }

    #[test]
    fn catalogue_names_follow_the_contract() {
        let layers = all_layers(&["key".into(), "0".into()], 2);
        let channels = names(&layers);
        for want in [
            "R",
            "G",
            "B",
            "A",
            "Z",
            "direct.R",
            "reflected.B",
            "reflected_1.G",
            "reflected_2.R",
            "light_key.R",
            "light_0.B",
            "unshadowed_key.G",
            "shadow_key.Y",
            "shadow_0.Y",
            "N.X",
            "P.Z",
            "albedo.G",
            "objectid.X",
            "ambient.R",
            "diffuse.R",
            "specular.R",
            "background.R",
        ] {
            assert!(channels.iter().any(|c| c == want), "missing {want}");
        }
        assert!(!channels.iter().any(|c| c == "reflected_3.R"));
        let mut unique = channels.clone();
        unique.sort();
        unique.dedup();
        assert_eq!(unique.len(), channels.len());
        assert!(channels
            .iter()
            .all(|c| c.matches('.').count() <= 1 && c.len() <= 31));
    }

    #[test]
    fn selection_keeps_beauty_and_order_and_rejects_unknown_names() {
        let all = all_layers(&["key".into()], 1);
        assert_eq!(select("all", &all).expect("all"), all);
        assert_eq!(
            names(&select("beauty", &all).expect("beauty")),
            ["R", "G", "B", "A"]
        );
        let some = select("shadow_key, direct,Z", &all).expect("list");
        let chosen: Vec<&str> = some.iter().map(Layer::selection_name).collect();
        assert_eq!(chosen, ["beauty", "direct", "shadow_key", "Z"]);
        let err = select("direct,shadow_kye", &all).unwrap_err();
        assert!(err.contains("unknown AOV layer `shadow_kye`"), "{err}");
        assert!(err.contains("did you mean `shadow_key`?"), "{err}");
        assert!(err.contains("light_key"), "{err}");
    }
}
