// POM with horizon self-shadowing, the GPU twin of `pom_horizon.rs`: POM's trace (parameter
// 0: LAYERS); the frame then marches the horizon toward the light from the hit with at most
// the technique's STEPS samples (parameter 1, passed to the frame as `ShadowMode::Horizon`),
// in `shadow.wgsl`'s `horizon_shadow`.
fn trace(uv: vec2<f32>, view_ts: vec3<f32>) -> Hit {
    let layers = param(0u);
    let m = layered_march(uv, layer_step(view_ts, layers), layers);
    return interpolate(m, layers);
}
