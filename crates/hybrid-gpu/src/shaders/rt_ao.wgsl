// Ray-traced ambient occlusion (the CPU's `ao::openness`): per opaque pixel, `counts.x`
// stratified cosine-distributed rays of length `values.x` about the shading normal, rotated
// by the pixel's random shift; AO (`ambient.w`) is the fraction that escapes. Rays below the
// geometric surface count as occluded without a ray.

@group(1) @binding(1) var<storage, read_write> gbuf: array<GPoint>;
@group(1) @binding(4) var<storage, read_write> ambient: array<vec4f>;

@compute @workgroup_size(8, 8, 1)
fn rt_ao_main(@builtin(global_invocation_id) id: vec3u) {
    if id.x >= frame.size.x || id.y >= frame.size.y {
        return;
    }
    let i = pixel_index(id.x, id.y);
    let sp = unpack_surface(gbuf[i]);
    if !gp_valid(sp) {
        return;
    }
    var rng = rng_new(rtp.counts.zw, i);
    let shift = rng_vec2(&rng);
    let n = max(rtp.counts.x, 1u);
    let radius = rtp.values.x;
    var open = 0u;
    var traced = 0u;
    for (var k = 0u; k < n; k++) {
        let dir = frame_to_world(sp.n.xyz, cosine_hemisphere(stratified(k, n, shift)));
        if dot(dir, sp.g.xyz) <= 0.0 {
            continue;
        }
        traced++;
        if !rt_any(offset_origin(sp, dir), dir, 0.0, radius * SHADOW_END, 0xffu) {
            open++;
        }
    }
    ambient[i].w = f32(open) / f32(n);
    count_rays(traced);
}
