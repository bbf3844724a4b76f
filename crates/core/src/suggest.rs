//! "Did you mean ...?" for misspelt names (elements, attributes, layers).

/// The candidate closest to `given` by edit distance, ignoring case, if it is close enough to
/// be a plausible misspelling (at most a third of the word, and at least one edit, away).
pub fn nearest<'a>(given: &str, candidates: &[&'a str]) -> Option<&'a str> {
    let given = given.to_lowercase();
    let limit = (given.chars().count() / 3).max(1);
    candidates
        .iter()
        .map(|&c| (strsim::levenshtein(&given, &c.to_lowercase()), c))
        .filter(|&(d, _)| d <= limit)
        .min_by_key(|&(d, _)| d)
        .map(|(_, c)| c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_common_misspellings() {
        let attrs = [
            "x",
            "y",
            "z",
            "radius",
            "colour",
            "kD",
            "kS",
            "n",
            "reflectivity",
        ];
        assert_eq!(nearest("color", &attrs), Some("colour"));
        assert_eq!(nearest("kd", &attrs), Some("kD"));
        assert_eq!(nearest("raduis", &attrs), Some("radius"));
        assert_eq!(nearest("sphear", &["sphere", "plane"]), Some("sphere"));
        assert_eq!(nearest("teapot", &["sphere", "plane"]), None);
    }
}
