//! Self-contained HTML pages (each lab's, and the suite's index in [`crate::suite`]), rendered
//! from the template files under `crates/lab/templates/` with minijinja.
//!
//! A page is two renders. First the lab's own template (its prose, sections, tables, figures
//! and charts, built from the shared macros of `macros.html`) with the lab's context; every
//! section it opens is recorded, in order, with a unique identifier. Then `page.html`, the
//! skeleton every page shares (head, inline CSS from `report.css`, header, the table of
//! contents when there are three or more sections, footer), around that body.
//!
//! Escaping: templates are HTML, so every value a template prints is escaped by
//! [`escape_html`] unless the template marks it `safe`; only markup the lab made itself (an
//! SVG chart, the rendered body) is. Paths in `src`/`href` go through the `url` filter
//! (percent-encoding of spaces, `#`, `?` and `%`), then the same escaping. Numbers reach the
//! templates as text formatted by [`format_number`] (or as integers), never as floats, so
//! that a page shows exactly the digits the lab chose.
//!
//! Pages carry their own CSS (no external assets, no JavaScript) so that a results folder can
//! be opened straight from disk, archived or mailed. The templates are compiled into the
//! binary; files are written atomically.

use crate::error::{LabError, Result};
use minijinja::value::{Serde, Value};
use minijinja::{AutoEscape, Environment, UndefinedBehavior};
use renderlab_core::io::write_atomic;
use serde::Serialize;
use std::path::Path;
use std::sync::{Arc, Mutex};

/// A page template: its file name (which also selects HTML escaping) and its text.
#[derive(Clone, Copy, Debug)]
pub struct Template {
    /// File name, ending in `.html`.
    pub name: &'static str,
    /// The template's text.
    pub source: &'static str,
}

/// The templates every page may use: the skeleton, its CSS and the macros.
const SHARED: [Template; 3] = [
    Template { name: "page.html", source: include_str!("../../templates/page.html") },
    Template { name: "report.css", source: include_str!("../../templates/report.css") },
    Template { name: "macros.html", source: include_str!("../../templates/macros.html") },
];

/// Escapes `&`, `<`, `>`, `"` and `'` so that `s` shows as text in HTML or SVG, in element
/// content and in attribute values alike.
pub fn escape_html(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + s.len() / 8);
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// Formats a measured value for a table with `decimals` digits after the point, rendering the
/// non-finite values that metrics legitimately produce: `∞` (PSNR of identical images), `−∞`,
/// and `–` for NaN (nothing measured, e.g. an empty mask).
pub fn format_number(v: f64, decimals: usize) -> String {
    if v.is_nan() {
        "–".into()
    } else if v == f64::INFINITY {
        "∞".into()
    } else if v == f64::NEG_INFINITY {
        "−∞".into()
    } else {
        format!("{v:.decimals$}")
    }
}

/// Whether a table cell reads as a number (right-aligned in tables).
fn is_numeric(cell: &str) -> bool {
    let t = cell.trim();
    let t = t
        .strip_suffix('%')
        .or_else(|| t.strip_suffix('×'))
        .or_else(|| t.strip_suffix('x'))
        .unwrap_or(t)
        .trim();
    matches!(t, "∞" | "−∞" | "–" | "inf" | "-inf" | "nan") || t.parse::<f64>().is_ok()
}

/// Per column of a table, whether all its non-blank cells read as numbers (and there is at
/// least one). The table has as many columns as its header or its longest row.
fn numeric_columns(headers: &[String], rows: &[Vec<String>]) -> Vec<bool> {
    let ncols = headers.len().max(rows.iter().map(Vec::len).max().unwrap_or(0));
    (0..ncols)
        .map(|c| {
            let mut cells = rows.iter().filter_map(|r| r.get(c)).filter(|s| !s.trim().is_empty()).peekable();
            cells.peek().is_some() && cells.all(|s| is_numeric(s))
        })
        .collect()
}

/// A relative path made fit for `src`/`href`: spaces, `#`, `?` and `%` percent-encoded,
/// backslashes turned to slashes (HTML escaping follows, as for every value).
fn url(path: &str) -> String {
    let mut s = String::with_capacity(path.len());
    for c in path.chars() {
        match c {
            ' ' => s.push_str("%20"),
            '#' => s.push_str("%23"),
            '?' => s.push_str("%3F"),
            '%' => s.push_str("%25"),
            '\\' => s.push('/'),
            c => s.push(c),
        }
    }
    s
}

