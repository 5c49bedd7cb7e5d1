// The path-traced reference (renderlab-hybrid's `reference`): one invocation per pixel runs
// `count` paths of one half, continuing that pixel's random stream where the last batch left
// it, and adds their terms to the half's sums. Written with the operations of the CPU's
// `trace_from`, `area_lights_on_segment`, `direct_light_parts` (one sample per light),
// `openness` and `unshadowed_direct_parts` (and `sample_bsdf` in `reference_bsdf.wgsl`),
// drawing the same random numbers in the same order, so that a GPU path follows the CPU's
// path until rounding parts them. Follows the ray tracer's prelude (group 2), COMMON
// (group 0 the scene, group 1 the frame's constants), the random streams, SHADING, SURFACE,
// the header's constants (SHADOW_END, SMOOTH_FOR_LIGHTS, SHARE_U) and `reference_bsdf.wgsl`.

struct RefParams {
    first: u32,          // index of the batch's first path in the half
    count: u32,          // paths in this batch
    half: u32,           // paths per pixel in the half (the AO rays' count too)
    max_depth: u32,
    roulette_after: u32,
    mask: u32,
    regularize: f32,
    ao_radius: f32,
    base: vec2<u32>,     // the half's path stream (Rng::stream_base)
    ao_base: vec2<u32>,  // the half's AO stream
}

@group(3) @binding(0) var<uniform> rp: RefParams;
// Per pixel, SUMS floats: the five radiance terms' sums (emitted, direct, diffuse, specular,
// translucent; xyz each), then the area lights' share of the first surface's direct light.
@group(3) @binding(1) var<storage, read_write> sums: array<f32>;
// Per pixel, STATE words: the path stream's state (low, high), rays traced (low, high),
// AO rays that escaped, the pixel's kind.
@group(3) @binding(2) var<storage, read_write> state: array<u32>;

const SUMS: u32 = 16u;
const STATE: u32 = 6u;
const KIND_SKY: u32 = 0u;
const KIND_OPAQUE: u32 = 1u;
const KIND_TRANSLUCENT: u32 = 2u;
const ROUTE_CAMERA: u32 = 0u;
const ROUTE_TRANSLUCENT: u32 = 1u;
const ROUTE_OPAQUE: u32 = 2u;

// ---- lights ----

// `stratified(0, 1, shift)` as the CPU computes it in f64 (exact in f32 written this way).
fn one_point(shift: vec2f) -> vec2f {
    return vec2f(select(shift.x - 0.5, shift.x + 0.5, shift.x < 0.5), shift.y);
}

// `direct_light_parts(.., 1, with_area, ..).total`: one sample per light behind one shadow
// ray, every light drawing its shift whether or not it is lit.
fn direct_light(sp: Surface, v: vec3f, with_area: bool, rng: ptr<function, vec2<u32>>, rays: ptr<function, u32>) -> vec3f {
    var total = vec3f(0.0);
    for (var li = 0u; li < frame.size.z; li++) {
        let l = lights[li];
        let kind = light_kind(l);
        if !with_area && kind == 3u {
            continue;
        }
        let shift = rng_vec2(rng);
        let s = light_sample(l, sp.p.xyz, one_point(shift));
        if all(s.radiance == vec3f(0.0)) {
            continue;
        }
        let f = brdf_eval(sp, v, s.to_light);
        if all(f == vec3f(0.0)) {
            continue;
        }
        *rays += 1u;
        var t_max = F32_MAX;
        if kind != 2u {
            t_max = s.distance * SHADOW_END;
        }
        if !rt_any(surface_offset(sp, s.to_light), s.to_light, 0.0, t_max, rp.mask) {
            total += f * s.radiance;
        }
    }
    return total;
}

// `area_lights_on_segment`: the radiance of the area lights whose emitting side the ray
// passes through before `t_max`.
fn area_on_segment(origin: vec3f, dir: vec3f, t_max: f32) -> vec3f {
    var sum = vec3f(0.0);
    for (var li = 0u; li < frame.size.z; li++) {
        let l = lights[li];
        if light_kind(l) != 3u {
            continue;
        }
        let hu = l.half_u_inner.xyz;
        let hv = l.half_v_outer.xyz;
        let n = cross(hu, hv);
        let d_n = dot(dir, n);
        if d_n >= 0.0 {
            continue;
        }
        let t = dot(l.position_kind.xyz - origin, n) / d_n;
        if !(t > 0.0 && t < t_max) {
            continue;
        }
        let q = origin + dir * t - l.position_kind.xyz;
        let a = dot(q, hu) / dot(hu, hu);
        let b = dot(q, hv) / dot(hv, hv);
        if abs(a) <= 1.0 && abs(b) <= 1.0 {
            sum += l.color_range.xyz * l.direction_intensity.w;
        }
    }
    return sum;
}

