//! The registry's text: the names, order, help and errors the catalogue gave when it was a
//! hand-written enum, pinned so that the generated forms stay what they were.

use super::*;

#[test]
fn default_names_and_order_are_the_catalogues() {
    let names: Vec<String> = SceneKind::defaults().iter().map(SceneKind::name).collect();
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
    assert_eq!(
        SceneKind::defaults()[..4],
        [SceneKind::Checkerboard, SceneKind::ThesisQuad, SceneKind::ThesisCircuit, SceneKind::ThesisEarth]
    );
    assert_eq!(SceneKind::defaults()[5], SceneKind::TiltedQuad(45.0));
    for k in SceneKind::defaults() {
        assert_eq!(SceneKind::parse(&k.name()).unwrap(), k);
        assert_eq!(k.has_horizon(), matches!(k, SceneKind::Checkerboard | SceneKind::ZonePlate));
    }
}

#[test]
fn parsing_reads_the_old_forms() {
    assert_eq!(SceneKind::parse(" zone_plate ").unwrap(), SceneKind::ZonePlate);
    assert_eq!(SceneKind::parse("quad_tilt_30.5").unwrap(), SceneKind::TiltedQuad(30.5));
    assert_eq!(SceneKind::parse("quad_tilt_89.9").unwrap().name(), "quad_tilt_89.9");
    assert_eq!(SceneKind::TiltedQuad(12.25).name(), "quad_tilt_12.25");
    let expected = "(expected checkerboard, thesis_quad, thesis_quad_circuit, thesis_quad_earth, \
                    quad_tilt_DEG or zone_plate)";
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
    assert_eq!(
        SceneKind::help(),
        "checkerboard, thesis_quad (checker), thesis_quad_circuit, thesis_quad_earth, \
         quad_tilt_DEG (DEG in 0..=89.9), zone_plate"
    );
}

#[test]
fn an_out_of_range_tilt_is_refused_when_built() {
    let e = SceneKind::TiltedQuad(95.0).build(64, 48).unwrap_err();
    assert_eq!(e.to_string(), "tilt: 95° must lie in [0, 89.9]");
}
