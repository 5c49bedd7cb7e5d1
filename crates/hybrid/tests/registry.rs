//! The stage registry: every stage parses its own syntax and its default, writes labels and
//! flag values that read back, has help, sweeps valid settings and renders on a small scene;
//! and the configuration, labels and flag errors the command line and the lab rely on.

use renderlab_core::Camera;
use renderlab_hybrid::rng::Stream;
use renderlab_hybrid::stages::ao::{SSAO_RADIUS, SSAO_SAMPLES};
use renderlab_hybrid::stages::entry::{Entry, Phase};
use renderlab_hybrid::stages::gi::GI_REGULARIZE_ROUGHNESS;
use renderlab_hybrid::stages::reflections::DEFAULT_MAX_ROUGHNESS;
use renderlab_hybrid::stages::{DESCRIPTORS, NAMES};
use renderlab_hybrid::{Ao, Gi, HybridRenderer, Reflections, Shadows, StageConfig, StageId, Translucency};
use renderlab_scene::procedural::showcase;
use std::collections::HashSet;

/// A stage's flag values as the command line gives them, `None` for the others.
fn only<'a>(stage: &'a str, value: &'a str) -> impl Fn(&str) -> Option<&'a str> {
    move |name| (name == stage).then_some(value)
}

#[test]
fn every_stage_is_complete_and_distinct() {
    assert_eq!(DESCRIPTORS.len(), StageId::ALL.len());
    let names: HashSet<&str> = NAMES.iter().copied().collect();
    assert_eq!(names.len(), NAMES.len(), "names are unique");
    let positions: HashSet<u32> = DESCRIPTORS.iter().map(|d| d.sweep_position).collect();
    assert_eq!(positions.len(), DESCRIPTORS.len(), "sweep positions are unique");
    let mut streams: HashSet<Stream> = DESCRIPTORS.iter().map(|d| d.stream).collect();
    assert_eq!(streams.len(), DESCRIPTORS.len(), "streams are unique");
    streams.insert(Stream::REFERENCE_A);
    streams.insert(Stream::REFERENCE_B);
    assert_eq!(streams.len(), DESCRIPTORS.len() + 2, "no stage shares the reference's streams");
    assert!(DESCRIPTORS.iter().any(|d| d.phase == Phase::Terms));
    for &id in StageId::ALL {
        let d = id.descriptor();
        assert_eq!(StageId::from_name(d.name), Some(id));
        assert!(!d.help.is_empty() && d.help.ends_with('.'), "{}", d.name);
        assert!(d.syntax.split('|').any(|c| c.starts_with("rt")), "{}: a ray-traced choice", d.name);
        assert!(d.syntax.split('|').any(|c| c == d.default), "{}: the default is a choice", d.name);
        let help = d.help_text();
        assert!(help.contains(d.syntax) && help.contains(d.default) && !help.contains('\n'));
    }
}

#[test]
fn every_stage_parses_its_default_to_its_baseline_and_reads_back_its_values() {
    let base = StageConfig::all_raster();
    for &id in StageId::ALL {
        let d = id.descriptor();
        let c = StageConfig::from_flags(only(d.name, d.default)).unwrap();
        assert_eq!(c, base, "{}", d.name);
        assert!(!c.differs(id));
        let sweep = StageConfig::thesis_sweep(id);
        assert!(!sweep.is_empty(), "{}", d.name);
        let labels: HashSet<String> = sweep.iter().map(StageConfig::label).collect();
        assert_eq!(labels.len(), sweep.len(), "{}: labels are unique", d.name);
        assert!(sweep.iter().any(|c| c.in_report_sweep(id)), "{}: in the report's sweep", d.name);
        for c in &sweep {
            assert!(c.validate().is_ok(), "{}", c.label());
            assert!(c.differs(id) && !c.is_all_raster(), "{}", c.label());
            assert!(c.sweep_count(id).is_some(), "{}", c.label());
            assert!(c.label().starts_with("rt-"), "{}", c.label());
        }
    }
    // Each choice's flag value reads back to it.
    fn round_trip<E: Entry>(values: &[E]) {
        for v in values {
            assert_eq!(E::parse(&v.flag_value()).unwrap(), *v, "{}", v.flag_value());
        }
        assert_eq!(E::parse(E::DESCRIPTOR.default).unwrap(), E::BASELINE);
    }
    round_trip(&[Shadows::Raster, Shadows::RayTraced { samples_per_light: 7 }]);
    round_trip(&Reflections::thesis_sweep());
    round_trip(&Translucency::thesis_sweep());
    round_trip(&[Gi::Off, Gi::RayTraced { samples_per_pixel: 3, regularize: 0.0 }]);
    round_trip(&Gi::thesis_sweep());
    assert_eq!(
        Gi::parse("rt:2").unwrap(),
        Gi::RayTraced { samples_per_pixel: 2, regularize: GI_REGULARIZE_ROUGHNESS }
    );
    round_trip(&Gi::thesis_sweep());
    round_trip(&[Ao::Off, Ao::BASELINE, Ao::RayTraced { samples_per_pixel: 3, radius: 0.25 }]);
    round_trip(&Ao::thesis_sweep());
}