/// A lower-case identifier for a heading, unique among `used` (which it joins).
fn slug(heading: &str, used: &[Anchor]) -> String {
    let mut s = String::new();
    for c in heading.chars() {
        if c.is_ascii_alphanumeric() {
            s.push(c.to_ascii_lowercase());
        } else if !s.ends_with('-') && !s.is_empty() {
            s.push('-');
        }
    }
    let base = s.trim_end_matches('-').to_string();
    let base = if base.is_empty() { "section".to_string() } else { base };
    let mut id = base.clone();
    let mut n = 2;
    while used.iter().any(|a| a.id == id) {
        id = format!("{base}-{n}");
        n += 1;
    }
    id
}

/// One section of a page, as the table of contents lists it.
#[derive(Clone, Debug, Serialize)]
struct Anchor {
    id: String,
    heading: String,
}

/// The environment for one page: the shared templates and `page`, HTML escaping by
/// [`escape_html`], the `url` filter, `numeric_columns`, and `anchor(heading)`, which records
/// each section in `anchors` and returns its identifier. An undefined name is an error, so
/// that a misspelt variable cannot leave a hole in a page.
fn environment(page: Template, anchors: Arc<Mutex<Vec<Anchor>>>) -> Result<Environment<'static>> {
    let mut env = Environment::new();
    env.set_undefined_behavior(UndefinedBehavior::Strict);
    env.set_syntax(
        minijinja::syntax::SyntaxConfig::builder()
            .trim_blocks(true)
            .lstrip_blocks(true)
            .keep_trailing_newline(true)
            .build()
            .map_err(|e| template_error(page.name, e))?,
    );
    env.set_formatter(|out, state, value| {
        if !value.is_safe() && matches!(state.auto_escape(), AutoEscape::Html) {
            out.write_str(&escape_html(&value.to_string()))?;
            Ok(())
        } else {
            minijinja::escape_formatter(out, state, value)
        }
    });
    env.add_filter("url", |path: String| url(&path));
    env.add_function("numeric_columns", |headers: Serde<Vec<String>>, rows: Serde<Vec<Vec<String>>>| {
        numeric_columns(&headers, &rows)
    });
    env.add_function("anchor", move |heading: String| {
        let mut used = anchors.lock().unwrap_or_else(|e| e.into_inner());
        let id = slug(&heading, &used);
        used.push(Anchor { id: id.clone(), heading });
        id
    });
    for t in SHARED.iter().chain([&page]) {
        env.add_template(t.name, t.source).map_err(|e| template_error(t.name, e))?;
    }
    Ok(env)
}

fn template_error(name: &str, e: minijinja::Error) -> LabError {
    LabError::Template { template: name.to_string(), reason: format!("{e:#}") }
}

/// The complete HTML page of `template` rendered with `context`, titled `title` under the
/// small heading `kicker`.
pub fn render_page(
    template: Template,
    title: &str,
    kicker: &str,
    context: &impl Serialize,
) -> Result<String> {
    let anchors = Arc::new(Mutex::new(Vec::new()));
    let env = environment(template, anchors.clone())?;
    let body = env
        .get_template(template.name)
        .and_then(|t| t.render(Value::from(Serde(context))))
        .map_err(|e| template_error(template.name, e))?;
    let anchors = std::mem::take(&mut *anchors.lock().unwrap_or_else(|e| e.into_inner()));
    let contents = if anchors.len() >= 3 { anchors } else { Vec::new() };
    env.get_template("page.html")
        .and_then(|t| {
            t.render(minijinja::context! { title, kicker, contents => Value::from(Serde(contents)), body })
        })
        .map_err(|e| template_error("page.html", e))
}

