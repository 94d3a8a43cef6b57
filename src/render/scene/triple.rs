//! Three numbers, strictly: a scene's points and directions are arrays of exactly three
//! numbers, and anything else (four numbers, a string, a table) is an error that the parser
//! reports with the key's line.

use serde::de::{Deserializer, Error};
use serde::Deserialize;

/// Reads an array of exactly three numbers.
pub fn three<'de, D: Deserializer<'de>>(deserializer: D) -> Result<[f64; 3], D::Error> {
    let values = Vec::<f64>::deserialize(deserializer)?;
    <[f64; 3]>::try_from(values.as_slice())
        .map_err(|_| D::Error::invalid_length(values.len(), &"an array of three numbers"))
}

/// Reads an array of exactly three numbers, where the key may be left out.
pub fn maybe_three<'de, D: Deserializer<'de>>(
    deserializer: D,
) -> Result<Option<[f64; 3]>, D::Error> {
    three(deserializer).map(Some)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, Deserialize)]
    struct Point {
        #[serde(deserialize_with = "three")]
        at: [f64; 3],
    }

    #[test]
    fn only_three_numbers_are_a_point() {
        let point: Point = toml::from_str("at = [1, 2.5, -3]").unwrap();
        assert_eq!(point.at, [1.0, 2.5, -3.0]);
        for bad in [
            "[1, 2, 3, 4]",
            "[1, 2]",
            "[]",
            "\"1, 2, 3\"",
            "{ x = 1 }",
            "[1, \"2\", 3]",
        ] {
            let error = toml::from_str::<Point>(&format!("at = {bad}"))
                .expect_err(bad)
                .to_string();
            assert!(error.contains("at"), "{bad}: {error}");
        }
    }
}
