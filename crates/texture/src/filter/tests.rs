//! The registry's tests: every entry walked (it parses its own syntax, its canonical name
//! round-trips, it has help, it renders a small frame, its GPU form is stated), and the texts
//! the catalogue generates held to the ones the command line has always printed.

use super::descriptor::ParamKind;
use super::*;
use crate::scene::{SceneKind, TestScene};

#[test]
fn names_round_trip_and_defaults_are_omitted() {
    for (text, name) in [
        ("trilinear", "trilinear"),
        ("aniso16", "aniso16"),
        ("aniso16:box", "aniso16:box"),
        ("aniso4:sigma=0.4", "aniso4:sigma=0.4"),
        ("ewa", "ewa"),
        ("ewa:texels=48:cut=2", "ewa:cut=2:texels=48"),
        ("ewa:sigma=0.5:cut=3:ecc=16:texels=216", "ewa"),
    ] {
        let f: FilterSpec = text.parse().unwrap();
        assert_eq!(f.name(), name);
        assert_eq!(f.name().parse::<FilterSpec>().unwrap(), f);
    }
    for bad in
        ["aniso0", "aniso99", "ewa:ecc=99", "ewa:sigma=nan", "ewa:box", "gauss", "trilinear:box", "ewa:16:24"]
    {
        assert!(bad.parse::<FilterSpec>().is_err(), "{bad}");
    }
}

/// Texts that spell `d` with its parameters at their defaults, their limits and in between,
/// each written explicitly.
fn spellings(d: &Descriptor) -> Vec<String> {
    let mut heads = vec![d.name.to_string()];
    let mut parts: Vec<String> = Vec::new();
    for p in d.params {
        match p.kind {
            ParamKind::Suffix { example, min, max } => {
                heads = [example, min, max].iter().map(|n| format!("{}{n}", d.name)).collect();
            }
            ParamKind::Real { key, default, min, max } => {
                parts.extend([default, min, max, 0.5 * (min + max)].map(|v| format!("{key}={v}")));
            }
            ParamKind::Whole { key, default, min, max } => {
                parts.extend([default, min, max, (min + max) / 2].map(|v| format!("{key}={v}")));
            }
            ParamKind::Kernel { with_box } => {
                parts.extend(
                    ["sigma=0.5", "cut=3", "sigma=0.1", "sigma=2", "cut=1", "cut=4", "sigma=0.45:cut=2"]
                        .map(String::from),
                );
                if with_box {
                    parts.push("box".into());
                }
            }
        }
    }
    let mut out = Vec::new();
    for h in &heads {
        out.push(h.clone());
        for p in &parts {
            out.push(format!("{h}:{p}"));
        }
        let keyed: Vec<&str> = parts.iter().map(String::as_str).filter(|p| p.contains('=')).collect();
        if !keyed.is_empty() {
            out.push(format!("{h}:{}", keyed.join(":")));
        }
    }
    out
}

#[test]
fn every_entry_parses_its_syntax_round_trips_has_help_and_renders() {
    let help = FilterSpec::help();
    let scene = TestScene::new(SceneKind::ThesisQuad, 24, 16).unwrap();
    let surface = scene.surface();
    for (i, d) in FILTERS.iter().enumerate() {
        assert!(FILTERS[..i].iter().all(|e| e.name != d.name), "{} twice", d.name);
        assert!(!d.description.is_empty() && help.contains(&format!("{}: {}", d.syntax(), d.description)));
        assert!(expected().contains(&d.syntax()));
        let texts = spellings(d);
        for text in &texts {
            let f: FilterSpec = text.parse().unwrap_or_else(|e| panic!("{text}: {e}"));
            assert_eq!(f.info().name, d.name, "{text}");
            assert_eq!(f.name().parse::<FilterSpec>().unwrap(), f, "{text}");
            assert_eq!(f.to_string(), f.name());
            match f.gpu() {
                Ok(twin) => assert_eq!(twin.cpu.gpu().unwrap(), twin, "{text}: the twin's twin"),
                Err(why) => assert!(!why.is_empty(), "{text}: a GPU form or a reason"),
            }
        }
        // The first spelling renders a small frame, the background where no surface shows.
        let f: FilterSpec = texts[0].parse().unwrap();
        let img = scene.render_spec(&surface, &f);
        assert_eq!(img.size(), (24, 16));
        assert!(img.pixels().iter().all(|c| c.is_finite()), "{}", d.name);
        let (fetches, _) = scene.count_fetches_spec(&surface, &f);
        assert!(fetches > 0, "{}: reads texels", d.name);
    }
}

