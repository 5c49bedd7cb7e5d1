//! The README's catalogue tables are generated from the registries: each table sits between
//! `<!-- catalogue:NAME -->` and `<!-- /catalogue:NAME -->` and must equal what the registry
//! gives today, so a new entry (technique, filter, ...) without its row fails here rather than
//! going unnoticed. `RENDERLAB_BLESS=1 cargo test -p renderlab --test readme -- catalogue` rewrites the
//! tables in place from the registries.

use renderlab_hybrid::stages::DESCRIPTORS as STAGES;
use renderlab_relief::techniques::DESCRIPTORS;
use renderlab_scene::procedural::SCENES;
use renderlab_texture::filter::FILTERS;
use renderlab_texture::materials::MATERIALS;
use renderlab_texture::scene::SCENES as TEXTURE_SCENES;

const README: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../README.md");

/// Every generated table: its marker name and its markdown.
fn tables() -> Vec<(&'static str, String)> {
    let mut relief = String::from("| technique | what it does | kernels |\n|---|---|---|\n");
    for d in DESCRIPTORS {
        let kernels: Vec<&str> = d.kernels.iter().map(|k| k.name()).collect();
        relief.push_str(&format!(
            "| `{}` | {} | {} |\n",
            cell(&d.syntax()),
            cell(d.summary),
            kernels.join(", ")
        ));
    }
    let mut filters = String::from("| filter | what it does |\n|---|---|\n");
    for f in FILTERS {
        filters.push_str(&format!("| `{}` | {} |\n", cell(&f.syntax()), cell(f.description)));
    }
    let mut texture_scenes = String::from("| scene | what it shows |\n|---|---|\n");
    for d in TEXTURE_SCENES {
        texture_scenes.push_str(&format!("| `{}` | {} |\n", cell(&d.syntax()), cell(d.description)));
    }
    let mut stages = String::from("| stage | flag | default | what the choices do |\n|---|---|---|---|\n");
    for d in STAGES {
        stages.push_str(&format!(
            "| {} | `--{} {}` | `{}` | {} |\n",
            d.name,
            d.name,
            cell(d.syntax),
            d.default,
            cell(d.help)
        ));
    }
    let mut scenes = String::from("| scene | triangles | lights | cameras | in a default run | what it is |\n|---|---|---|---|---|---|\n");
    for e in SCENES {
        let views: Vec<&str> = e.views.iter().map(|v| v.name).collect();
        let default = if e.default_run { "yes" } else { "no" };
        scenes.push_str(&format!(
            "| `{}` | {} | {} | {} | {} | {} |\n",
            e.name,
            e.triangles,
            e.lights,
            views.join(", "),
            default,
            cell(e.summary)
        ));
    }
    let mut materials = String::from("| material | relief depth | what it is |\n|---|---|---|\n");
    for m in MATERIALS {
        materials.push_str(&format!("| `{}` | {} | {} |\n", m.name, m.height_scale, cell(m.description)));
    }
    vec![
        ("relief", relief),
        ("materials", materials),
        ("filters", filters),
        ("texture-scenes", texture_scenes),
        ("stages", stages),
        ("scenes", scenes),
    ]
}

/// Text made safe for one markdown table cell.
fn cell(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ").replace('|', "\\|")
}

/// `text` with the block between the markers of `name` replaced by `table`; `None` where the
/// markers are missing.
fn with_table(text: &str, name: &str, table: &str) -> Option<String> {
    let (open, close) = (format!("<!-- catalogue:{name} -->\n"), format!("<!-- /catalogue:{name} -->"));
    let start = text.find(&open)? + open.len();
    let end = start + text[start..].find(&close)?;
    Some(format!("{}{}{}", &text[..start], table, &text[end..]))
}

#[test]
fn readme_catalogue_tables_match_the_registries() {
    let text = std::fs::read_to_string(README).unwrap_or_else(|e| panic!("reading {README}: {e}"));
    let mut updated = text.clone();
    for (name, table) in tables() {
        updated = with_table(&updated, name, &table).unwrap_or_else(|| {
            panic!("README.md has no <!-- catalogue:{name} --> … <!-- /catalogue:{name} --> block")
        });
    }
    if std::env::var_os("RENDERLAB_BLESS").is_some() {
        std::fs::write(README, &updated).expect("writing README.md");
        return;
    }
    assert!(
        updated == text,
        "README.md's catalogue tables differ from the registries; run \
         RENDERLAB_BLESS=1 cargo test -p renderlab --test readme -- catalogue to regenerate them"
    );
}

#[test]
fn readme_names_every_relief_technique_with_its_syntax() {
    let text = std::fs::read_to_string(README).expect("README.md");
    for d in DESCRIPTORS {
        let syntax = d.syntax();
        assert!(text.contains(&format!("`{syntax}`")), "README.md does not list `{syntax}`");
    }
}

#[test]
fn readme_names_every_texture_filter() {
    let text = std::fs::read_to_string(README).expect("README.md");
    for f in FILTERS {
        assert!(text.contains(f.name), "README.md does not name the filter {}", f.name);
    }
}