// ---- one path (`PathTracer::trace_from`) ----

struct PathOut {
    emitted: vec3f,
    direct: vec3f,
    diffuse: vec3f,
    specular: vec3f,
    translucent: vec3f,
}

fn add_route(out: ptr<function, PathOut>, route: u32, share: vec3f, c: vec3f) {
    if route == ROUTE_CAMERA {
        (*out).emitted += c;
    } else if route == ROUTE_TRANSLUCENT {
        (*out).translucent += c;
    } else {
        (*out).diffuse += c * share;
        (*out).specular += c * (vec3f(1.0) - share);
    }
}

fn lobe_share(d: f32, w: f32) -> f32 {
    if w > 0.0 {
        return clamp(d / w, 0.0, 1.0);
    }
    return 0.0;
}

fn trace_path(eye: vec3f, dir0: vec3f, first: RtHit, rng: ptr<function, vec2<u32>>, rays: ptr<function, u32>) -> PathOut {
    var out = PathOut(vec3f(0.0), vec3f(0.0), vec3f(0.0), vec3f(0.0), vec3f(0.0));
    var route = ROUTE_CAMERA;
    var share = vec3f(0.0);
    var origin = eye;
    var dir = dir0;
    var throughput = vec3f(1.0);
    var min_roughness = 0.0;
    var gathers_area = false;
    var opaque_first = false;
    for (var depth = 0u; depth < rp.max_depth; depth++) {
        var hit = first;
        if depth > 0u {
            *rays += 1u;
            hit = rt_closest(origin, dir, 0.0, F32_MAX, rp.mask);
        }
        let found = hit.instance != RT_NO_HIT;
        if gathers_area {
            var t_max = F32_MAX;
            if found {
                t_max = hit.t;
            }
            let c = throughput * area_on_segment(origin, dir, t_max);
            if depth == 1u && route == ROUTE_OPAQUE {
                out.direct += c;
            } else {
                add_route(&out, route, share, c);
            }
        }
        if !found {
            add_route(&out, route, share, throughput * frame.sky.xyz);
            break;
        }
        var sp = surface_from_hit(hit.instance, hit.primitive, vec2f(hit.u, hit.v), dir);
        sp.g.w = max(sp.g.w, min_roughness);
        if rp.regularize > 0.0 && sp.g.w >= rp.regularize {
            min_roughness = rp.regularize;
        }
        let v = -dir;
        gathers_area = sp.g.w < SMOOTH_FOR_LIGHTS;
        let direct = direct_light(sp, v, !gathers_area, rng, rays);
        if depth == 0u {
            if sp.e.w > 0.0 {
                route = ROUTE_TRANSLUCENT;
                add_route(&out, route, share, sp.e.xyz + direct);
            } else {
                opaque_first = true;
                out.emitted += sp.e.xyz;
                out.direct += direct;
            }
        } else {
            add_route(&out, route, share, throughput * (sp.e.xyz + direct));
        }
        let sc = sample_bsdf(sp, v, rng);
        if !sc.ok {
            break;
        }
        if depth == 0u && opaque_first {
            route = ROUTE_OPAQUE;
            share = vec3f(lobe_share(sc.diffuse.x, sc.weight.x), lobe_share(sc.diffuse.y, sc.weight.y),
                lobe_share(sc.diffuse.z, sc.weight.z));
        }
        throughput *= sc.weight;
        if !all_finite(throughput) || all(throughput == vec3f(0.0)) {
            break;
        }
        if depth + 1u >= rp.roulette_after {
            let q = min(max_el(throughput), 0.95);
            if rng_f32(rng) >= q {
                break;
            }
            throughput /= q;
        }
        origin = surface_offset(sp, sc.dir);
        dir = sc.dir;
    }
    return out;
}

// ---- the first surface's own facts (`PathTracer::first_surface`) ----

fn luminance(c: vec3f) -> f32 {
    return dot(c, vec3f(0.2126, 0.7152, 0.0722));
}

