//! "Did you mean ...?" for misspelt names (elements, attributes, layers).

/// The candidate closest to `given` by edit distance, ignoring case, if it is close enough to
/// be a plausible misspelling (at most a third of the word, and at least one edit, away).
pub fn nearest<'a>(given: &str, candidates: &[&'a str]) -> Option<&'a str> {
    let given = given.to_lowercase();
    let limit = (given.chars().count() / 3).max(1);
    candidates
        .iter()
        .map(|&c| (edit_distance(&given, &c.to_lowercase()), c))
        .filter(|&(d, _)| d <= limit)
        .min_by_key(|&(d, _)| d)
        .map(|(_, c)| c)
}

/// Levenshtein distance over characters.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut previous: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut current = vec![i + 1; b.len() + 1];
        for (j, &cb) in b.iter().enumerate() {
            let substitution = previous[j] + usize::from(ca != cb);
            current[j + 1] = substitution.min(previous[j + 1] + 1).min(current[j] + 1);
        }
        previous = current;
    }
    previous[b.len()]
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

    #[test]
    fn edit_distance_counts_edits() {
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("same", "same"), 0);
    }
}
