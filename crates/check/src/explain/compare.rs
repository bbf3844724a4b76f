//! `whitted explain --bug ID --compare`: the reference's ray tree and a mistake's side by
//! side, only the steps that differ. Both trees are the JSON of `explain --json` flattened
//! into rows named by where they are (depth, light, quantity), in the order a student reads
//! them: each vertex and its lights, where the chain leaves the scene, the fold of the chain,
//! the layers (which term changed), then the beauty.

use serde_json::Value;

use whitted_core::numbers::compact;

/// Rows shown at most: the first differences are the ones that cause the rest.
pub const SHOWN: usize = 12;

/// One flattened value of a tree.
type Row = (String, Value);

fn flatten(key: String, value: &Value, out: &mut Vec<Row>) {
    match value {
        Value::Object(map) => {
            for (k, v) in map {
                flatten(join(&key, k), v, out);
            }
        }
        _ => out.push((key, value.clone())),
    }
}

fn join(prefix: &str, key: &str) -> String {
    if prefix.is_empty() {
        key.to_string()
    } else {
        format!("{prefix}, {key}")
    }
}

/// A tree's rows in reading order.
fn rows(tree: &Value) -> Vec<Row> {
    let mut out = Vec::new();
    for vertex in tree["vertices"].as_array().into_iter().flatten() {
        let depth = format!("depth {}", vertex["depth"]);
        if let Value::Object(map) = vertex {
            // The vertex, its lights, then the colour they shade it with.
            for (k, v) in map
                .iter()
                .filter(|(k, _)| !["lights", "colour"].contains(&k.as_str()))
            {
                flatten(join(&depth, k), v, &mut out);
            }
        }
        for light in vertex["lights"].as_array().into_iter().flatten() {
            let name = format!("{depth}, light {}", light["light"].as_str().unwrap_or("?"));
            flatten(name, light, &mut out);
        }
        flatten(join(&depth, "colour"), &vertex["colour"], &mut out);
    }
    flatten("leaves the scene".into(), &tree["miss"], &mut out);
    for step in tree["fold_steps"].as_array().into_iter().flatten() {
        flatten(format!("fold at depth {}", step["depth"]), step, &mut out);
    }
    flatten("layer".into(), &tree["layers"], &mut out);
    out.push(("beauty".into(), tree["beauty"].clone()));
    out
}

/// A value in a few characters: numbers with 4 significant digits, vectors in brackets.
fn show(value: Option<&Value>) -> String {
    match value {
        None => "(none)".into(),
        Some(Value::Number(n)) => n.as_f64().map_or_else(|| n.to_string(), compact),
        Some(Value::Array(items)) => {
            // A vector's null component is a NaN (JSON has none).
            let parts: Vec<String> = items
                .iter()
                .map(|v| match v {
                    Value::Null => "NaN".into(),
                    v => show(Some(v)),
                })
                .collect();
            format!("({})", parts.join(", "))
        }
        Some(Value::Null) => "(none)".into(),
        Some(other) => other.to_string(),
    }
}

/// The rows where the two trees differ, as (where, the reference's, the mistake's), in the
/// reference's reading order, then the rows only the mistake's tree has.
pub fn differences(reference: &Value, mistake: &Value) -> Vec<(String, String, String)> {
    let (ours, theirs) = (rows(reference), rows(mistake));
    let find =
        |rows: &[Row], key: &str| rows.iter().find(|(k, _)| k == key).map(|(_, v)| v.clone());
    let mut out: Vec<(String, String, String)> = ours
        .iter()
        .filter_map(|(key, value)| {
            let other = find(&theirs, key);
            (other.as_ref() != Some(value))
                .then(|| (key.clone(), show(Some(value)), show(other.as_ref())))
        })
        .collect();
    out.extend(
        theirs
            .iter()
            .filter(|(key, _)| find(&ours, key).is_none())
            .map(|(key, value)| (key.clone(), show(None), show(Some(value)))),
    );
    out
}

/// The comparison as text: a heading, then at most `SHOWN` differing rows, the beauty's last
/// whenever it differs (what the pixel ends up as).
pub fn text(pixel: (u32, u32), name: &str, reference: &Value, mistake: &Value) -> String {
    let mut rows = differences(reference, mistake);
    if rows.len() > SHOWN {
        let beauty = rows.iter().position(|r| r.0 == "beauty");
        if let Some(beauty) = beauty.map(|i| rows.remove(i)) {
            rows.insert(SHOWN - 1, beauty);
        }
    }
    let mut out = format!(
        "pixel ({}, {}): the reference | {name}, the {} steps that differ{}\n",
        pixel.0,
        pixel.1,
        rows.len(),
        if rows.len() > SHOWN {
            format!(" (the first {SHOWN})")
        } else {
            String::new()
        }
    );
    if rows.is_empty() {
        out += "  none: this pixel is the same under both";
        return out;
    }
    let width = rows
        .iter()
        .take(SHOWN)
        .map(|r| r.0.len())
        .max()
        .unwrap_or(0);
    for (key, ours, theirs) in rows.iter().take(SHOWN) {
        out += &format!("  {key:<width$}  {ours}  |  {theirs}\n");
    }
    out.trim_end().to_string()
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn only_the_differing_rows_are_listed_in_reading_order() {
        let tree = |r: f64, specular: f64| {
            json!({"vertices": [{"depth": 0, "object": 1, "lights": [
                {"light": "1", "R": [r, 0.0, 1.0], "specular": [specular, specular, specular]}]}],
                "miss": null, "layers": {"specular": [specular, 0.0, 0.0]}, "beauty": [0.5, 0.5, 0.5]})
        };
        let rows = differences(&tree(0.5, 0.25), &tree(-0.5, 0.0));
        let keys: Vec<&str> = rows.iter().map(|r| r.0.as_str()).collect();
        assert_eq!(
            keys,
            [
                "depth 0, light 1, R",
                "depth 0, light 1, specular",
                "layer, specular"
            ]
        );
        assert_eq!(rows[0].1, "(0.5000, 0, 1.000)");
        assert!(text((1, 2), "x", &tree(0.5, 0.25), &tree(0.5, 0.25)).contains("none"));
    }
}
