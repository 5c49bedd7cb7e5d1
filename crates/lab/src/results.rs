//! Results files: JSON for anything serialisable and CSV for tables of flat rows, both written
//! atomically (a temporary file renamed into place) so that an interrupted experiment never
//! leaves half a file.
//!
//! Non-finite numbers differ by format, because JSON has no literal for them:
//! - JSON (serde_json's rule): `NaN`, `inf` and `-inf` are written as `null`;
//! - CSV: they are written as `nan`, `inf` and `-inf`, which spreadsheets, pandas and R read
//!   back as floats. Finite numbers are written exactly as serde_json writes them (shortest
//!   round-tripping form, e.g. `0.1`, `1e-7`).

use crate::error::{LabError, Result};
use renderlab_core::io::write_atomic;
use serde::ser::{self, Impossible, Serialize};
use std::fmt::Display;

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
/// Each row must serialise as a struct or map whose values are scalars: numbers, booleans,
/// strings, chars, `Option`s of those (`None` is an empty field), unit enum variants (written
/// by name) and newtypes around them. `#[serde(flatten)]` works, so a row can embed a
/// [`crate::timing::Timing`] and a [`crate::metrics::Metrics`]. Columns come in field order;
/// every row must have the same columns. Fields containing a comma, a quote or a line break
/// are quoted, with quotes doubled (RFC 4180). An empty slice writes an empty file.
pub fn write_csv<T: Serialize>(path: impl AsRef<Path>, rows: &[T]) -> Result<()> {
    let path = path.as_ref();
    let text = csv_string(rows).map_err(|e| LabError::Serialize { path: path.to_path_buf(), reason: e.0 })?;
    write_atomic(path, |out| out.write_all(text.as_bytes()))?;
    Ok(())
}

/// Why a value cannot be a CSV row.
#[derive(Debug)]
struct CsvError(String);

impl Display for CsvError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for CsvError {}

impl ser::Error for CsvError {
    fn custom<M: Display>(msg: M) -> Self {
        CsvError(msg.to_string())
    }
}

/// The CSV text of `rows` (header line first, `\n` line endings).
fn csv_string<T: Serialize>(rows: &[T]) -> std::result::Result<String, CsvError> {
    let mut out = String::new();
    let mut header: Option<Vec<String>> = None;
    for (i, row) in rows.iter().enumerate() {
        let mut ser = RowSerializer { cells: Vec::new() };
        row.serialize(&mut ser).map_err(|e| CsvError(format!("row {}: {}", i + 1, e.0)))?;
        let names: Vec<String> = ser.cells.iter().map(|(k, _)| k.clone()).collect();
        match &header {
            None => {
                push_line(&mut out, names.iter().map(String::as_str));
                header = Some(names);
            }
            Some(h) if *h != names => {
                return Err(CsvError(format!(
                    "row {} has columns [{}] but the first row has [{}]",
                    i + 1,
                    names.join(", "),
                    h.join(", ")
                )));
            }
            Some(_) => {}
        }
        push_line(&mut out, ser.cells.iter().map(|(_, v)| v.as_str()));
    }
    Ok(out)
}

/// Appends one CSV record.
fn push_line<'a>(out: &mut String, fields: impl Iterator<Item = &'a str>) {
    for (i, f) in fields.enumerate() {
        if i > 0 {
            out.push(',');
        }
        if f.contains([',', '"', '\n', '\r']) {
            out.push('"');
            out.push_str(&f.replace('"', "\"\""));
            out.push('"');
        } else {
            out.push_str(f);
        }
    }
    out.push('\n');
}

/// Collects `(column name, cell text)` pairs of one row.
struct RowSerializer {
    cells: Vec<(String, String)>,
}

fn not_a_row<T>() -> std::result::Result<T, CsvError> {
    Err(CsvError("a CSV row must serialise as a struct or a map of scalars".into()))
}

macro_rules! reject_scalars {
    ($($method:ident($($arg:ty),*)),* $(,)?) => {
        $(fn $method(self, $(_: $arg),*) -> std::result::Result<(), CsvError> { not_a_row() })*
    };
}

impl ser::Serializer for &mut RowSerializer {
    type Ok = ();
    type Error = CsvError;
    type SerializeSeq = Impossible<(), CsvError>;
    type SerializeTuple = Impossible<(), CsvError>;
    type SerializeTupleStruct = Impossible<(), CsvError>;
    type SerializeTupleVariant = Impossible<(), CsvError>;
    type SerializeMap = Self;
    type SerializeStruct = Self;
    type SerializeStructVariant = Impossible<(), CsvError>;

