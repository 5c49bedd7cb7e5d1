// Ray-traced shadows (the CPU's `shadows::run` through `lighting::direct_light`): per opaque
// pixel and light, one shadow ray for a punctual light, `counts.x` stratified samples over an
// area light rotated by the pixel's random shift (drawn for every light, as on the CPU);
// `direct = Σ brdf · radiance · visible / n`.

@group(1) @binding(1) var<storage, read_write> gbuf: array<GPoint>;
@group(1) @binding(3) var<storage, read_write> direct: array<vec4f>;

@compute @workgroup_size(8, 8, 1)
fn rt_shadows_main(@builtin(global_invocation_id) id: vec3u) {
    if id.x >= frame.size.x || id.y >= frame.size.y {
        return;
    }
    let i = pixel_index(id.x, id.y);
    let sp = unpack_surface(gbuf[i]);
    if !gp_valid(sp) {
        direct[i] = vec4f(0.0);
        return;
    }
    let v = -view_dir(id.x, id.y);
    var rng = rng_new(rtp.counts.zw, i);
    var sum = vec3f(0.0);
    var traced = 0u;
    for (var li = 0u; li < frame.size.z; li++) {
        let l = lights[li];
        var n = 1u;
        if light_kind(l) == 3u {
            n = max(rtp.counts.x, 1u);
        }
        let shift = rng_vec2(&rng);
        var acc = vec3f(0.0);
        for (var s = 0u; s < n; s++) {
            let ls = light_sample(l, sp.p.xyz, stratified(s, n, shift));
            if all(ls.radiance == vec3f(0.0)) {
                continue;
            }
            let f = brdf_eval(sp, v, ls.to_light);
            if all(f == vec3f(0.0)) {
                continue;
            }
            traced++;
            if light_visible(sp, ls) {
                acc += f * ls.radiance;
            }
        }
        sum += acc / f32(n);
    }
    direct[i] = vec4f(sum, 0.0);
    count_rays(traced);
}
