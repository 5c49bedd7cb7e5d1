//! The stage syntax of the command line: one descriptor per stage of the hybrid frame (its
//! flag, its choices with their parameters and defaults, what it does), from which the CLI's
//! `--help` is generated and each flag's value parsed into the renderer's
//! [`StageConfig`].
//!
//! A choice is `NAME[:P1[:P2]]`; parameters left out from the end take their defaults, e.g.
//! `--reflections rt:4` is 4 bounces at the default max roughness.

use renderlab_hybrid::config::{SSAO_RADIUS, SSAO_SAMPLES};
use renderlab_hybrid::{Ao, Gi, Reflections, Shadows, StageConfig, Translucency};

/// One stage's flag: its name, syntax, default and help.
#[derive(Clone, Copy, Debug)]
pub struct StageFlag {
    /// The flag without dashes, e.g. `reflections`.
    pub flag: &'static str,
    /// The accepted values, e.g. `ssr|rt[:BOUNCES[:MAXROUGH]]`.
    pub syntax: &'static str,
    /// The value when the flag is absent (the all-raster baseline's choice).
    pub default: &'static str,
    /// What the stage computes and what each parameter does.
    pub help: &'static str,
}

/// Ray-traced shadows' default shadow rays per area light.
pub const DEFAULT_SHADOW_SAMPLES: u32 = 1;
/// Ray-traced reflections' default bounces.
pub const DEFAULT_BOUNCES: u32 = 1;
/// Default max roughness of ray-traced reflections and translucency (every surface traced).
pub const DEFAULT_MAX_ROUGHNESS: f32 = 1.0;
/// Ray-traced translucency's default max refraction rays (the thesis's smallest setting).
pub const DEFAULT_REFRACTION_RAYS: u32 = 3;
/// Ray-traced GI's default samples per pixel (the thesis's smallest setting).
pub const DEFAULT_GI_SPP: u32 = 4;
/// Ray-traced AO's default samples per pixel.
pub const DEFAULT_AO_SPP: u32 = 1;

/// Every stage, in the order of the frame's passes.
pub const STAGE_FLAGS: [StageFlag; 5] = [
    StageFlag {
        flag: "shadows",
        syntax: "raster|rt[:SAMPLES]",
        default: "raster",
        help: "Shadows. raster: shadow maps filtered with PCF. rt: a shadow ray (any hit) toward \
               each light per pixel, hard and exact for point, spot and directional lights; \
               SAMPLES stratified rays over each area light give its soft shadow (default 1).",
    },
    StageFlag {
        flag: "reflections",
        syntax: "ssr|rt[:BOUNCES[:MAXROUGH]]",
        default: "ssr",
        help: "Indirect specular. ssr: screen-space reflections (the sky where the march \
               finds nothing). rt: one reflected ray per pixel followed for up to BOUNCES \
               specular bounces (default 1) on surfaces no rougher than MAXROUGH in [0, 1] \
               (default 1); rougher pixels keep the SSR result.",
    },
    StageFlag {
        flag: "translucency",
        syntax: "raster|rt[:RAYS[:MAXROUGH]]",
        default: "raster",
        help: "Translucent surfaces. raster: sorted forward blending without refraction. rt: \
               refraction with Snell's law, Fresnel and total internal reflection, at most RAYS \
               refraction rays per path (default 3; an exhausted path is black), on surfaces \
               no rougher than MAXROUGH (default 1).",
    },
    StageFlag {
        flag: "gi",
        syntax: "off|rt[:SPP]",
        default: "off",
        help: "Indirect diffuse light. off: the raster ambient term (sky radiance times the \
               diffuse albedo). rt: one diffuse bounce with SPP cosine-distributed rays per \
               pixel (default 4).",
    },
    StageFlag {
        flag: "ao",
        syntax: "ssao|off|rt[:SPP[:RADIUS]]",
        default: "ssao",
        help: "Ambient occlusion. ssao: screen-space AO against the G-buffer depth (16 samples, \
               radius 0.5). off: none. rt: SPP occlusion rays per pixel (default 1) of length \
               RADIUS world units (default 0.5, the SSAO radius); AO is the fraction that \
               escapes.",
    },
];

/// The descriptor of `flag`.
pub fn stage_flag(flag: &str) -> Option<&'static StageFlag> {
    STAGE_FLAGS.iter().find(|s| s.flag == flag)
}

/// `--help` text of `flag`: its help, syntax and default.
pub fn help(flag: &str) -> String {
    match stage_flag(flag) {
        Some(s) => format!("{} Syntax: {}. Default: {}.", s.help, s.syntax, s.default),
        None => String::new(),
    }
}