    reject_scalars!(
        serialize_bool(bool),
        serialize_i8(i8),
        serialize_i16(i16),
        serialize_i32(i32),
        serialize_i64(i64),
        serialize_u8(u8),
        serialize_u16(u16),
        serialize_u32(u32),
        serialize_u64(u64),
        serialize_f32(f32),
        serialize_f64(f64),
        serialize_char(char),
        serialize_str(&str),
        serialize_bytes(&[u8]),
        serialize_none(),
        serialize_unit(),
        serialize_unit_struct(&'static str),
        serialize_unit_variant(&'static str, u32, &'static str),
    );

    fn serialize_some<T: ?Sized + Serialize>(self, value: &T) -> std::result::Result<(), CsvError> {
        value.serialize(self)
    }

    fn serialize_newtype_struct<T: ?Sized + Serialize>(
        self,
        _name: &'static str,
        value: &T,
    ) -> std::result::Result<(), CsvError> {
        value.serialize(self)
    }

    fn serialize_newtype_variant<T: ?Sized + Serialize>(
        self,
        _name: &'static str,
        _index: u32,
        _variant: &'static str,
        _value: &T,
    ) -> std::result::Result<(), CsvError> {
        not_a_row()
    }

    fn serialize_seq(self, _len: Option<usize>) -> std::result::Result<Self::SerializeSeq, CsvError> {
        not_a_row()
    }

    fn serialize_tuple(self, _len: usize) -> std::result::Result<Self::SerializeTuple, CsvError> {
        not_a_row()
    }

    fn serialize_tuple_struct(
        self,
        _name: &'static str,
        _len: usize,
    ) -> std::result::Result<Self::SerializeTupleStruct, CsvError> {
        not_a_row()
    }

    fn serialize_tuple_variant(
        self,
        _name: &'static str,
        _index: u32,
        _variant: &'static str,
        _len: usize,
    ) -> std::result::Result<Self::SerializeTupleVariant, CsvError> {
        not_a_row()
    }

    fn serialize_map(self, _len: Option<usize>) -> std::result::Result<Self, CsvError> {
        Ok(self)
    }

    fn serialize_struct(self, _name: &'static str, _len: usize) -> std::result::Result<Self, CsvError> {
        Ok(self)
    }

    fn serialize_struct_variant(
        self,
        _name: &'static str,
        _index: u32,
        _variant: &'static str,
        _len: usize,
    ) -> std::result::Result<Self::SerializeStructVariant, CsvError> {
        not_a_row()
    }
}

impl ser::SerializeStruct for &mut RowSerializer {
    type Ok = ();
    type Error = CsvError;

    fn serialize_field<T: ?Sized + Serialize>(
        &mut self,
        key: &'static str,
        value: &T,
    ) -> std::result::Result<(), CsvError> {
        let cell =
            value.serialize(CellSerializer).map_err(|e| CsvError(format!("field '{key}': {}", e.0)))?;
        self.cells.push((key.to_string(), cell));
        Ok(())
    }

    fn end(self) -> std::result::Result<(), CsvError> {
        Ok(())
    }
}

impl ser::SerializeMap for &mut RowSerializer {
    type Ok = ();
    type Error = CsvError;

    fn serialize_key<T: ?Sized + Serialize>(&mut self, key: &T) -> std::result::Result<(), CsvError> {
        let key = key.serialize(CellSerializer).map_err(|e| CsvError(format!("map key: {}", e.0)))?;
        self.cells.push((key, String::new()));
        Ok(())
    }

    fn serialize_value<T: ?Sized + Serialize>(&mut self, value: &T) -> std::result::Result<(), CsvError> {
        let last = self.cells.last_mut().ok_or_else(|| CsvError("map value without a key".into()))?;
        last.1 =
            value.serialize(CellSerializer).map_err(|e| CsvError(format!("field '{}': {}", last.0, e.0)))?;
        Ok(())
    }

    fn end(self) -> std::result::Result<(), CsvError> {
        Ok(())
    }
}

/// Turns one scalar into the text of a CSV cell.
struct CellSerializer;

fn not_a_scalar<T>() -> std::result::Result<T, CsvError> {
    Err(CsvError("not a scalar (CSV rows must be flat; use #[serde(flatten)] or write JSON)".into()))
}

/// Text of a float: serde_json's shortest form when finite, `inf`, `-inf` or `nan` otherwise.
fn float_text<F: Serialize + Into<f64> + Copy>(v: F) -> String {
    let x: f64 = v.into();
    if x.is_nan() {
        "nan".into()
    } else if x.is_infinite() {
        if x > 0.0 { "inf" } else { "-inf" }.into()
    } else {
        serde_json::to_string(&v).unwrap_or_else(|_| x.to_string())
    }
}

macro_rules! display_scalars {
    ($($method:ident($ty:ty)),* $(,)?) => {
        $(fn $method(self, v: $ty) -> std::result::Result<String, CsvError> { Ok(v.to_string()) })*
    };
}

impl ser::Serializer for CellSerializer {
    type Ok = String;
    type Error = CsvError;
    type SerializeSeq = Impossible<String, CsvError>;
    type SerializeTuple = Impossible<String, CsvError>;
    type SerializeTupleStruct = Impossible<String, CsvError>;
    type SerializeTupleVariant = Impossible<String, CsvError>;
    type SerializeMap = Impossible<String, CsvError>;
    type SerializeStruct = Impossible<String, CsvError>;
    type SerializeStructVariant = Impossible<String, CsvError>;

