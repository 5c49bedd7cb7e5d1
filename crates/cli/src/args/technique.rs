//! The technique flags' parser and help, from the relief technique catalogue.

use renderlab_relief::Technique;

/// Reads one technique name for clap (the error names the problem; clap adds the flag).
pub fn parse_technique(s: &str) -> Result<Technique, String> {
    Technique::parse(s).map_err(|e| e.to_string())
}

/// The technique list of `--help`, generated from the catalogue.
pub fn techniques_help() -> String {
    format!(
        "Techniques, comma-separated (default: the lab's list). NAME[:P1[:P2…]], parameters left \
         out from the end take their defaults:\n{}",
        renderlab_relief::techniques::help()
    )
}

/// The one-line technique syntax of `-h`, generated from the catalogue.
pub fn techniques_syntax() -> String {
    format!(
        "Techniques, comma-separated (default: the lab's list): {}",
        renderlab_relief::techniques::syntax()
    )
}
