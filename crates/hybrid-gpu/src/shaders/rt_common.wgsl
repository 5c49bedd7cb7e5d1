// What every ray-traced stage of the frame shares: its parameters and the frame's ray
// counters (group 3), how a secondary ray leaves a surface, what it finds, and the shading
// of a hit (`lighting.rs`: direct light with shadow rays, the ambient term). Follows the ray tracer's
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

// Accel::surface: the nearest surface along the unit `dir` from `origin`, resolved
// (`surface_from_hit`); invalid (`gp_valid` false) where the ray escapes.
fn trace_surface(origin: vec3f, dir: vec3f) -> Surface {
    let h = rt_closest(origin, dir, 0.0, F32_MAX, 0xffu);
    var s: Surface;
    if h.instance == RT_NO_HIT {
        return s;
    }
    return surface_from_hit(h.instance, h.primitive, vec2f(h.u, h.v), dir);
}

// Accel::is_translucent: whether scene instance `instance` has a translucent material.
fn instance_translucent(instance: u32) -> bool {
    return materials[instances[instance].refs.z].transmission_ior.x > 0.0;
}

// lighting::direct_light: direct light at `sp` seen from the unit `v`, for every light
// `brdf · radiance · visible` with one shadow ray per sample; a punctual light takes one
// sample, an area light `area_samples` stratified samples rotated by a shift drawn from
// `rng` (drawn for every light, as on the CPU). Adds the shadow rays traced to `rays`.
fn direct_light(sp: Surface, v: vec3f, area_samples: u32, rng: ptr<function, vec2u>, rays: ptr<function, u32>) -> vec3f {
    var sum = vec3f(0.0);
    for (var li = 0u; li < frame.size.z; li++) {
        let l = lights[li];
        var n = 1u;
        if light_kind(l) == 3u {
            n = max(area_samples, 1u);
        }
        let shift = rng_vec2(rng);
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
            *rays += 1u;
            if light_visible(sp, ls) {
                acc += f * ls.radiance;
            }
        }
        sum += acc / f32(n);
    }
    return sum;
}

// lighting::ambient: the raster pipeline's ambient term, sky × diffuse albedo.
fn ambient_term(sp: Surface, v: vec3f) -> vec3f {
    return frame.sky.xyz * diffuse_albedo(sp, v);
}

// Adds n to this stage's 64-bit ray count: two words (low, high), the carry added to the high
// word by the one invocation whose addition wrapped the low word.
fn count_rays(n: u32) {
    if n > 0u {
        let slot = 2u * rtp.counts.y;
        let old = atomicAdd(&rt_rays[slot], n);
        if old > 0xffffffffu - n {
            atomicAdd(&rt_rays[slot + 1u], 1u);
        }
    }
}