    display_scalars!(
        serialize_bool(bool),
        serialize_i8(i8),
        serialize_i16(i16),
        serialize_i32(i32),
        serialize_i64(i64),
        serialize_i128(i128),
        serialize_u8(u8),
        serialize_u16(u16),
        serialize_u32(u32),
        serialize_u64(u64),
        serialize_u128(u128),
        serialize_char(char),
        serialize_str(&str),
    );

    fn serialize_f32(self, v: f32) -> std::result::Result<String, CsvError> {
        Ok(float_text(v))
    }

    fn serialize_f64(self, v: f64) -> std::result::Result<String, CsvError> {
        Ok(float_text(v))
    }

    fn serialize_bytes(self, _v: &[u8]) -> std::result::Result<String, CsvError> {
        not_a_scalar()
    }

    fn serialize_none(self) -> std::result::Result<String, CsvError> {
        Ok(String::new())
    }

    fn serialize_some<T: ?Sized + Serialize>(self, value: &T) -> std::result::Result<String, CsvError> {
        value.serialize(self)
    }

    fn serialize_unit(self) -> std::result::Result<String, CsvError> {
        Ok(String::new())
    }

    fn serialize_unit_struct(self, _name: &'static str) -> std::result::Result<String, CsvError> {
        Ok(String::new())
    }

    fn serialize_unit_variant(
        self,
        _name: &'static str,
        _index: u32,
        variant: &'static str,
    ) -> std::result::Result<String, CsvError> {
        Ok(variant.to_string())
    }

    fn serialize_newtype_struct<T: ?Sized + Serialize>(
        self,
        _name: &'static str,
        value: &T,
    ) -> std::result::Result<String, CsvError> {
        value.serialize(self)
    }

    fn serialize_newtype_variant<T: ?Sized + Serialize>(
        self,
        _name: &'static str,
        _index: u32,
        _variant: &'static str,
        _value: &T,
    ) -> std::result::Result<String, CsvError> {
        not_a_scalar()
    }

    fn serialize_seq(self, _len: Option<usize>) -> std::result::Result<Self::SerializeSeq, CsvError> {
        not_a_scalar()
    }

    fn serialize_tuple(self, _len: usize) -> std::result::Result<Self::SerializeTuple, CsvError> {
        not_a_scalar()
    }

    fn serialize_tuple_struct(
        self,
        _name: &'static str,
        _len: usize,
    ) -> std::result::Result<Self::SerializeTupleStruct, CsvError> {
        not_a_scalar()
    }

    fn serialize_tuple_variant(
        self,
        _name: &'static str,
        _index: u32,
        _variant: &'static str,
        _len: usize,
    ) -> std::result::Result<Self::SerializeTupleVariant, CsvError> {
        not_a_scalar()
    }

    fn serialize_map(self, _len: Option<usize>) -> std::result::Result<Self::SerializeMap, CsvError> {
        not_a_scalar()
    }

    fn serialize_struct(
        self,
        _name: &'static str,
        _len: usize,
    ) -> std::result::Result<Self::SerializeStruct, CsvError> {
        not_a_scalar()
    }

    fn serialize_struct_variant(
        self,
        _name: &'static str,
        _index: u32,
        _variant: &'static str,
        _len: usize,
    ) -> std::result::Result<Self::SerializeStructVariant, CsvError> {
        not_a_scalar()
    }
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
    fn csv_supports_flatten_and_non_finite_values() {
        #[derive(Serialize)]
        struct Inner {
            median_ms: f64,
            min_ms: f32,
        }
        #[derive(Serialize)]
        struct Outer {
            name: &'static str,
            #[serde(flatten)]
            timing: Inner,
            ratio: f64,
        }
        let text = csv_string(&[Outer {
            name: "a",
            timing: Inner { median_ms: f64::NAN, min_ms: 0.1 },
            ratio: f64::NEG_INFINITY,
        }])
        .unwrap();
        assert_eq!(text, "name,median_ms,min_ms,ratio\na,nan,0.1,-inf\n");
    }

    #[test]
    fn csv_rejects_nested_values_and_differing_columns() {
        #[derive(Serialize)]
        struct Nested {
            v: Vec<u32>,
        }
        let e = csv_string(&[Nested { v: vec![1] }]).unwrap_err();
        assert!(e.0.contains("field 'v'"), "{}", e.0);
        let maps: Vec<std::collections::BTreeMap<&str, f64>> =
            vec![[("a", 1.0)].into_iter().collect(), [("b", 2.0)].into_iter().collect()];
        let e = csv_string(&maps).unwrap_err();
        assert!(e.0.contains("row 2"), "{}", e.0);
        assert!(csv_string(&[1.0f64]).is_err());
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
