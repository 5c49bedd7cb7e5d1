//! Results files: JSON for anything serialisable and CSV for tables of flat rows, both written
//! atomically (a temporary file renamed into place) so that an interrupted experiment never
//! leaves half a file.
//!
//! Non-finite numbers differ by format, because JSON has no literal for them:
//! - JSON (serde_json's rule): `NaN`, `inf` and `-inf` are written as `null`;
//! - CSV (the `csv` crate, which formats floats with `ryu`): `NaN`, `inf` and `-inf`, which
//!   spreadsheets, pandas and R read back as floats. Finite numbers are written in the
//!   shortest form that reads back exactly (e.g. `0.1`, `1e-7`, `2.0`), as in the JSON.

use crate::error::{LabError, Result};
use renderlab_core::io::write_atomic;
use serde::Serialize;
use std::path::Path;

/// Writes `value` as pretty-printed JSON (with a final newline), atomically.
pub fn write_json<T: Serialize + ?Sized>(path: impl AsRef<Path>, value: &T) -> Result<()> {
    let path = path.as_ref();
    let mut bytes = serde_json::to_vec_pretty(value)
        .map_err(|e| LabError::Serialize { path: path.to_path_buf(), reason: e.to_string() })?;
    bytes.push(b'\n');
    write_atomic(path, |out| out.write_all(&bytes))?;
    Ok(())
}

/// Writes `rows` as CSV with a header row, atomically.
///
/// Each row must serialise as a struct of scalars: numbers, booleans, strings, chars,
/// `Option`s of those (`None` is an empty field), unit enum variants (written by name) and
/// newtypes around them. The header is the first row's field names, in field order; every row
/// must have as many fields. A row type may not use `#[serde(flatten)]` (it serialises as a
/// map, which CSV rows cannot be): give the row its own flat fields. Fields containing a
/// comma, a quote or a line break are quoted, with quotes doubled (RFC 4180); lines end in
/// `\n`. An empty slice writes an empty file.
pub fn write_csv<T: Serialize>(path: impl AsRef<Path>, rows: &[T]) -> Result<()> {
    let path = path.as_ref();
    let bytes = csv_bytes(rows).map_err(|e| LabError::Serialize { path: path.to_path_buf(), reason: e })?;
    write_atomic(path, |out| out.write_all(&bytes))?;
    Ok(())
}

