//! Reading a stage's flag value `NAME[:P1[:P2]]`: the choice's name and its parameters,
//! each checked against its range, with errors that name the flag and its syntax in one
//! line.

use super::entry::Descriptor;

/// The largest count any stage parameter accepts (bounces, rays, samples): bounds the work
/// of one pixel.
pub const MAX_COUNT: u32 = 4096;

/// Splits `NAME[:P…]` and checks the count of parameters.
pub fn split<'a>(
    d: &Descriptor,
    value: &'a str,
    max_params: usize,
) -> Result<(&'a str, Vec<&'a str>), String> {
    let mut parts = value.split(':');
    let name = parts.next().unwrap_or_default();
    let params: Vec<&str> = parts.collect();
    if params.len() > max_params {
        return Err(format!("--{} {value:?}: too many parameters (syntax: {})", d.name, d.syntax));
    }
    Ok((name, params))
}

/// Parameter `i` of `params` as a count in 1..=[`MAX_COUNT`], or `default` when absent.
pub fn count(d: &Descriptor, what: &str, params: &[&str], i: usize, default: u32) -> Result<u32, String> {
    let Some(text) = params.get(i) else { return Ok(default) };
    match text.parse::<u32>() {
        Ok(n) if (1..=MAX_COUNT).contains(&n) => Ok(n),
        _ => Err(format!("--{}: {what} {text:?} must be a whole number in 1..={MAX_COUNT}", d.name)),
    }
}

/// Parameter `i` as a finite number in `[lo, hi]`, or `default` when absent.
pub fn number(
    d: &Descriptor,
    what: &str,
    params: &[&str],
    i: usize,
    (lo, hi): (f32, f32),
    default: f32,
) -> Result<f32, String> {
    let Some(text) = params.get(i) else { return Ok(default) };
    match text.parse::<f32>() {
        Ok(v) if v.is_finite() && v >= lo && v <= hi => Ok(v),
        _ => Err(format!("--{}: {what} {text:?} must be a number in [{lo}, {hi}]", d.name)),
    }
}

/// The error for a value whose choice is not the stage's.
pub fn unknown(d: &Descriptor, value: &str) -> String {
    format!("--{}: unknown choice {value:?} (syntax: {})", d.name, d.syntax)
}

/// Checks a count parameter of a built choice: in 1..=[`MAX_COUNT`].
pub fn check_count(what: &str, n: u32) -> Result<(), String> {
    if (1..=MAX_COUNT).contains(&n) {
        Ok(())
    } else {
        Err(format!("{what} must lie in 1..={MAX_COUNT}, got {n}"))
    }
}

/// Checks a roughness parameter of a built choice: in [0, 1].
pub fn check_roughness(what: &str, r: f32) -> Result<(), String> {
    if (0.0..=1.0).contains(&r) {
        Ok(())
    } else {
        Err(format!("{what} must lie in [0, 1], got {r}"))
    }
}

/// Checks a radius parameter of a built choice: finite and positive.
pub fn check_radius(what: &str, r: f32) -> Result<(), String> {
    if r.is_finite() && r > 0.0 {
        Ok(())
    } else {
        Err(format!("{what} must be finite and positive, got {r}"))
    }
}
