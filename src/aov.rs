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
            Quantity::Shadow(_) => &["Y"],
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
            | Quantity::ObjectId => Kind::Data,
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
            Quantity::Shadow(i) => out[0] = f64::from(u8::from(s.lights[i].occluded_at_primary)),
            Quantity::Depth => out[0] = hit.map_or(Z_MISS, |h| h.position.z),
            Quantity::Normal => rgb(out, hit.map_or(glam::DVec3::ZERO, |h| h.normal)),
            Quantity::Position => rgb(out, hit.map_or(glam::DVec3::ZERO, |h| h.position)),
            Quantity::Albedo => rgb(out, hit.map_or(glam::DVec3::ZERO, |h| h.albedo)),
            Quantity::ObjectId => out[0] = hit.map_or(0.0, |h| (h.object + 1) as f64),
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

/// What a stored layer is, for showing it: whitted's layer names, recognised here where they
/// are made.
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

/// The role of a layer named as whitted names them, or `None` for a name it never writes.
pub fn role_of_layer(name: &str) -> Option<Role> {
    let is_bounce = |k: &str| !k.is_empty() && k.bytes().all(|b| b.is_ascii_digit());
    Some(match name {
        BEAUTY | "direct" | "reflected" | "ambient" | "diffuse" | "specular" | "background" => {
            Role::Colour
        }
        "N" => Role::Normal,
        "objectid" => Role::ObjectId,
        "Z" | "P" | "albedo" => Role::Data,
        _ if name.strip_prefix("reflected_").is_some_and(is_bounce) => Role::Colour,
        _ if name.starts_with("light_") || name.starts_with("unshadowed_") => Role::Colour,
        _ if name.starts_with("shadow_") => Role::Mask,
        _ => return None,
    })
}

/// The name the bare `R G B A` channels go by.
pub const BEAUTY: &str = "beauty";

/// Every layer a render of a scene with these lights and bounces can write, in file order:
/// beauty, the radiance split, per-light layers, shadow masks, then the data layers.
pub fn all_layers(light_names: &[String], bounces: u32) -> Vec<Layer> {
    let mut layers = vec![
        Layer::new("", Quantity::Beauty),
        Layer::new("direct", Quantity::Direct),
        Layer::new("reflected", Quantity::Reflected),
    ];
    layers.extend(
        (1..=bounces).map(|k| Layer::new(format!("reflected_{k}"), Quantity::ReflectedBounce(k))),
    );
    layers.push(Layer::new("ambient", Quantity::Ambient));
    for (i, name) in light_names.iter().enumerate() {
        layers.push(Layer::new(format!("light_{name}"), Quantity::Light(i)));
    }
    for (i, name) in light_names.iter().enumerate() {
        layers.push(Layer::new(
            format!("unshadowed_{name}"),
            Quantity::Unshadowed(i),
        ));
    }
    layers.extend([
        Layer::new("diffuse", Quantity::Diffuse),
        Layer::new("specular", Quantity::Specular),
        Layer::new("background", Quantity::Background),
    ]);
    for (i, name) in light_names.iter().enumerate() {
        layers.push(Layer::new(format!("shadow_{name}"), Quantity::Shadow(i)));
    }
    layers.extend([
        Layer::new("Z", Quantity::Depth),
        Layer::new("N", Quantity::Normal),
        Layer::new("P", Quantity::Position),
        Layer::new("albedo", Quantity::Albedo),
        Layer::new("objectid", Quantity::ObjectId),
    ]);
    layers
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

    fn names(layers: &[Layer]) -> Vec<String> {
        layers.iter().flat_map(Layer::channel_names).collect()
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