/// Each parameter's default and range, as its descriptor holds them, are the ones the help
/// text states.
#[test]
fn descriptions_state_the_descriptors_defaults_and_ranges() {
    for d in FILTERS {
        for p in d.params {
            let stated = match p.kind {
                ParamKind::Suffix { min, max, .. } => format!("({min}..={max})"),
                ParamKind::Real { default, .. } => format!("{} (default {default})", p.name),
                ParamKind::Whole { default, .. } => format!("{} texels (default {default})", p.name),
                ParamKind::Kernel { .. } => "(default σ=0.5, cut=3)".into(),
            };
            assert!(d.description.contains(&stated), "{}: '{stated}' not in '{}'", d.name, d.description);
        }
    }
    assert_eq!(PixelFilter::GAUSSIAN, PixelFilter::Gaussian { sigma: 0.5, cut: 3.0 });
}

#[test]
fn the_lab_measures_every_filter() {
    let lab = lab_filters();
    for d in FILTERS {
        assert!(lab.iter().any(|f| f.info().name == d.name), "{} is never measured", d.name);
    }
    for f in &lab {
        assert_eq!(f.name().parse::<FilterSpec>().unwrap(), *f);
    }
    // The filters the lab measured when its list was written by hand (a filter added to the
    // registry adds its own settings without changing these).
    let old = ["nearest", "bilinear", "bicubic", "trilinear", "aniso", "ewa"];
    let names: Vec<String> =
        lab.iter().filter(|f| old.contains(&f.info().name)).map(FilterSpec::name).collect();
    assert_eq!(
        names.join(", "),
        "nearest, bilinear, bicubic, trilinear, aniso2, aniso4, aniso8, aniso16, aniso16:box, ewa, \
         ewa:cut=2:texels=96, ewa:texels=64"
    );
}

#[test]
fn gpu_forms_follow_the_entries() {
    let form = |s: &str| s.parse::<FilterSpec>().unwrap().gpu();
    let sampler = |linear, levels| GpuForm::Sampler(HardwareSampler { linear, levels });
    assert_eq!(form("nearest").unwrap().form, sampler(false, Levels::Base));
    assert_eq!(form("bilinear").unwrap().form, sampler(true, Levels::Base));
    assert_eq!(form("trilinear").unwrap().form, sampler(true, Levels::Gradients));
    assert_eq!(form("aniso1:box").unwrap(), form("trilinear").unwrap());
    let hw = form("aniso16:box").unwrap();
    assert_eq!((hw.name.as_str(), hw.cpu.name()), ("hw-aniso16", "aniso16:box".to_string()));
    assert_eq!(hw.form, sampler(true, Levels::Quad { anisotropy: 16 }));
    let e = form("ewa:texels=64").unwrap();
    assert_eq!(e.name, "ewa:texels=64");
    assert_eq!(e.form, GpuForm::Wgsl(WgslParams { sigma: 0.5, cut: 3.0, bound: 16.0, budget: 64 }));
    for (bad, why) in [("bicubic", "bicubic"), ("aniso16", "equal weights"), ("aniso32:box", "16 probes")] {
        assert!(form(bad).unwrap_err().contains(why), "{bad}");
    }
    assert_eq!(wgsl_sources().len(), 1);
}