/// Renders a lab's page (see [`render_page`]; the kicker names it a lab report) and writes it
/// to `path` atomically (the images it references are the caller's).
pub fn write_page(path: &Path, template: Template, title: &str, context: &impl Serialize) -> Result<()> {
    let html = render_page(template, title, "renderlab · lab report", context)?;
    write_atomic(path, |out| out.write_all(html.as_bytes()))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A page exercising every macro.
    const TEST: Template = Template {
        name: "test.html",
        source: r#"{% import "macros.html" as m %}
<p>{{ text }}</p>
{% for heading in headings %}
{% call m.section(heading) %}
<p>text</p>
{% endcall %}
{% endfor %}
{{ m.table(headers, rows) }}
{% call m.grid(3) %}
{{ m.figure(path, text) }}
{% endcall %}
{{ m.plot(svg) }}
"#,
    };

    #[derive(Serialize)]
    struct Context {
        text: String,
        headings: Vec<String>,
        headers: Vec<String>,
        rows: Vec<Vec<String>>,
        path: String,
        svg: String,
    }

    fn context(text: &str, headings: &[&str]) -> Context {
        Context {
            text: text.into(),
            headings: headings.iter().map(|s| s.to_string()).collect(),
            headers: vec![text.into(), "PSNR (dB)".into(), "speed-up".into()],
            rows: vec![
                vec!["POM".into(), format_number(f64::INFINITY, 2), "2.5×".into()],
                vec![text.into(), "31.25".into(), "1.0×".into()],
            ],
            path: "a b/<x>.png".into(),
            svg: "<svg><b>chart</b></svg>".into(),
        }
    }

    #[test]
    fn text_is_escaped_everywhere_and_markup_only_where_marked_safe() {
        let evil = "<script>alert('x')</script> & \"q\" / ok";
        let html = render_page(TEST, evil, "kicker", &context(evil, &[evil])).unwrap();
        assert!(!html.contains("<script>"), "{html}");
        assert!(html.contains("&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt; &amp; &quot;q&quot; / ok"));
        assert!(html.contains("<title>&lt;script&gt;"));
        assert!(html.contains("src=\"a%20b/&lt;x&gt;.png\""));
        // The chart is markup the lab made: inserted as given.
        assert!(html.contains("<figure class=\"plot\">\n<svg><b>chart</b></svg></figure>\n"));
    }

    #[test]
    fn page_structure_contents_and_numeric_columns() {
        let html = render_page(TEST, "Relief", "k", &context("x", &["Setup", "Results", "Results"])).unwrap();
        assert!(html.starts_with("<!DOCTYPE html>\n<html lang=\"en\">\n"));
        assert!(html.ends_with("</body>\n</html>\n"));
        assert!(html.contains(
            "<nav class=\"toc\"><strong>Contents</strong><ol><li><a href=\"#setup\">Setup</a></li>\
             <li><a href=\"#results\">Results</a></li><li><a href=\"#results-2\">Results</a></li></ol></nav>\n"
        ));
        assert!(html.contains("<section id=\"results-2\">\n<h2>Results</h2>\n<p>text</p>\n</section>\n"));
        assert!(html.contains("<td>POM</td><td class=\"num\">∞</td><td class=\"num\">2.5×</td>"));
        assert!(html.contains("<th>x</th><th class=\"num\">PSNR (dB)</th>"));
        assert!(html.contains("<div class=\"grid\" style=\"--cols: 3\">\n<figure><a href="));
        assert_eq!(html.matches("<section").count(), html.matches("</section>").count());
        assert!(!html.contains("http://") && !html.contains("https://"), "no external assets");
        // Fewer than three sections: no contents.
        let html = render_page(TEST, "Relief", "k", &context("x", &["Setup"])).unwrap();
        assert!(!html.contains("<nav"));
    }

    #[test]
    fn a_misspelt_variable_is_an_error_naming_the_template() {
        let bad = Template { name: "bad.html", source: "{{ nope }}" };
        let e = render_page(bad, "t", "k", &context("x", &[])).unwrap_err();
        assert!(e.to_string().contains("bad.html"), "{e}");
    }

    #[test]
    fn format_number_handles_non_finite() {
        assert_eq!(format_number(1.23456, 2), "1.23");
        assert_eq!(format_number(f64::INFINITY, 2), "∞");
        assert_eq!(format_number(f64::NEG_INFINITY, 2), "−∞");
        assert_eq!(format_number(f64::NAN, 2), "–");
    }

    #[test]
    fn write_is_atomic() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("relief.html");
        write_page(&path, TEST, "Relief", &context("hello", &[])).unwrap();
        assert!(std::fs::read_to_string(&path).unwrap().contains("<p>hello</p>"));
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1, "no temporary files left");
        // A directory that does not exist is an error naming the file, not a panic.
        let e =
            write_page(&dir.path().join("nope").join("x.html"), TEST, "t", &context("x", &[])).unwrap_err();
        assert!(e.to_string().contains("x.html"));
    }
}
