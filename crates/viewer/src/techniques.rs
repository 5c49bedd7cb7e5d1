//! Choosing techniques from the keyboard: keys 1–6 are the thesis's six techniques, ←/→ step
//! through every technique of the registry, ↑/↓ change the layer count within
//! [`MIN_LAYERS`]..=[`MAX_LAYERS`], and the min/max sliders set an adaptive technique's range.
//! Everything is derived from the registry's descriptors (names, parameter names, defaults),
//! so a technique added there appears here without an edit.

use renderlab_relief::techniques::DESCRIPTORS;
use renderlab_relief::Technique;

/// The thesis's six techniques, keys 1 to 6, by registry name: basic texturing, normal
/// mapping, parallax mapping, steep parallax mapping, POM and the thesis's adaptive POM.
pub const THESIS_SIX: [&str; 6] = ["basic", "normal", "parallax", "steep", "pom", "adaptive"];
/// Fewest layers ↓ reaches.
pub const MIN_LAYERS: u32 = 1;
/// Most layers ↑ reaches (the thesis's limit).
pub const MAX_LAYERS: u32 = 50;

/// The names of the parameters that ↑/↓ set: the march's layer or step count, and an
/// adaptive technique's maximum.
const LAYER_PARAMS: [&str; 4] = ["LAYERS", "STEPS", "LINEAR", "MAX"];

/// The technique named `name` at its defaults (`None` when the registry has no such name).
pub fn by_name(name: &str) -> Option<Technique> {
    Technique::parse(name).ok()
}

/// Thesis technique `key` (1–6) at its defaults.
pub fn thesis(key: usize) -> Option<Technique> {
    THESIS_SIX.get(key.checked_sub(1)?).and_then(|n| by_name(n))
}

/// The registry's technique `steps` entries after (or, negative, before) `current`'s, at its
/// defaults, wrapping around.
pub fn step(current: Technique, steps: i32) -> Technique {
    let n = DESCRIPTORS.len() as i32;
    let at = DESCRIPTORS.iter().position(|d| d.name == current.descriptor().name).unwrap_or(0) as i32;
    let next = (at + steps).rem_euclid(n) as usize;
    by_name(DESCRIPTORS[next].name).unwrap_or(current)
}

/// `technique` with parameter `param` set to `value` (clamped to the parameter's range by
/// rejection: an out-of-range value leaves the technique as it is).
pub fn with_param(technique: Technique, param: &str, value: u32) -> Technique {
    let d = technique.descriptor();
    let Some(index) = d.params.iter().position(|p| p.name == param) else {
        return technique;
    };
    let name = technique.name();
    let mut parts: Vec<String> = name.split(':').map(str::to_string).collect();
    if parts.len() != d.params.len() + 1 {
        return technique;
    }
    parts[index + 1] = value.to_string();
    Technique::parse(&parts.join(":")).unwrap_or(technique)
}

/// The value of `technique`'s parameter `param`, if it has one of that name.
pub fn param(technique: Technique, param: &str) -> Option<u32> {
    let index = technique.descriptor().params.iter().position(|p| p.name == param)?;
    technique.params().get(index).copied()
}

/// The layer count ↑/↓ change (the first of `LAYER_PARAMS` the technique has); `None` for
/// a technique without one (basic texturing, normal mapping, parallax mapping).
pub fn layers(technique: Technique) -> Option<u32> {
    LAYER_PARAMS.iter().find_map(|p| param(technique, p))
}

/// `technique` with its layer count moved by `delta`, within [`MIN_LAYERS`]..=[`MAX_LAYERS`];
/// an adaptive technique's minimum follows its maximum down.
pub fn add_layers(technique: Technique, delta: i32) -> Technique {
    let Some((name, current)) = LAYER_PARAMS.iter().find_map(|p| param(technique, p).map(|v| (*p, v))) else {
        return technique;
    };
    let target = (current as i32 + delta).clamp(MIN_LAYERS as i32, MAX_LAYERS as i32) as u32;
    let mut t = technique;
    if name == "MAX" {
        if let Some(min) = param(t, "MIN") {
            if min > target {
                t = with_param(t, "MIN", target);
            }
        }
    }
    with_param(t, name, target)
}

/// `technique` with an adaptive range `min..=max` (both clamped to the layer limits, `min`
/// at most `max`); a technique without `MIN`/`MAX` parameters is returned as it is.
pub fn with_range(technique: Technique, min: u32, max: u32) -> Technique {
    if param(technique, "MIN").is_none() || param(technique, "MAX").is_none() {
        return technique;
    }
    let max = max.clamp(MIN_LAYERS, MAX_LAYERS);
    let min = min.clamp(MIN_LAYERS, max);
    // Lower the minimum first so that the pair stays valid in between.
    let t = with_param(technique, "MIN", MIN_LAYERS);
    let t = with_param(t, "MAX", max);
    with_param(t, "MIN", min)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_one_to_six_are_the_thesis_techniques() {
        let names: Vec<String> = (1..=6).map(|k| thesis(k).unwrap().descriptor().name.to_string()).collect();
        assert_eq!(names, THESIS_SIX);
        assert!(thesis(0).is_none() && thesis(7).is_none());
    }

    #[test]
    fn the_arrows_visit_every_registry_technique_and_wrap() {
        let start = thesis(1).unwrap();
        let mut t = start;
        let mut seen = vec![];
        for _ in 0..DESCRIPTORS.len() {
            seen.push(t.descriptor().name);
            t = step(t, 1);
        }
        assert_eq!(t, start);
        assert_eq!(seen, DESCRIPTORS.iter().map(|d| d.name).collect::<Vec<_>>());
        assert_eq!(step(step(start, 1), -1), start);
    }

    #[test]
    fn layers_move_within_the_limits() {
        let pom = by_name("pom:32").unwrap();
        assert_eq!(layers(add_layers(pom, 2)), Some(34));
        assert_eq!(layers(add_layers(pom, 100)), Some(MAX_LAYERS));
        assert_eq!(layers(add_layers(pom, -100)), Some(MIN_LAYERS));
        let basic = by_name("basic").unwrap();
        assert_eq!(add_layers(basic, 1), basic);
        assert_eq!(layers(basic), None);
    }

    #[test]
    fn an_adaptive_range_stays_ordered() {
        let a = by_name("adaptive:4:32").unwrap();
        let lowered = add_layers(a, -30);
        assert_eq!((param(lowered, "MIN"), param(lowered, "MAX")), (Some(2), Some(2)));
        let ranged = with_range(a, 40, 10);
        assert_eq!((param(ranged, "MIN"), param(ranged, "MAX")), (Some(10), Some(10)));
        let ranged = with_range(a, 8, 48);
        assert_eq!((param(ranged, "MIN"), param(ranged, "MAX")), (Some(8), Some(48)));
    }
}
