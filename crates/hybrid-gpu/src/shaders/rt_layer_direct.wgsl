// A translucent layer's direct light with ray-traced visibility (the CPU's forward pass with
// `RayTracedVisibility`): the raster pass's strata centres, each sample's visibility from a
// shadow ray.
fn layer_direct(sp: Surface, v: vec3f) -> vec3f {
    var sum = vec3f(0.0);
    for (var li = 0u; li < frame.size.z; li++) {
        let l = lights[li];
        var n = 1u;
        if light_kind(l) == 3u {
            n = max(frame.size.w, 1u);
        }
        let count = n * n;
        var light_sum = vec3f(0.0);
        for (var s = 0u; s < count; s++) {
            let u = vec2f((f32(s % n) + 0.5) / f32(n), (f32(s / n) + 0.5) / f32(n));
            let ls = light_sample(l, sp.p.xyz, u);
            if all(ls.radiance == vec3f(0.0)) {
                continue;
            }
            let f = brdf_eval(sp, v, ls.to_light);
            if all(f == vec3f(0.0)) {
                continue;
            }
            if light_visible(sp, ls) {
                light_sum += f * ls.radiance;
            }
        }
        sum += light_sum / f32(count);
    }
    return sum;
}
