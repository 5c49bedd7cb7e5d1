// Ray-traced GI (the CPU's `gi::run`): per opaque pixel with a diffuse albedo, `counts.x`
// stratified cosine-distributed rays about the shading normal rotated by the pixel's random
// shift (rays below the face are skipped but still count in the mean); a hit gives its
// emission and direct light (one random sample per area light), its roughness raised to at
// least `values.x` (the regularisation), an escaping ray the sky. `ambient.xyz` is the mean
// times the diffuse albedo; `ambient.w` is 1 (no occlusion) for the AO pass after it.

@group(1) @binding(1) var<storage, read_write> gbuf: array<GPoint>;
@group(1) @binding(4) var<storage, read_write> ambient: array<vec4f>;

@compute @workgroup_size(8, 8, 1)
fn rt_gi_main(@builtin(global_invocation_id) id: vec3u) {
    if id.x >= frame.size.x || id.y >= frame.size.y {
        return;
    }
    let i = pixel_index(id.x, id.y);
    let sp = unpack_surface(gbuf[i]);
    ambient[i] = vec4f(0.0, 0.0, 0.0, 1.0);
    if !gp_valid(sp) {
        return;
    }
    let albedo = diffuse_albedo(sp, -view_dir(id.x, id.y));
    if all(albedo == vec3f(0.0)) {
        return;
    }
    var rng = rng_new(rtp.counts.zw, i);
    let shift = rng_vec2(&rng);
    let n = max(rtp.counts.x, 1u);
    var sum = vec3f(0.0);
    var rays = 0u;
    for (var s = 0u; s < n; s++) {
        let dir = frame_to_world(sp.n.xyz, cosine_hemisphere(stratified(s, n, shift)));
        if dot(dir, sp.g.xyz) <= 0.0 {
            continue;
        }
        rays++;
        var hit = trace_surface(offset_origin(sp, dir), dir);
        if !gp_valid(hit) {
            sum += frame.sky.xyz;
        } else {
            hit.g.w = max(hit.g.w, rtp.values.x);
            sum += hit.e.xyz + direct_light(hit, -dir, 1u, &rng, &rays);
        }
    }
    ambient[i] = vec4f(albedo * sum / f32(n), 1.0);
    count_rays(rays);
}
