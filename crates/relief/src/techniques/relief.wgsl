// Relief mapping, the GPU twin of `relief.rs`: a linear search for the first layer under
// the surface, then a binary search between the last point above and the first point below.
// Parameters 0 and 1: LINEAR and BINARY steps.
fn trace(uv: vec2<f32>, view_ts: vec3<f32>) -> Hit {
    return relief_trace(uv, view_ts, param(0u), param(1u));
}
