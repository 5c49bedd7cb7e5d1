//! The registry's text: the names, order, help and errors the catalogue gave when it was a
//! hand-written enum, pinned so that the generated forms stay what they were; a new scene
//! adds its own without editing them.

use super::*;

#[test]
fn default_names_and_order_are_the_catalogues() {
    let old = |k: &SceneKind| OLD.iter().any(|(o, ..)| *o == k.info().name);
    let names: Vec<String> = SceneKind::defaults().iter().filter(|k| old(k)).map(SceneKind::name).collect();
    assert_eq!(
        names,
        [
            "checkerboard",
            "thesis_quad",
            "thesis_quad_circuit",
            "thesis_quad_earth",
            "quad_tilt_0",
            "quad_tilt_45",
            "quad_tilt_70",
            "quad_tilt_85",
            "zone_plate"
        ]
    );
    let kinds: Vec<SceneKind> = SceneKind::defaults().into_iter().filter(old).collect();
    assert_eq!(
        kinds[..4],
        [SceneKind::Checkerboard, SceneKind::ThesisQuad, SceneKind::ThesisCircuit, SceneKind::ThesisEarth]
    );
    assert_eq!(kinds[5], SceneKind::TiltedQuad(45.0));
    for k in SceneKind::defaults() {
        assert_eq!(SceneKind::parse(&k.name()).unwrap(), k);
    }
    for (name, syntax, help, horizon) in OLD {
        let d = SCENES.iter().find(|d| d.name == name).expect("an old scene is still in the catalogue");
        assert_eq!((d.syntax().as_str(), d.help_item().as_str(), d.horizon), (syntax, help, horizon));
    }
}

/// Every scene of the old hand-written catalogue: name, syntax, `--scenes` help item, whether
/// it shows the horizon.
const OLD: [(&str, &str, &str, bool); 6] = [
    ("checkerboard", "checkerboard", "checkerboard", true),
    ("thesis_quad", "thesis_quad", "thesis_quad (checker)", false),
    ("thesis_quad_circuit", "thesis_quad_circuit", "thesis_quad_circuit", false),
    ("thesis_quad_earth", "thesis_quad_earth", "thesis_quad_earth", false),
    ("quad_tilt_", "quad_tilt_DEG", "quad_tilt_DEG (DEG in 0..=89.9)", false),
    ("zone_plate", "zone_plate", "zone_plate", true),
];

#[test]
fn parsing_reads_the_old_forms() {
    assert_eq!(SceneKind::parse(" zone_plate ").unwrap(), SceneKind::ZonePlate);
    assert_eq!(SceneKind::parse("quad_tilt_30.5").unwrap(), SceneKind::TiltedQuad(30.5));
    assert_eq!(SceneKind::parse("quad_tilt_89.9").unwrap().name(), "quad_tilt_89.9");
    assert_eq!(SceneKind::TiltedQuad(12.25).name(), "quad_tilt_12.25");
    let syntaxes: Vec<String> = SCENES.iter().map(Descriptor::syntax).collect();
    let (last, first) = syntaxes.split_last().unwrap();
    let expected = format!("(expected {} or {last})", first.join(", "));
    for bad in ["teapot", "", "quad_tilt_x", "quad_tilt_"] {
        let e = SceneKind::parse(bad).unwrap_err().to_string();
        assert_eq!(e, format!("unknown scene '{}' {expected}", bad.trim()));
    }
    for (bad, shown) in
        [("quad_tilt_90", "90"), ("quad_tilt_-1", "-1"), ("quad_tilt_nan", "NaN"), ("quad_tilt_inf", "inf")]
    {
        let e = SceneKind::parse(bad).unwrap_err().to_string();
        assert_eq!(e, format!("tilt: {shown}° must lie in [0, 89.9]"));
    }
}

#[test]
fn help_lists_the_catalogue() {
    let items: Vec<String> = SCENES.iter().map(Descriptor::help_item).collect();
    assert_eq!(SceneKind::help(), items.join(", "));
}

#[test]
fn an_out_of_range_tilt_is_refused_when_built() {
    let e = SceneKind::TiltedQuad(95.0).build(64, 48).unwrap_err();
    assert_eq!(e.to_string(), "tilt: 95° must lie in [0, 89.9]");
}
