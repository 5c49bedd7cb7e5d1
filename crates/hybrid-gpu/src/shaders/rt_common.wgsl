// What every ray-traced stage of the frame shares: its parameters and the frame's ray
// counters (group 3), and how a secondary ray leaves a surface. Follows the ray tracer's
// prelude (group 2), common.wgsl, shading.wgsl, surface.wgsl and random.wgsl; rt/pass.rs puts
// SHADOW_END (the CPU's: a shadow segment stops this fraction short of its length) before it.

struct RtParams {
    // x: samples (rays per pixel or per area light, or bounces), y: this stage's counter,
    // zw: the stage's random-stream base (Rng::stream_base, low and high words).
    counts: vec4u,
    // x: a length or a roughness limit, y: a second parameter, zw: unused.
    values: vec4f,
}

@group(3) @binding(0) var<uniform> rtp: RtParams;
@group(3) @binding(1) var<storage, read_write> rt_rays: array<atomic<u32>>;

// ShadingPoint::offset_origin: the point a secondary ray toward `dir` leaves from, pushed off
// along the geometric normal on dir's side by 1e-4 · (1 + the position's largest magnitude).
fn offset_origin(s: Surface, dir: vec3f) -> vec3f {
    let p = s.p.xyz;
    let scale = 1e-4 * (1.0 + max(abs(p.x), max(abs(p.y), abs(p.z))));
    let n = select(-s.g.xyz, s.g.xyz, dot(dir, s.g.xyz) >= 0.0);
    return p + n * scale;
}

// Accel::occluded toward a light sample: whether nothing lies between the surface and the
// sample (all surfaces opaque, translucent ones included, as on the CPU).
fn light_visible(sp: Surface, ls: LightSample) -> bool {
    return !rt_any(offset_origin(sp, ls.to_light), ls.to_light, 0.0, ls.distance * SHADOW_END, 0xffu);
}

fn count_rays(n: u32) {
    if n > 0u {
        atomicAdd(&rt_rays[rtp.counts.y], n);
    }
}
