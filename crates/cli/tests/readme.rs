//! The README names every technique and every texture filter of the catalogues, so that a
//! new entry without its line in the README fails here rather than going unnoticed.

use renderlab_relief::techniques::DESCRIPTORS;
use renderlab_texture::filter::FILTERS;

fn readme() -> String {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../README.md");
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("reading {path}: {e}"))
}

#[test]
fn readme_names_every_relief_technique_with_its_syntax() {
    let text = readme();
    for d in DESCRIPTORS {
        let syntax = d.syntax();
        assert!(text.contains(&format!("`{syntax}`")), "README.md does not list `{syntax}`");
    }
}

#[test]
fn readme_names_every_texture_filter() {
    let text = readme();
    for f in FILTERS {
        assert!(text.contains(f.name), "README.md does not name the filter {}", f.name);
    }
}
