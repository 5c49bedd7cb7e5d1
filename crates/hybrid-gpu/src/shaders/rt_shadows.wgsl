// Ray-traced shadows (the CPU's `shadows::run`): `direct_light` (rt_common.wgsl) of every
// opaque pixel: per light, one shadow ray for a punctual light, `counts.x` stratified samples over an
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
    var traced = 0u;
    let sum = direct_light(sp, v, rtp.counts.x, &rng, &traced);
    direct[i] = vec4f(sum, 0.0);
    count_rays(traced);
}
