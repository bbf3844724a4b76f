//! The attribute names the scene format has (docs/scene-format.md): a closed set, so an enum.
//! Each attribute's name is matched once, where it is read; everything after that (allowed
//! sets, duplicates, lookups) compares enum values rather than strings, which a million-sphere
//! scene does some eighty times per sphere.

/// One attribute name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Key {
    X,
    Y,
    Z,
    Radius,
    Colour,
    Nx,
    Ny,
    Nz,
    KD,
    KS,
    N,
    Reflectivity,
    Intensity,
    Name,
}

impl Key {
    /// How many keys there are: the size of a table indexed by `Key as usize`.
    pub(super) const COUNT: usize = 14;

    /// The name as written in a scene file.
    pub(super) fn name(self) -> &'static str {
        match self {
            Key::X => "x",
            Key::Y => "y",
            Key::Z => "z",
            Key::Radius => "radius",
            Key::Colour => "colour",
            Key::Nx => "nx",
            Key::Ny => "ny",
            Key::Nz => "nz",
            Key::KD => "kD",
            Key::KS => "kS",
            Key::N => "n",
            Key::Reflectivity => "reflectivity",
            Key::Intensity => "intensity",
            Key::Name => "name",
        }
    }

    /// The key written `name`, if the format has one (case matters, as in XML).
    pub(super) fn from_name(name: &str) -> Option<Key> {
        Some(match name {
            "x" => Key::X,
            "y" => Key::Y,
            "z" => Key::Z,
            "radius" => Key::Radius,
            "colour" => Key::Colour,
            "nx" => Key::Nx,
            "ny" => Key::Ny,
            "nz" => Key::Nz,
            "kD" => Key::KD,
            "kS" => Key::KS,
            "n" => Key::N,
            "reflectivity" => Key::Reflectivity,
            "intensity" => Key::Intensity,
            "name" => Key::Name,
            _ => return None,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALL: [Key; Key::COUNT] = [
        Key::X,
        Key::Y,
        Key::Z,
        Key::Radius,
        Key::Colour,
        Key::Nx,
        Key::Ny,
        Key::Nz,
        Key::KD,
        Key::KS,
        Key::N,
        Key::Reflectivity,
        Key::Intensity,
        Key::Name,
    ];

    #[test]
    fn names_and_keys_match_one_to_one() {
        for (i, key) in ALL.into_iter().enumerate() {
            assert_eq!(key as usize, i, "{key:?} indexes its own table slot");
            assert_eq!(Key::from_name(key.name()), Some(key));
        }
        for other in ["X", "kd", "color", "", "radius ", "nam"] {
            assert_eq!(Key::from_name(other), None, "{other}");
        }
    }
}
