// Ray-traced ambient occlusion (the CPU's `ao::openness`): per opaque pixel, `samples`
// stratified cosine-distributed rays of length `radius` about the shading normal, rotated by
// the pixel's random shift; AO is the fraction that escapes. Rays below the geometric
// surface count as occluded without a ray. Follows the ray tracer's prelude (group 1), the
// random streams and the surface record.

struct AoParams {
    width: u32,
    height: u32,
    samples: u32,
    mask: u32,
    base: vec2<u32>,
    radius: f32,
    pad: u32,
}

@group(0) @binding(0) var<storage, read> surfaces: array<RtSurface>;
@group(0) @binding(1) var<storage, read_write> ao_out: array<f32>;
@group(0) @binding(2) var<uniform> ao: AoParams;
@group(0) @binding(3) var<storage, read_write> ao_rays: atomic<u32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= ao.width || id.y >= ao.height {
        return;
    }
    let i = id.y * ao.width + id.x;
    let s = surfaces[i];
    if !surface_present(s) {
        ao_out[i] = 1.0;
        return;
    }
    var rng = rng_new(ao.base, i);
    let shift = rng_vec2(&rng);
    let n = max(ao.samples, 1u);
    var open = 0u;
    var traced = 0u;
    for (var k = 0u; k < n; k++) {
        let dir = frame_to_world(s.normal.xyz, cosine_hemisphere(stratified(k, n, shift)));
        if dot(dir, s.geometric.xyz) <= 0.0 {
            continue;
        }
        traced++;
        if !rt_any(offset_origin(s, dir), dir, 0.0, ao.radius * SHADOW_END, ao.mask) {
            open++;
        }
    }
    ao_out[i] = f32(open) / f32(n);
    atomicAdd(&ao_rays, traced);
}
