//! The one `WIDTHxHEIGHT` parser of the command line.

/// The one parser of every `WIDTHxHEIGHT` flag (`--resolution`, `--size`): two whole numbers
/// joined by `x`, `X` or `×` (`1920x1080`, `16×9`). A side below 1 is refused by its range
/// (`-16x16` reaches this parser, see [`crate::args::try_parse`], and is named as out of range rather than
/// taken for a flag); each command then checks its own largest size.
pub fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let bad = || format!("'{s}' is not WIDTHxHEIGHT (e.g. 1920x1080)");
    let (w, h) = s.split_once(['x', 'X', '×']).ok_or_else(bad)?;
    let side = |v: &str| -> Result<i64, String> { v.trim().parse::<i64>().map_err(|_| bad()) };
    let (w, h) = (side(w)?, side(h)?);
    if w < 1 || h < 1 {
        return Err(format!("{w}x{h}: each side must be at least 1 pixel"));
    }
    let max = i64::from(u32::MAX);
    if w > max || h > max {
        return Err(format!("{w}x{h}: a side is larger than {max} pixels"));
    }
    Ok((w as u32, h as u32))
}
