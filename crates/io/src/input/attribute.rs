//! A header attribute as a typed value: a person reads it as text (`info`), a program as JSON
//! with numbers as numbers, boxes as `{"min": [x, y], "max": [x, y]}` and matrices as arrays
//! of rows (docs/info-json.md).

use std::fmt;

use serde_json::{json, Value};

/// One attribute's value.
#[derive(Debug, Clone, PartialEq)]
pub enum Attribute {
    Integer(i64),
    Number(f64),
    Text(String),
    /// An integer box, both corners inclusive (OpenEXR's `box2i`: data and display windows).
    Box {
        min: [i64; 2],
        max: [i64; 2],
    },
    /// A vector of numbers (`v2f`, `v3f`, ...).
    Vector(Vec<f64>),
    /// A matrix, row by row (`m33f`, `m44f`).
    Matrix(Vec<Vec<f64>>),
    /// Primaries and white point, each (x, y).
    Chromaticities {
        red: [f64; 2],
        green: [f64; 2],
        blue: [f64; 2],
        white: [f64; 2],
    },
    /// Anything else, as the reader describes it.
    Other(String),
}

impl Attribute {
    /// The attribute as typed JSON.
    pub fn to_json(&self) -> Value {
        match self {
            Attribute::Integer(i) => json!(i),
            Attribute::Number(n) if n.is_finite() => json!(n),
            Attribute::Number(_) => Value::Null,
            Attribute::Text(t) | Attribute::Other(t) => json!(t),
            Attribute::Box { min, max } => json!({ "min": min, "max": max }),
            Attribute::Vector(v) => json!(v),
            Attribute::Matrix(rows) => json!(rows),
            Attribute::Chromaticities {
                red,
                green,
                blue,
                white,
            } => json!({ "red": red, "green": green, "blue": blue, "white": white }),
        }
    }

    /// A square matrix from its values in row order (16 for 4x4).
    pub fn matrix(values: &[f32]) -> Self {
        let side = (values.len() as f64).sqrt() as usize;
        Attribute::Matrix(
            values
                .chunks(side.max(1))
                .map(|row| row.iter().map(|&v| f64::from(v)).collect())
                .collect(),
        )
    }
}

impl fmt::Display for Attribute {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let list = |v: &[f64]| v.iter().map(f64::to_string).collect::<Vec<_>>().join(", ");
        match self {
            Attribute::Integer(i) => write!(f, "{i}"),
            Attribute::Number(n) => write!(f, "{n}"),
            Attribute::Text(t) | Attribute::Other(t) => write!(f, "{t}"),
            Attribute::Box { min, max } => {
                write!(f, "({}, {}) - ({}, {})", min[0], min[1], max[0], max[1])
            }
            Attribute::Vector(v) => write!(f, "({})", list(v)),
            Attribute::Matrix(rows) => {
                let rows: Vec<String> = rows.iter().map(|r| format!("[{}]", list(r))).collect();
                write!(f, "[{}]", rows.join(", "))
            }
            Attribute::Chromaticities {
                red,
                green,
                blue,
                white,
            } => write!(
                f,
                "red ({}, {}), green ({}, {}), blue ({}, {}), white ({}, {})",
                red[0], red[1], green[0], green[1], blue[0], blue[1], white[0], white[1]
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn attributes_are_typed_in_json_and_readable_as_text() {
        assert_eq!(Attribute::Integer(2).to_json(), json!(2));
        let window = Attribute::Box {
            min: [0, 0],
            max: [639, 479],
        };
        assert_eq!(window.to_json(), json!({"min": [0, 0], "max": [639, 479]}));
        assert_eq!(window.to_string(), "(0, 0) - (639, 479)");
        let m = Attribute::matrix(&[1.0, 0.0, 0.0, 1.0]);
        assert_eq!(m.to_json(), json!([[1.0, 0.0], [0.0, 1.0]]));
    }
}
