//! Self-contained HTML reports: a page per lab with sections, paragraphs, tables, images and
//! inline SVG charts, and an index page linking the labs.
//!
//! Pages carry their own CSS (no external assets, no JavaScript) so that a results folder can
//! be opened straight from disk, archived or mailed. Everything given as text is HTML-escaped;
//! only [`Report::raw_html`] and [`Report::svg`] insert markup as given. Files are written
//! atomically.

use crate::error::Result;
use renderlab_core::io::write_atomic;
use std::fmt::Write as _;

use std::path::{Path, PathBuf};

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

/// Escapes a relative path for use as a URL in `src`/`href` (spaces, `#`, `?` and `%` are
/// percent-encoded; everything else is HTML-escaped).
fn escape_url(path: &str) -> String {
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
    escape_html(&s)
}

/// A lower-case identifier for a heading, unique within the page.
fn slug(heading: &str, used: &mut Vec<String>) -> String {
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
    while used.contains(&id) {
        id = format!("{base}-{n}");
        n += 1;
    }
    used.push(id.clone());
    id
}

const CSS: &str = r#"
:root {
  --ink: #1f2328; --muted: #5b6570; --line: #d9dee4; --panel: #f5f7f9;
  --accent: #2f5f8f; --head: #16202b;
}
* { box-sizing: border-box; }
html { -webkit-text-size-adjust: 100%; }
body {
  margin: 0; color: var(--ink); background: #fff;
  font: 15px/1.55 system-ui, -apple-system, "Segoe UI", Roboto, "Helvetica Neue", Arial, sans-serif;
}
header.page { background: var(--head); color: #f3f5f7; }
header.page .inner { max-width: 1180px; margin: 0 auto; padding: 26px 32px 22px; }
header.page h1 { margin: 0; font-size: 26px; font-weight: 650; letter-spacing: -0.01em; }
header.page .kicker {
  font-size: 12px; text-transform: uppercase; letter-spacing: 0.12em; color: #9fb3c8;
  margin-bottom: 4px;
}
header.page a { color: #9fc5ec; }
main { max-width: 1180px; margin: 0 auto; padding: 8px 32px 56px; }
nav.toc { margin: 20px 0 8px; padding: 12px 16px; background: var(--panel);
  border: 1px solid var(--line); border-radius: 6px; font-size: 14px; }
nav.toc strong { font-size: 12px; text-transform: uppercase; letter-spacing: 0.08em; color: var(--muted); }
nav.toc ol { margin: 6px 0 0; padding-left: 20px; columns: 2; column-gap: 32px; }
a { color: var(--accent); text-decoration: none; }
a:hover { text-decoration: underline; }
h2 { font-size: 20px; font-weight: 650; margin: 40px 0 12px; padding-bottom: 6px;
  border-bottom: 1px solid var(--line); }
p { margin: 10px 0; max-width: 90ch; }
code { font: 13px/1.4 ui-monospace, SFMono-Regular, Menlo, Consolas, monospace;
  background: var(--panel); padding: 1px 4px; border-radius: 3px; }
.table-wrap { overflow-x: auto; margin: 14px 0 22px; }
table { border-collapse: collapse; font-size: 14px; font-variant-numeric: tabular-nums; }
th, td { padding: 6px 14px; text-align: left; border-bottom: 1px solid var(--line); white-space: nowrap; }
thead th { background: var(--panel); font-weight: 600; border-bottom: 2px solid #c4ccd5; }
th.num, td.num { text-align: right; }
tbody tr:nth-child(even) { background: #fafbfc; }
tbody tr:hover { background: #eef4fa; }
figure { margin: 14px 0 24px; }
figure img { display: block; max-width: 100%; height: auto; border: 1px solid var(--line);
  border-radius: 4px; background: #fff; }
figure.plot svg { display: block; max-width: 100%; height: auto; border: 1px solid var(--line);
  border-radius: 6px; }
figcaption { color: var(--muted); font-size: 13px; margin-top: 6px; }
.grid { display: grid; gap: 18px; grid-template-columns: repeat(var(--cols, 2), minmax(0, 1fr));
  margin: 14px 0 24px; }
.grid figure { margin: 0; }
.cards { display: grid; gap: 16px; grid-template-columns: repeat(auto-fill, minmax(460px, 1fr));
  margin: 24px 0; }
.card { display: flex; gap: 16px; align-items: flex-start; border: 1px solid var(--line);
  border-radius: 8px; padding: 16px 18px; color: var(--ink); background: #fff; }
.card img.thumb { flex: 0 0 160px; width: 160px; height: 120px; object-fit: cover;
  border: 1px solid var(--line); border-radius: 4px; background: var(--panel); }
.card .text { min-width: 0; }
.card:hover { border-color: var(--accent); text-decoration: none; box-shadow: 0 2px 8px rgba(0,0,0,0.06); }
.card h3 { margin: 0 0 6px; font-size: 17px; color: var(--accent); }
.card p { margin: 0; color: var(--muted); font-size: 14px; }
footer { border-top: 1px solid var(--line); margin-top: 16px; color: var(--muted); font-size: 12px; }
footer .inner { max-width: 1180px; margin: 0 auto; padding: 14px 32px 28px; }
@media (max-width: 720px) {
  main, header.page .inner, footer .inner { padding-left: 16px; padding-right: 16px; }
  .grid { grid-template-columns: 1fr; }
  nav.toc ol { columns: 1; }
}
@media print {
  header.page { background: none; color: var(--ink); }
  header.page .kicker { color: var(--muted); }
  tbody tr:hover { background: none; }
  figure, table { break-inside: avoid; }
}
"#;

/// A complete HTML page around `body` (already HTML).
fn page(title: &str, kicker: &str, body: &str) -> String {
    let t = escape_html(title);
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>{t}</title>\n<style>{CSS}</style>\n</head>\n<body>\n\
         <header class=\"page\"><div class=\"inner\"><div class=\"kicker\">{k}</div>\
         <h1>{t}</h1></div></header>\n<main>\n{body}</main>\n\
         <footer><div class=\"inner\">Generated by renderlab-lab. Images are 8-bit sRGB; \
         metrics compare sRGB-encoded values with the reference.</div></footer>\n\
         </body>\n</html>\n",
        k = escape_html(kicker),
    )
}

/// One piece of a report body.
#[derive(Clone, Debug)]
enum Block {
    /// A section heading (text, not yet escaped).
    Section(String),
    /// Finished HTML.
    Html(String),
}

/// An HTML report under construction. Methods append to the page in order and return
/// `&mut Self` so that calls chain; [`Report::write`] renders and saves it.
#[derive(Clone, Debug)]
pub struct Report {
    title: String,
    blocks: Vec<Block>,
}

impl Report {
    /// An empty report whose page title and main heading is `title`.
    pub fn new(title: impl Into<String>) -> Self {
        Report { title: title.into(), blocks: Vec::new() }
    }

    /// Starts a new section headed `heading` (text). Pages with three or more sections get a
    /// table of contents at the top.
    pub fn section(&mut self, heading: &str) -> &mut Self {
        self.blocks.push(Block::Section(heading.to_string()));
        self
    }

    /// A paragraph of plain text (escaped; blank lines are kept as paragraph breaks).
    pub fn paragraph(&mut self, text: &str) -> &mut Self {
        for para in text.split("\n\n").filter(|p| !p.trim().is_empty()) {
            self.blocks.push(Block::Html(format!("<p>{}</p>\n", escape_html(para.trim()))));
        }
        self
    }

    /// Inserts `html` as given, unescaped: for markup the other methods do not offer. The
    /// caller is responsible for escaping any text inside it (see [`escape_html`]).
    pub fn raw_html(&mut self, html: &str) -> &mut Self {
        self.blocks.push(Block::Html(format!("{html}\n")));
        self
    }

    /// A table with a header row. Every cell is text (escaped). Columns whose cells all read
    /// as numbers (including `∞`, `–`, percentages and `2.5×`) are right-aligned. Rows shorter
    /// than the header are padded with empty cells.
    pub fn table<S: AsRef<str>>(&mut self, headers: &[S], rows: Vec<Vec<String>>) -> &mut Self {
        debug_assert!(
            rows.iter().all(|r| r.len() == headers.len()),
            "every table row needs one cell per header"
        );
        let ncols = headers.len().max(rows.iter().map(Vec::len).max().unwrap_or(0));
        let numeric: Vec<bool> = (0..ncols)
            .map(|c| {
                let mut cells =
                    rows.iter().filter_map(|r| r.get(c)).filter(|s| !s.trim().is_empty()).peekable();
                cells.peek().is_some() && cells.all(|s| is_numeric(s))
            })
            .collect();
        let class = |c: usize| if numeric[c] { " class=\"num\"" } else { "" };
        let mut h = String::from("<div class=\"table-wrap\"><table>\n<thead><tr>");
        for c in 0..ncols {
            let text = headers.get(c).map(|s| s.as_ref()).unwrap_or("");
            let _ = write!(h, "<th{}>{}</th>", class(c), escape_html(text));
        }
        h.push_str("</tr></thead>\n<tbody>\n");
        for row in &rows {
            h.push_str("<tr>");
            for c in 0..ncols {
                let text = row.get(c).map(String::as_str).unwrap_or("");
                let _ = write!(h, "<td{}>{}</td>", class(c), escape_html(text));
            }
            h.push_str("</tr>\n");
        }
        h.push_str("</tbody></table></div>\n");
        self.blocks.push(Block::Html(h));
        self
    }

    /// An image (path relative to the report file) with a caption; clicking opens it at full
    /// size.
    pub fn image(&mut self, rel_path: &str, caption: &str) -> &mut Self {
        self.blocks.push(Block::Html(format!("{}\n", figure(rel_path, caption))));
        self
    }

    /// Images side by side, `columns` per row (one column on narrow screens), each with its
    /// caption: for comparing techniques, or a rendering with its error maps.
    pub fn image_grid<P: AsRef<str>, C: AsRef<str>>(
        &mut self,
        items: &[(P, C)],
        columns: usize,
    ) -> &mut Self {
        let mut h = format!("<div class=\"grid\" style=\"--cols: {}\">\n", columns.max(1));
        for (path, caption) in items {
            h.push_str(&figure(path.as_ref(), caption.as_ref()));
            h.push('\n');
        }
        h.push_str("</div>\n");
        self.blocks.push(Block::Html(h));
        self
    }

    /// An inline SVG chart (such as [`crate::plot::scatter_svg`] returns), inserted as given
    /// and scaled to the page width.
    pub fn svg(&mut self, svg: &str) -> &mut Self {
        self.blocks.push(Block::Html(format!("<figure class=\"plot\">\n{svg}</figure>\n")));
        self
    }

    /// The complete HTML page.
    pub fn to_html(&self) -> String {
        let mut used = Vec::new();
        let mut toc = Vec::new();
        let mut body = String::new();
        let mut open = false;
        for b in &self.blocks {
            match b {
                Block::Section(heading) => {
                    if open {
                        body.push_str("</section>\n");
                    }
                    let id = slug(heading, &mut used);
                    let text = escape_html(heading);
                    let _ = write!(body, "<section id=\"{id}\">\n<h2>{text}</h2>\n");
                    toc.push((id, text));
                    open = true;
                }
                Block::Html(h) => body.push_str(h),
            }
        }
        if open {
            body.push_str("</section>\n");
        }
        let mut nav = String::new();
        if toc.len() >= 3 {
            nav.push_str("<nav class=\"toc\"><strong>Contents</strong><ol>");
            for (id, text) in &toc {
                let _ = write!(nav, "<li><a href=\"#{id}\">{text}</a></li>");
            }
            nav.push_str("</ol></nav>\n");
        }
        page(&self.title, "renderlab · lab report", &(nav + &body))
    }

    /// Writes the page to `path` atomically (the images it references are the caller's).
    pub fn write(&self, path: impl AsRef<Path>) -> Result<()> {
        let html = self.to_html();
        write_atomic(path.as_ref(), |out| out.write_all(html.as_bytes()))?;
        Ok(())
    }
}

/// A `<figure>` with a linked image and caption.
fn figure(rel_path: &str, caption: &str) -> String {
    let src = escape_url(rel_path);
    let cap = escape_html(caption);
    format!(
        "<figure><a href=\"{src}\"><img src=\"{src}\" alt=\"{cap}\" loading=\"lazy\"></a>\
         <figcaption>{cap}</figcaption></figure>"
    )
}

/// One lab's card on the index page.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct IndexCard {
    /// The lab's title (text).
    pub title: String,
    /// The lab's page, relative to the index.
    pub link: String,
    /// The lab's headline (text).
    pub summary: String,
    /// The lab's headline image, relative to the index, shown as a thumbnail beside the
    /// summary (none: text only).
    pub image: Option<String>,
}

/// Writes `out_dir/index.html`, the top-level results page: one card per lab, linking to the
/// lab's page, with its headline image as a thumbnail beside its title and summary. Returns
/// the path written.
pub fn write_index(out_dir: impl AsRef<Path>, labs: &[IndexCard]) -> Result<PathBuf> {
    let mut body = String::from(
        "<p>Each lab measures rendering methods for cost and for error against a ground-truth \
         reference. Open a lab for its tables, plots and images.</p>\n<div class=\"cards\">\n",
    );
    for card in labs {
        let title = escape_html(&card.title);
        let thumb = card.image.as_deref().map_or_else(String::new, |src| {
            format!("<img class=\"thumb\" src=\"{}\" alt=\"{title}\" loading=\"lazy\">", escape_url(src))
        });
        let _ = writeln!(
            body,
            "<a class=\"card\" href=\"{}\">{thumb}<div class=\"text\"><h3>{title}</h3><p>{}</p></div></a>",
            escape_url(&card.link),
            escape_html(&card.summary)
        );
    }
    body.push_str("</div>\n");
    let html = page("renderlab results", "renderlab", &body);
    let path = out_dir.as_ref().join("index.html");
    write_atomic(&path, |out| out.write_all(html.as_bytes()))?;
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_is_escaped_everywhere() {
        let evil = "<script>alert('x')</script> & \"q\"";
        let mut r = Report::new(evil);
        r.section(evil)
            .paragraph(evil)
            .table(&[evil], vec![vec![evil.to_string()]])
            .image("a b/<x>.png", evil)
            .image_grid(&[("c.png", evil)], 3);
        let html = r.to_html();
        assert!(!html.contains("<script>"), "{html}");
        assert!(html.contains("&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt; &amp; &quot;q&quot;"));
        assert!(html.contains("src=\"a%20b/&lt;x&gt;.png\""));
        // Raw HTML and SVG are the documented exceptions.
        let mut r = Report::new("t");
        r.raw_html("<b>bold</b>").svg("<svg></svg>");
        let html = r.to_html();
        assert!(html.contains("<b>bold</b>") && html.contains("<svg></svg>"));
    }

    #[test]
    fn page_structure_toc_and_numeric_columns() {
        let mut r = Report::new("Relief");
        for s in ["Setup", "Results", "Results"] {
            r.section(s).paragraph("text");
        }
        r.table(
            &["technique", "PSNR (dB)", "speed-up"],
            vec![
                vec!["POM".into(), format_number(f64::INFINITY, 2), "2.5×".into()],
                vec!["relief".into(), "31.25".into(), "1.0×".into()],
            ],
        );
        let html = r.to_html();
        assert!(html.starts_with("<!DOCTYPE html>"));
        assert!(html.trim_end().ends_with("</html>"));
        assert!(html.contains("<nav class=\"toc\">"));
        assert!(html.contains("id=\"results-2\""));
        assert!(html.contains("<td>POM</td><td class=\"num\">∞</td><td class=\"num\">2.5×</td>"));
        assert_eq!(html.matches("<section").count(), html.matches("</section>").count());
        assert!(!html.contains("http://") && !html.contains("https://"), "no external assets");
    }

    #[test]
    fn format_number_handles_non_finite() {
        assert_eq!(format_number(1.23456, 2), "1.23");
        assert_eq!(format_number(f64::INFINITY, 2), "∞");
        assert_eq!(format_number(f64::NEG_INFINITY, 2), "−∞");
        assert_eq!(format_number(f64::NAN, 2), "–");
    }

    #[test]
    fn write_is_atomic_and_index_links_labs() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("relief.html");
        let mut r = Report::new("Relief");
        r.paragraph("hello");
        r.write(&path).unwrap();
        assert!(std::fs::read_to_string(&path).unwrap().contains("<p>hello</p>"));
        let card = |image: Option<&str>| IndexCard {
            title: "Relief <mapping>".into(),
            link: "relief/index.html".into(),
            summary: "POM vs relief".into(),
            image: image.map(String::from),
        };
        let index = write_index(dir.path(), &[card(Some("relief/img/ref 60.png")), card(None)]).unwrap();
        let html = std::fs::read_to_string(index).unwrap();
        assert_eq!(html.matches("href=\"relief/index.html\"").count(), 2);
        assert!(html.contains("Relief &lt;mapping&gt;"));
        // The headline image sits inside the card, before its text; a card without one has none.
        assert_eq!(html.matches("<img class=\"thumb\" src=\"relief/img/ref%2060.png\"").count(), 1);
        let first = html.find("<img class=\"thumb\"").unwrap();
        assert!(first < html.find("<h3>").unwrap());
        let names: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        assert_eq!(names.len(), 2, "no temporary files left: {names:?}");
        // A directory that does not exist is an error naming the file, not a panic.
        let e = r.write(dir.path().join("nope").join("x.html")).unwrap_err();
        assert!(e.to_string().contains("x.html"));
    }
}