/// The CSV text of `rows` (header line first), or why a row cannot be written.
fn csv_bytes<T: Serialize>(rows: &[T]) -> std::result::Result<Vec<u8>, String> {
    let mut w = csv::Writer::from_writer(Vec::new());
    for (i, row) in rows.iter().enumerate() {
        w.serialize(row).map_err(|e| format!("row {}: {e}", i + 1))?;
    }
    w.into_inner().map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Serialize;

    #[derive(Serialize, Debug, PartialEq, Clone, Copy)]
    enum Kind {
        Pom,
        Relief,
    }

    #[derive(Serialize, Debug, PartialEq, Clone)]
    struct Row {
        technique: String,
        kind: Kind,
        steps: u32,
        time_ms: f64,
        psnr_db: f64,
        ok: bool,
        note: Option<String>,
    }

    /// The CSV text of `rows`.
    fn csv_string<T: Serialize>(rows: &[T]) -> std::result::Result<String, String> {
        csv_bytes(rows).map(|b| String::from_utf8(b).unwrap())
    }

    /// A small RFC 4180 reader for the round trip.
    fn parse_csv(text: &str) -> Vec<Vec<String>> {
        let mut rows = Vec::new();
        let mut row = Vec::new();
        let mut field = String::new();
        let mut quoted = false;
        let mut chars = text.chars().peekable();
        while let Some(c) = chars.next() {
            match (quoted, c) {
                (true, '"') if chars.peek() == Some(&'"') => {
                    chars.next();
                    field.push('"');
                }
                (true, '"') => quoted = false,
                (true, c) => field.push(c),
                (false, '"') => quoted = true,
                (false, ',') => row.push(std::mem::take(&mut field)),
                (false, '\n') => {
                    row.push(std::mem::take(&mut field));
                    rows.push(std::mem::take(&mut row));
                }
                (false, c) => field.push(c),
            }
        }
        rows
    }

    fn rows() -> Vec<Row> {
        vec![
            Row {
                technique: "POM, 32 steps".into(),
                kind: Kind::Pom,
                steps: 32,
                time_ms: 1.25,
                psnr_db: 31.5,
                ok: true,
                note: Some("said \"fast\"\nsecond line".into()),
            },
            Row {
                technique: "relief".into(),
                kind: Kind::Relief,
                steps: 8,
                time_ms: 0.1,
                psnr_db: f64::INFINITY,
                ok: false,
                note: None,
            },
        ]
    }

    #[test]
    fn csv_round_trip_with_quoting() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("rows.csv");
        write_csv(&path, &rows()).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.starts_with("technique,kind,steps,time_ms,psnr_db,ok,note\n"));
        assert!(text.contains("\"POM, 32 steps\""));
        assert!(text.contains("\"said \"\"fast\"\"\nsecond line\""));
        let parsed = parse_csv(&text);
        assert_eq!(parsed.len(), 3);
        assert_eq!(
            parsed[1],
            ["POM, 32 steps", "Pom", "32", "1.25", "31.5", "true", "said \"fast\"\nsecond line"]
        );
        assert_eq!(parsed[2], ["relief", "Relief", "8", "0.1", "inf", "false", ""]);
        // Numbers read back exactly.
        assert_eq!(parsed[2][3].parse::<f64>().unwrap(), 0.1);
        assert_eq!(parsed[2][4].parse::<f64>().unwrap(), f64::INFINITY);
        // No temporary file is left behind.
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    proptest::proptest! {
        #[test]
        fn csv_quoting_round_trips_any_text(
            a in "[a-z0-9,\" \n\r]{0,12}",
            b in "[a-z0-9,\" \n\r]{0,12}",
        ) {
            #[derive(Serialize)]
            struct Pair {
                a: String,
                b: String,
            }
            let text = csv_string(&[Pair { a: a.clone(), b: b.clone() }]).unwrap();
            let parsed = parse_csv(&text);
            proptest::prop_assert_eq!(parsed.len(), 2);
            proptest::prop_assert_eq!(&parsed[1], &vec![a, b]);
        }
    }

    #[test]
    fn csv_writes_non_finite_values_and_shortest_floats() {
        #[derive(Serialize)]
        struct Row {
            name: &'static str,
            median_ms: f64,
            min_ms: f32,
            ratio: f64,
            whole: f64,
        }
        let text = csv_string(&[Row {
            name: "a",
            median_ms: f64::NAN,
            min_ms: 0.1,
            ratio: f64::NEG_INFINITY,
            whole: 2.0,
        }])
        .unwrap();
        assert_eq!(text, "name,median_ms,min_ms,ratio,whole\na,NaN,0.1,-inf,2.0\n");
    }

    #[test]
    fn csv_rejects_nested_values_flatten_and_differing_columns() {
        #[derive(Serialize)]
        struct Nested {
            v: Vec<u32>,
        }
        assert!(csv_string(&[Nested { v: vec![1] }]).is_err());
        #[derive(Serialize)]
        struct Inner {
            a: f64,
        }
        #[derive(Serialize)]
        struct Flattened {
            #[serde(flatten)]
            inner: Inner,
        }
        assert!(csv_string(&[Flattened { inner: Inner { a: 1.0 } }]).is_err());
        #[derive(Serialize)]
        struct Short {
            a: f64,
        }
        #[derive(Serialize)]
        #[serde(untagged)]
        enum Either {
            Two(Row),
            One(Short),
        }
        let e = csv_string(&[Either::Two(rows()[1].clone()), Either::One(Short { a: 1.0 })]).unwrap_err();
        assert!(e.contains("row 2"), "{e}");
        assert_eq!(csv_string::<Row>(&[]).unwrap(), "");
    }

    #[test]
    fn json_writes_null_for_non_finite_values() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("r.json");
        write_json(&path, &rows()).unwrap();
        let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        assert_eq!(v[0]["technique"], "POM, 32 steps");
        assert_eq!(v[0]["steps"], 32);
        assert!(v[1]["psnr_db"].is_null());
    }

    #[test]
    fn write_to_a_missing_directory_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("missing").join("r.csv");
        let e = write_csv(&path, &rows()).unwrap_err();
        assert!(e.to_string().contains("r.csv"), "{e}");
    }
}
