// The thesis's adaptive POM, the GPU twin of `adaptive_pom.rs`: the layer count follows the
// view angle and the complexity map (read nearest at the undisplaced UV), then POM runs with
// that many layers. Parameters 0 and 1: the base MIN and MAX layer counts.
//
// `lerp` (not WGSL's `mix`) keeps the CPU's rounding, so that the truncated layer count
// agrees at the range's ends: `mix(a, b, 1)` need not be `a + (b − a)·1`.

// Exponent of the view-angle factor (thesis: 0.8), as `ANGLE_EXPONENT` in `adaptive_pom.rs`.
const ANGLE_EXPONENT: f32 = 0.8;

fn trace(uv: vec2<f32>, view_ts: vec3<f32>) -> Hit {
    let base_min = f32(param(0u));
    let base_max = f32(param(1u));
    // F = (1 − |V·N|)^0.8 with N = (0, 0, 1); pow(0, y) is left undefined by WGSL.
    let x = max(1.0 - abs(normalize(view_ts).z), 0.0);
    let f = select(0.0, pow(x, ANGLE_EXPONENT), x > 0.0);
    let lo = lerp(base_min, base_max / 2.0, f);
    let hi = lerp(base_min, base_max, f);
    let c = clamp(complexity_at(uv), 0.0, 1.0);
    let layers = max(u32(lerp(lo, hi, c)), 1u);
    let m = layered_march(uv, layer_step(view_ts, layers), layers);
    return interpolate(m, layers);
}
