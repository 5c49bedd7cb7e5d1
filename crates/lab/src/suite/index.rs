//! The report's index page (`templates/index.html`): one card per lab, its headline image
//! beside its title and summary, linking to the lab's page.

use crate::error::Result;
use crate::report::{render_page, Template};
use renderlab_core::io::write_atomic;
use serde::Serialize;
use std::path::{Path, PathBuf};

const INDEX: Template = Template { name: "index.html", source: include_str!("../../templates/index.html") };

/// One lab's card on the index page.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
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
    #[derive(Serialize)]
    struct Context<'a> {
        cards: &'a [IndexCard],
    }
    let html = render_page(INDEX, "renderlab results", "renderlab", &Context { cards: labs })?;
    let path = out_dir.as_ref().join("index.html");
    write_atomic(&path, |out| out.write_all(html.as_bytes()))?;
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn index_links_labs_with_their_images() {
        let dir = tempfile::tempdir().unwrap();
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
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1, "no temporary files left");
    }
}
