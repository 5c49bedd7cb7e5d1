// POM with soft self-shadowing, the GPU twin of `pom_shadow.rs`: POM's trace (parameter 0:
// LAYERS); the frame then marches toward the light from the hit with the technique's shadow
// samples (parameter 1, passed to the frame as `ShadowMode::Soft`), in `shadow.wgsl`.
fn trace(uv: vec2<f32>, view_ts: vec3<f32>) -> Hit {
    let layers = param(0u);
    let m = layered_march(uv, layer_step(view_ts, layers), layers);
    return interpolate(m, layers);
}