// The area lights' share of the unshadowed direct light (`unshadowed_direct_parts`, 4
// fixed points per area light).
fn area_share(sp: Surface, v: vec3f) -> f32 {
    var total = vec3f(0.0);
    var area = vec3f(0.0);
    for (var li = 0u; li < frame.size.z; li++) {
        let l = lights[li];
        let is_area = light_kind(l) == 3u;
        var n = 1u;
        if is_area {
            n = 4u;
        }
        var acc = vec3f(0.0);
        for (var i = 0u; i < n; i++) {
            var u = vec2f(0.5, 0.0);
            if is_area {
                u = SHARE_U[i];
            }
            let s = light_sample(l, sp.p.xyz, u);
            acc += brdf_eval(sp, v, s.to_light) * s.radiance;
        }
        let c = acc / f32(n);
        total += c;
        if is_area {
            area += c;
        }
    }
    let t = luminance(total);
    if t > 0.0 {
        return luminance(area) / t;
    }
    return 0.0;
}

// The AO rays `first .. first + count` of `half` (`ao::openness`): how many escape.
fn ao_open(sp: Surface, pixel: u32, rays: ptr<function, u32>) -> u32 {
    var rng = rng_new(rp.ao_base, pixel);
    let shift = rng_vec2(&rng);
    let n = max(rp.half, 1u);
    var open = 0u;
    for (var k = rp.first; k < min(rp.first + rp.count, n); k++) {
        let dir = frame_to_world(sp.n.xyz, cosine_hemisphere(stratified(k, n, shift)));
        if dot(dir, sp.g.xyz) <= 0.0 {
            continue;
        }
        *rays += 1u;
        if !rt_any(surface_offset(sp, dir), dir, 0.0, rp.ao_radius * SHADOW_END, rp.mask) {
            open++;
        }
    }
    return open;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= frame.size.x || id.y >= frame.size.y {
        return;
    }
    let i = id.y * frame.size.x + id.x;
    let eye = frame.eye.xyz;
    let dir = view_dir(id.x, id.y);
    // The pixel-centre ray every path starts with (counted once per pixel and half).
    let first = rt_closest(eye, dir, 0.0, F32_MAX, rp.mask);
    let sb = i * STATE;
    let fb = i * SUMS;
    var rng: vec2<u32>;
    var rays = 0u;
    var kind = KIND_SKY;
    var first_sp: Surface;
    if first.instance != RT_NO_HIT && rp.max_depth > 0u {
        first_sp = surface_from_hit(first.instance, first.primitive, vec2f(first.u, first.v), dir);
        kind = select(KIND_OPAQUE, KIND_TRANSLUCENT, first_sp.e.w > 0.0);
    }
    if rp.first == 0u {
        rng = rng_new(rp.base, i);
        rays = 1u;
        var share = 0.0;
        if kind == KIND_OPAQUE {
            share = area_share(first_sp, -dir);
        }
        sums[fb + 15u] = share;
        state[sb + 4u] = 0u;
        state[sb + 5u] = kind;
    } else {
        rng = vec2<u32>(state[sb], state[sb + 1u]);
    }
    var e = vec3f(sums[fb], sums[fb + 1u], sums[fb + 2u]);
    var d = vec3f(sums[fb + 3u], sums[fb + 4u], sums[fb + 5u]);
    var df = vec3f(sums[fb + 6u], sums[fb + 7u], sums[fb + 8u]);
    var sp = vec3f(sums[fb + 9u], sums[fb + 10u], sums[fb + 11u]);
    var tr = vec3f(sums[fb + 12u], sums[fb + 13u], sums[fb + 14u]);
    for (var s = 0u; s < rp.count; s++) {
        let p = trace_path(eye, dir, first, &rng, &rays);
        e += p.emitted;
        d += p.direct;
        df += p.diffuse;
        sp += p.specular;
        tr += p.translucent;
    }
    sums[fb] = e.x;
    sums[fb + 1u] = e.y;
    sums[fb + 2u] = e.z;
    sums[fb + 3u] = d.x;
    sums[fb + 4u] = d.y;
    sums[fb + 5u] = d.z;
    sums[fb + 6u] = df.x;
    sums[fb + 7u] = df.y;
    sums[fb + 8u] = df.z;
    sums[fb + 9u] = sp.x;
    sums[fb + 10u] = sp.y;
    sums[fb + 11u] = sp.z;
    sums[fb + 12u] = tr.x;
    sums[fb + 13u] = tr.y;
    sums[fb + 14u] = tr.z;
    if kind == KIND_OPAQUE {
        state[sb + 4u] += ao_open(first_sp, i, &rays);
    }
    state[sb] = rng.x;
    state[sb + 1u] = rng.y;
    let lo = state[sb + 2u] + rays;
    state[sb + 3u] += select(0u, 1u, lo < rays);
    state[sb + 2u] = lo;
}