#[test]
fn every_setting_of_every_sweep_renders_on_a_small_scene() {
    let scene = showcase();
    let renderer = HybridRenderer::new(&scene).unwrap();
    let cam = &scene.cameras[0].camera;
    let camera = Camera { width: 16, height: 9, ..*cam };
    let base = renderer.render(&camera, &StageConfig::all_raster(), 1).unwrap();
    assert_eq!(base.rays.total(), 0);
    for &id in StageId::ALL {
        let c = *StageConfig::thesis_sweep(id).last().unwrap();
        let f = renderer.render(&camera, &c, 1).unwrap();
        assert_eq!(f.hdr.len(), 16 * 9);
        assert!(f.hdr.iter().all(|p| p.is_finite()), "{}", c.label());
        assert!(f.rays.get(id) > 0, "{}: the ray-traced choice traces rays", c.label());
        assert_eq!(f.rays.total(), f.rays.get(id), "{}: only its own stage traces", c.label());
    }
}

#[test]
fn frame_order_is_geometry_terms_lit_compose_over() {
    let ms = renderlab_hybrid::PerStage::<u32>::default();
    let names: Vec<&str> = ms.in_frame_order().into_iter().map(|(n, _)| n).collect();
    assert_eq!(names, ["geometry", "shadows", "gi", "ao", "reflections", "compose", "translucency"]);
    let sweep: Vec<&str> = StageId::in_sweep_order().into_iter().map(StageId::name).collect();
    assert_eq!(sweep, ["shadows", "translucency", "reflections", "gi", "ao"]);
}

#[test]
fn labels_name_the_ray_traced_stages() {
    assert_eq!(StageConfig::all_raster().label(), "raster");
    let c = StageConfig {
        reflections: Reflections::RayTraced { max_bounces: 4, max_roughness: 0.5 },
        ..StageConfig::all_raster()
    };
    assert_eq!(c.label(), "rt-reflections b4 r0.5");
    let c = StageConfig {
        shadows: Shadows::RayTraced { samples_per_light: 4 },
        ao: Ao::RayTraced { samples_per_pixel: 2, radius: 1.0 },
        ..StageConfig::all_raster()
    };
    assert_eq!(c.label(), "rt-shadows s4+rt-ao 2spp r1");
    assert!(!c.is_all_raster() && StageConfig::all_raster().is_all_raster());
}

#[test]
fn bad_parameters_are_refused() {
    let mut c = StageConfig::all_raster();
    assert!(c.validate().is_ok());
    c.gi = Gi::RayTraced { samples_per_pixel: 0, regularize: GI_REGULARIZE_ROUGHNESS };
    assert!(c.validate().is_err());
    c.gi = Gi::Off;
    c.reflections = Reflections::RayTraced { max_bounces: 1, max_roughness: f32::NAN };
    assert!(c.validate().is_err());
    c.reflections = Reflections::ScreenSpace;
    c.ao = Ao::RayTraced { samples_per_pixel: 1, radius: -1.0 };
    assert!(c.validate().is_err());
}