/// Splits `NAME[:P…]` and checks the count of parameters.
fn split<'a>(flag: &str, value: &'a str, max_params: usize) -> Result<(&'a str, Vec<&'a str>), String> {
    let mut parts = value.split(':');
    let name = parts.next().unwrap_or_default();
    let params: Vec<&str> = parts.collect();
    if params.len() > max_params {
        return Err(format!("--{flag} {value:?}: too many parameters (syntax: {})", syntax(flag)));
    }
    Ok((name, params))
}

fn syntax(flag: &str) -> &'static str {
    stage_flag(flag).map_or("", |s| s.syntax)
}

/// Parameter `i` of `params` as a count in 1..=MAX_COUNT, or `default` when absent.
fn count(flag: &str, what: &str, params: &[&str], i: usize, default: u32) -> Result<u32, String> {
    let Some(text) = params.get(i) else { return Ok(default) };
    let max = renderlab_hybrid::config::MAX_COUNT;
    match text.parse::<u32>() {
        Ok(n) if (1..=max).contains(&n) => Ok(n),
        _ => Err(format!("--{flag}: {what} {text:?} must be a whole number in 1..={max}")),
    }
}

/// Parameter `i` as a number in `[lo, hi]` (`hi` excluded from nothing; finite), or `default`.
fn number(
    flag: &str,
    what: &str,
    params: &[&str],
    i: usize,
    lo: f32,
    hi: f32,
    default: f32,
) -> Result<f32, String> {
    let Some(text) = params.get(i) else { return Ok(default) };
    match text.parse::<f32>() {
        Ok(v) if v.is_finite() && v >= lo && v <= hi => Ok(v),
        _ => Err(format!("--{flag}: {what} {text:?} must be a number in [{lo}, {hi}]")),
    }
}

fn unknown(flag: &str, name: &str) -> String {
    format!("--{flag}: unknown choice {name:?} (syntax: {})", syntax(flag))
}

/// Parses `--shadows`.
pub fn parse_shadows(value: &str) -> Result<Shadows, String> {
    let (name, p) = split("shadows", value, 1)?;
    match name {
        "raster" if p.is_empty() => Ok(Shadows::Raster),
        "rt" => Ok(Shadows::RayTraced {
            samples_per_light: count("shadows", "SAMPLES", &p, 0, DEFAULT_SHADOW_SAMPLES)?,
        }),
        _ => Err(unknown("shadows", value)),
    }
}

/// Parses `--reflections`.
pub fn parse_reflections(value: &str) -> Result<Reflections, String> {
    let (name, p) = split("reflections", value, 2)?;
    match name {
        "ssr" if p.is_empty() => Ok(Reflections::ScreenSpace),
        "rt" => Ok(Reflections::RayTraced {
            max_bounces: count("reflections", "BOUNCES", &p, 0, DEFAULT_BOUNCES)?,
            max_roughness: number("reflections", "MAXROUGH", &p, 1, 0.0, 1.0, DEFAULT_MAX_ROUGHNESS)?,
        }),
        _ => Err(unknown("reflections", value)),
    }
}

/// Parses `--translucency`.
pub fn parse_translucency(value: &str) -> Result<Translucency, String> {
    let (name, p) = split("translucency", value, 2)?;
    match name {
        "raster" if p.is_empty() => Ok(Translucency::Raster),
        "rt" => Ok(Translucency::RayTraced {
            max_refraction_rays: count("translucency", "RAYS", &p, 0, DEFAULT_REFRACTION_RAYS)?,
            max_roughness: number("translucency", "MAXROUGH", &p, 1, 0.0, 1.0, DEFAULT_MAX_ROUGHNESS)?,
        }),
        _ => Err(unknown("translucency", value)),
    }
}

/// Parses `--gi`.
pub fn parse_gi(value: &str) -> Result<Gi, String> {
    let (name, p) = split("gi", value, 1)?;
    match name {
        "off" if p.is_empty() => Ok(Gi::Off),
        "rt" => Ok(Gi::RayTraced { samples_per_pixel: count("gi", "SPP", &p, 0, DEFAULT_GI_SPP)? }),
        _ => Err(unknown("gi", value)),
    }
}

