//! Serde for an `f64` that may be non-finite: finite values as JSON numbers, the others as
//! the strings `"inf"`, `"-inf"` and `"NaN"` (JSON has no literal for them), read back
//! exactly. Used with `#[serde(with = "renderlab_core::any_f64")]` by results that may hold an infinite PSNR or an undefined ratio.

use serde::{Deserialize, Deserializer, Serializer};

/// Writes `v`.
pub fn serialize<S: Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
    if v.is_finite() {
        s.serialize_f64(*v)
    } else if v.is_nan() {
        s.serialize_str("NaN")
    } else if *v > 0.0 {
        s.serialize_str("inf")
    } else {
        s.serialize_str("-inf")
    }
}

#[derive(Deserialize)]
#[serde(untagged)]
enum Either {
    Number(f64),
    Text(String),
}

/// Reads a value [`serialize`] wrote.
pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    match Either::deserialize(d)? {
        Either::Number(v) => Ok(v),
        Either::Text(t) => match t.as_str() {
            "inf" => Ok(f64::INFINITY),
            "-inf" => Ok(f64::NEG_INFINITY),
            "NaN" => Ok(f64::NAN),
            _ => Err(serde::de::Error::custom(format!("not a number: {t:?}"))),
        },
    }
}