#[test]
fn defaults_are_the_all_raster_baseline() {
    let c = StageConfig::from_flags(|name| DESCRIPTORS.iter().find(|d| d.name == name).map(|d| d.default))
        .unwrap();
    assert_eq!(c, StageConfig::all_raster());
    assert_eq!(StageConfig::from_flags(|_| None).unwrap(), StageConfig::all_raster());
}

#[test]
fn choices_with_and_without_parameters() {
    assert_eq!(Shadows::parse("rt:4").unwrap(), Shadows::RayTraced { samples_per_light: 4 });
    assert_eq!(
        Reflections::parse("rt:8").unwrap(),
        Reflections::RayTraced { max_bounces: 8, max_roughness: DEFAULT_MAX_ROUGHNESS }
    );
    assert_eq!(
        Translucency::parse("rt:20:0.1").unwrap(),
        Translucency::RayTraced { max_refraction_rays: 20, max_roughness: 0.1 }
    );
    assert_eq!(
        Gi::parse("rt:16").unwrap(),
        Gi::RayTraced { samples_per_pixel: 16, regularize: GI_REGULARIZE_ROUGHNESS }
    );
    assert_eq!(Ao::parse("rt:2:1.5").unwrap(), Ao::RayTraced { samples_per_pixel: 2, radius: 1.5 });
    assert_eq!(Ao::parse("off").unwrap(), Ao::Off);
    assert_eq!(Ao::parse("ssao").unwrap(), Ao::ScreenSpace { samples: SSAO_SAMPLES, radius: SSAO_RADIUS });
}

#[test]
fn bad_values_name_the_flag() {
    for (flag, bad) in [
        ("shadows", Shadows::parse("rt:0").err()),
        ("shadows", Shadows::parse("maps").err()),
        ("reflections", Reflections::parse("rt:1:2").err()),
        ("reflections", Reflections::parse("rt:1:nan").err()),
        ("reflections", Reflections::parse("ssr:3").err()),
        ("translucency", Translucency::parse("rt:3:0.5:9").err()),
        ("gi", Gi::parse("rt:-1").err()),
        ("ao", Ao::parse("rt:1:0").err()),
        ("ao", Ao::parse("").err()),
    ] {
        let e = bad.expect("refused");
        assert!(e.starts_with(&format!("--{flag}")), "{e}");
        assert!(!e.contains('\n'));
    }
    // The messages as the command line has always printed them.
    assert_eq!(
        Translucency::parse("rt:3:0.5:9").unwrap_err(),
        "--translucency \"rt:3:0.5:9\": too many parameters (syntax: raster|rt[:RAYS[:MAXROUGH]])"
    );
    assert_eq!(
        Shadows::parse("rt:0").unwrap_err(),
        "--shadows: SAMPLES \"0\" must be a whole number in 1..=4096"
    );
    assert_eq!(
        Reflections::parse("rt:1:2").unwrap_err(),
        "--reflections: MAXROUGH \"2\" must be a number in [0, 1]"
    );
    assert_eq!(Gi::parse("maps").unwrap_err(), "--gi: unknown choice \"maps\" (syntax: off|rt[:SPP[:REG]])");
}

proptest::proptest! {
    #[test]
    fn parsed_configs_always_validate(n in 0u32..10_000, r in -2.0f32..3.0) {
        for v in [format!("rt:{n}:{r}"), format!("rt:{n}")] {
            if let Ok(c) = Reflections::parse(&v) {
                let cfg = StageConfig { reflections: c, ..StageConfig::all_raster() };
                proptest::prop_assert!(cfg.validate().is_ok());
            }
            if let Ok(c) = Translucency::parse(&v) {
                let cfg = StageConfig { translucency: c, ..StageConfig::all_raster() };
                proptest::prop_assert!(cfg.validate().is_ok());
            }
            if let Ok(c) = Ao::parse(&v) {
                let cfg = StageConfig { ao: c, ..StageConfig::all_raster() };
                proptest::prop_assert!(cfg.validate().is_ok());
            }
        }
    }
}
