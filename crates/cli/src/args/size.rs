//! The one `WIDTHxHEIGHT` parser of the command line, and its ranged form.

use super::range::Whole;

/// The one parser of every `WIDTHxHEIGHT` flag (`--resolution`, `--size`): two whole numbers
/// joined by `x`, `X` or `×` (`1920x1080`, `16×9`). A side below 1 is refused by its range
/// (`-16x16` reaches this parser, see [`crate::args::try_parse`], and is named as out of range rather than
/// taken for a flag); a command with a range of sides checks it with [`size_in`], the others
/// their own largest size.
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

/// The clap value parser of a `WIDTHxHEIGHT` flag whose sides must each lie in `sides`
/// ([`parse_size`], then the range).
pub fn size_in(
    sides: Whole<u32>,
) -> impl Fn(&str) -> Result<(u32, u32), String> + Clone + Send + Sync + 'static {
    move |s: &str| {
        let (w, h) = parse_size(s)?;
        if !sides.contains(w) || !sides.contains(h) {
            return Err(format!("{w}x{h}: each side must lie in {sides}"));
        }
        Ok((w, h))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_size_parser_takes_x_capital_x_and_times_and_refuses_by_range() {
        for s in ["16x9", "16X9", "16×9", " 16 x 9 "] {
            assert_eq!(parse_size(s), Ok((16, 9)), "{s}");
        }
        assert!(parse_size("-16x16").unwrap_err().contains("at least 1"));
        assert!(parse_size("0x9").unwrap_err().contains("at least 1"));
        assert!(parse_size("16y9").unwrap_err().contains("is not WIDTHxHEIGHT"));
        assert!(parse_size("99999999999x9").unwrap_err().contains("larger than"));
    }

    #[test]
    fn a_ranged_size_names_its_range() {
        let p = size_in(Whole::new(8, 4096));
        assert_eq!(p("16×12"), Ok((16, 12)));
        assert_eq!(p("4x16"), Err("4x16: each side must lie in 8..=4096".into()));
        assert!(p("-16x16").unwrap_err().contains("at least 1"));
    }
}