/// The help and error texts the registry generates are the ones the catalogue printed when it
/// was written by hand.
#[test]
fn generated_texts_are_the_hand_written_ones() {
    // Each filter's syntax and description as the hand-written catalogue had them (a filter
    // added to the registry adds its own without changing these).
    let old = [
        ("nearest", "nearest texel of level 0 (1 fetch)"),
        ("bilinear", "bilinear on level 0 (4 fetches)"),
        ("bicubic", "Catmull-Rom bicubic on level 0 (16 fetches)"),
        (
            "trilinear",
            "mip-mapping, level from the longer screen axis' footprint as GPUs choose it (8 fetches)",
        ),
        (
            "anisoN[:box|:sigma=S:cut=C]",
            "up to N trilinear probes (1..=64) along the footprint's major axis, Gaussian-weighted by \
             the pixel filter (default σ=0.5, cut=3) or equal-weighted (box, as GPUs)",
        ),
        (
            "ewa[:sigma=S][:cut=C][:ecc=E][:texels=T]",
            "Heckbert's elliptical weighted average with the pixel filter's Gaussian (default σ=0.5, \
             cut=3), eccentricity clamp E (default 16) and at most T texels (default 216)",
        ),
    ];
    for (i, (syntax, description)) in old.iter().enumerate() {
        assert_eq!((FILTERS[i].syntax().as_str(), FILTERS[i].description), (*syntax, *description));
    }
    // The lists join them as the hand-written code did.
    let syntaxes: Vec<String> = FILTERS.iter().map(Descriptor::syntax).collect();
    let expected = syntaxes.join(", ");
    assert_eq!(super::expected(), expected);
    let lines: Vec<String> = FILTERS.iter().map(|d| format!("{}: {}", d.syntax(), d.description)).collect();
    assert_eq!(FilterSpec::help(), lines.join("; "));
    let pixel = "pixel filter: '{}' is not 'box', 'sigma=S' or 'cut=C' (e.g. sigma=0.45:cut=2)";
    let range = "pixel filter: σ = {} must lie in 0.1..=2 px and cut = {} in 1..=4 σ";
    for (text, reason) in [
        ("aniso0", "probe count N must lie in 1..=64".to_string()),
        ("aniso", "expected anisoN with N a whole number, e.g. aniso16".into()),
        ("anisox", "expected anisoN with N a whole number, e.g. aniso16".into()),
        ("aniso4:foo", "unknown parameter 'foo' (box, sigma=S or cut=C)".into()),
        ("aniso16:box:box", "unknown parameter 'box' (box, sigma=S or cut=C)".into()),
        ("aniso4:sigma=x", pixel.replace("{}", "sigma=x")),
        ("aniso4:sigma=9", range.replacen("{}", "9", 1).replacen("{}", "3", 1)),
        ("ewa:ecc=99", "eccentricity clamp E must lie in 1..=64".into()),
        ("ewa:ecc=x", "ecc=E needs a number".into()),
        ("ewa:texels=5", "texel budget T must lie in 16..=4096".into()),
        ("ewa:texels=1.5", "texels=T needs a whole number".into()),
        ("ewa:box", "unknown parameter 'box' (sigma=S, cut=C, ecc=E or texels=T)".into()),
        ("ewa:16:24", "unknown parameter '16' (sigma=S, cut=C, ecc=E or texels=T)".into()),
        ("ewa:cut=0.5", range.replacen("{}", "0.5", 1).replacen("{}", "0.5", 1)),
        ("trilinear:box", "takes no parameters".into()),
        ("nearest:", "takes no parameters".into()),
        ("gauss", "unknown filter".into()),
        ("NEAREST", "unknown filter".into()),
    ] {
        let e = text.parse::<FilterSpec>().unwrap_err();
        assert_eq!(e.reason, reason, "{text}");
        assert_eq!(e.to_string(), format!("filter '{text}': {reason} (expected {expected})"));
    }
}
