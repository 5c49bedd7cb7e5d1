//! The features lab on tiny frames: every section runs, writes its table and images, and
//! draws the conclusions its studies support.

use renderlab_lab::features_lab::{run_features, FeaturesConfig};
use renderlab_relief::Technique;

fn tech(names: &[&str]) -> Vec<Technique> {
    names.iter().map(|n| Technique::parse(n).unwrap()).collect()
}

#[test]
fn every_section_runs_and_writes_its_table_and_images() {
    let mut cfg = FeaturesConfig::quick();
    cfg.silhouettes.width = 96;
    cfg.silhouettes.height = 72;
    cfg.silhouettes.texture_size = 64;
    cfg.silhouettes.study.methods = tech(&["pom:16", "silhouette:32"]);
    cfg.depth_offset.width = 96;
    cfg.depth_offset.height = 64;
    cfg.depth_offset.tracers = vec!["pom:16".into()];
    cfg.depth_offset.picture = "pom:16".into();
    cfg.lod.width = 96;
    cfg.lod.height = 54;
    cfg.lod.frames = 2;
    cfg.lod.texture_size = 64;
    cfg.lod.techniques = tech(&["pom:32", "pom-lod"]);
    cfg.grazing.width = 96;
    cfg.grazing.height = 60;
    cfg.grazing.elevations = vec![5.0];
    cfg.grazing.methods = tech(&["pom-shadow:16:16", "pom-horizon:16:16"]);
    let dir = tempfile::tempdir().unwrap();
    let s = run_features(&cfg, dir.path(), &|_, _, _| {}).unwrap();
    assert_eq!(s.sections.len(), 4);
    for section in &s.sections {
        let table = dir.path().join(format!("{}.json", section.stem));
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&table).unwrap()).unwrap();
        assert_eq!(json["rows"].as_array().unwrap().len(), section.rows.len(), "{}", section.stem);
        assert!(!section.rows.is_empty(), "{} has no rows", section.stem);
        assert!(section.rows.iter().all(|r| r.len() == section.headers.len()), "{}", section.stem);
        for f in &section.figures {
            assert!(dir.path().join(&f.file).exists(), "missing {}", f.file);
        }
        assert!(!section.findings.is_empty(), "{} found nothing", section.stem);
    }
    let html = std::fs::read_to_string(&s.index).unwrap();
    for title in ["Silhouettes", "Pixel-depth offset", "Level of detail", "grazing light"] {
        assert!(html.contains(title), "the page lacks {title}");
    }
    assert!(s.headline_image.is_some_and(|p| p.exists()));
}