/// Parses `--ao`.
pub fn parse_ao(value: &str) -> Result<Ao, String> {
    let (name, p) = split("ao", value, 2)?;
    match name {
        "ssao" if p.is_empty() => Ok(Ao::ScreenSpace { samples: SSAO_SAMPLES, radius: SSAO_RADIUS }),
        "off" if p.is_empty() => Ok(Ao::Off),
        "rt" => Ok(Ao::RayTraced {
            samples_per_pixel: count("ao", "SPP", &p, 0, DEFAULT_AO_SPP)?,
            radius: number("ao", "RADIUS", &p, 1, 1e-6, 1e6, SSAO_RADIUS)?,
        }),
        _ => Err(unknown("ao", value)),
    }
}

/// The configuration of five flag values (any of them `None`: the baseline's choice),
/// validated by the renderer's own rules.
pub fn stage_config(
    shadows: Option<&str>,
    reflections: Option<&str>,
    translucency: Option<&str>,
    gi: Option<&str>,
    ao: Option<&str>,
) -> Result<StageConfig, String> {
    let base = StageConfig::all_raster();
    let config = StageConfig {
        shadows: shadows.map_or(Ok(base.shadows), parse_shadows)?,
        reflections: reflections.map_or(Ok(base.reflections), parse_reflections)?,
        translucency: translucency.map_or(Ok(base.translucency), parse_translucency)?,
        gi: gi.map_or(Ok(base.gi), parse_gi)?,
        ao: ao.map_or(Ok(base.ao), parse_ao)?,
    };
    config.validate()?;
    Ok(config)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_the_all_raster_baseline() {
        let defaults: Vec<&str> = STAGE_FLAGS.iter().map(|s| s.default).collect();
        let c = stage_config(
            Some(defaults[0]),
            Some(defaults[1]),
            Some(defaults[2]),
            Some(defaults[3]),
            Some(defaults[4]),
        )
        .unwrap();
        assert_eq!(c, StageConfig::all_raster());
        assert_eq!(stage_config(None, None, None, None, None).unwrap(), StageConfig::all_raster());
    }

    #[test]
    fn choices_with_and_without_parameters() {
        assert_eq!(parse_shadows("rt:4").unwrap(), Shadows::RayTraced { samples_per_light: 4 });
        assert_eq!(
            parse_reflections("rt:8").unwrap(),
            Reflections::RayTraced { max_bounces: 8, max_roughness: DEFAULT_MAX_ROUGHNESS }
        );
        assert_eq!(
            parse_translucency("rt:20:0.1").unwrap(),
            Translucency::RayTraced { max_refraction_rays: 20, max_roughness: 0.1 }
        );
        assert_eq!(parse_gi("rt:16").unwrap(), Gi::RayTraced { samples_per_pixel: 16 });
        assert_eq!(parse_ao("rt:2:1.5").unwrap(), Ao::RayTraced { samples_per_pixel: 2, radius: 1.5 });
        assert_eq!(parse_ao("off").unwrap(), Ao::Off);
    }

    #[test]
    fn bad_values_name_the_flag() {
        for (flag, bad) in [
            ("shadows", parse_shadows("rt:0").err()),
            ("shadows", parse_shadows("maps").err()),
            ("reflections", parse_reflections("rt:1:2").err()),
            ("reflections", parse_reflections("rt:1:nan").err()),
            ("reflections", parse_reflections("ssr:3").err()),
            ("translucency", parse_translucency("rt:3:0.5:9").err()),
            ("gi", parse_gi("rt:-1").err()),
            ("ao", parse_ao("rt:1:0").err()),
            ("ao", parse_ao("").err()),
        ] {
            let e = bad.expect("refused");
            assert!(e.starts_with(&format!("--{flag}")), "{e}");
            assert!(!e.contains('\n'));
        }
    }

    proptest::proptest! {
        #[test]
        fn parsed_configs_always_validate(n in 0u32..10_000, r in -2.0f32..3.0) {
            for v in [format!("rt:{n}:{r}"), format!("rt:{n}")] {
                if let Ok(c) = parse_reflections(&v) {
                    let cfg = StageConfig { reflections: c, ..StageConfig::all_raster() };
                    proptest::prop_assert!(cfg.validate().is_ok());
                }
                if let Ok(c) = parse_translucency(&v) {
                    let cfg = StageConfig { translucency: c, ..StageConfig::all_raster() };
                    proptest::prop_assert!(cfg.validate().is_ok());
                }
                if let Ok(c) = parse_ao(&v) {
                    let cfg = StageConfig { ao: c, ..StageConfig::all_raster() };
                    proptest::prop_assert!(cfg.validate().is_ok());
                }
            }
        }
    }
}
