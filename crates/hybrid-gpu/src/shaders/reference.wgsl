// The path-traced reference (renderlab-hybrid's `reference`): one invocation per pixel runs
// `count` paths of one half, continuing that pixel's random stream where the last batch left
// it, and adds their terms to the half's sums. Written with the operations of the CPU's
// `trace_from`, `sample_bsdf`, `area_lights_on_segment`, `direct_light_parts` (one sample
// per light), `openness` and `unshadowed_direct_parts`, drawing the same random numbers in
// the same order, so that a GPU path follows the CPU's path until rounding parts them.
// Follows the ray tracer's prelude (group 2), COMMON (group 0 the scene, group 1 the
// frame's constants), the random streams, SHADING, SURFACE and the header's constants
// (SHADOW_END, SMOOTH_FOR_LIGHTS, SHARE_U).

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

// ---- geometry helpers (renderlab_scene::sampling) ----

struct Basis {
    t: vec3f,
    b: vec3f,
    n: vec3f,
}

// `Frame::new`: glam's `any_orthonormal_pair` about the unit `n`.
fn basis_of(n: vec3f) -> Basis {
    let sign = select(1.0, -1.0, (bitcast<u32>(n.z) & 0x80000000u) != 0u);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    return Basis(vec3f(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x), vec3f(b, sign + n.y * n.y * a, -n.y), n);
}

fn to_world(f: Basis, v: vec3f) -> vec3f {
    return f.t * v.x + f.b * v.y + f.n * v.z;
}

fn to_local(f: Basis, v: vec3f) -> vec3f {
    return vec3f(dot(v, f.t), dot(v, f.b), dot(v, f.n));
}

fn max_el(v: vec3f) -> f32 {
    return max(v.x, max(v.y, v.z));
}

fn all_finite(v: vec3f) -> bool {
    return is_finite(v.x) && is_finite(v.y) && is_finite(v.z);
}

// `sampling::reflect`: `v` mirrored about `n`.
fn mirror(v: vec3f, n: vec3f) -> vec3f {
    return 2.0 * dot(v, n) * n - v;
}

// `sampling::refract`; w = 0 on total internal reflection.
fn refract_dir(v: vec3f, n: vec3f, eta: f32) -> vec4f {
    let cos_i = dot(v, n);
    let sin2_t = eta * eta * max(1.0 - cos_i * cos_i, 0.0);
    if sin2_t >= 1.0 {
        return vec4f(0.0);
    }
    let cos_t = sqrt(1.0 - sin2_t);
    return vec4f(normalize_exact(-v * eta + n * (eta * cos_i - cos_t)), 1.0);
}

fn ggx_g1(cos_theta: f32, alpha: f32) -> f32 {
    let c2 = max(cos_theta * cos_theta, 1e-12);
    let tan2 = max(1.0 - c2, 0.0) / c2;
    return 2.0 / (1.0 + sqrt(1.0 + alpha * alpha * tan2));
}

// `sampling::ggx_visible_normal` (Heitz 2018).
fn ggx_visible_normal(v_local: vec3f, alpha: f32, u: vec2f) -> vec3f {
    let vh = normalize_exact(vec3f(alpha * v_local.x, alpha * v_local.y, v_local.z));
    let len2 = vh.x * vh.x + vh.y * vh.y;
    var t1 = vec3f(1.0, 0.0, 0.0);
    if len2 > 0.0 {
        t1 = vec3f(-vh.y, vh.x, 0.0) / sqrt(len2);
    }
    let t2 = cross(vh, t1);
    let r = sqrt(u.x);
    let phi = 2.0 * PI * u.y;
    let p1 = r * cos(phi);
    var p2 = r * sin(phi);
    let k = 0.5 * (1.0 + vh.z);
    p2 = (1.0 - k) * sqrt(max(1.0 - p1 * p1, 0.0)) + k * p2;
    let nh = t1 * p1 + t2 * p2 + vh * sqrt(max(1.0 - p1 * p1 - p2 * p2, 0.0));
    return normalize_exact(vec3f(alpha * nh.x, alpha * nh.y, max(nh.z, 1e-6)));
}

// ShadingPoint::offset_origin.
fn surface_offset(sp: Surface, dir: vec3f) -> vec3f {
    let p = sp.p.xyz;
    let scale = 1e-4 * (1.0 + max(abs(p.x), max(abs(p.y), abs(p.z))));
    let g = sp.g.xyz;
    let n = select(-g, g, dot(dir, g) >= 0.0);
    return p + n * scale;
}

// `brdf::eval_lobes`: (whole, diffuse lobe), each times the cosine.
struct Lobes {
    whole: vec3f,
    diffuse: vec3f,
}

fn eval_lobes(sp: Surface, v: vec3f, l: vec3f) -> Lobes {
    let n = sp.n.xyz;
    let n_dot_l = dot(n, l);
    let n_dot_v = dot(n, v);
    if n_dot_l <= 0.0 || n_dot_v <= 0.0 {
        return Lobes(vec3f(0.0), vec3f(0.0));
    }
    let h = normalize_exact(v + l);
    let n_dot_h = max(dot(n, h), 0.0);
    let v_dot_h = max(dot(v, h), 0.0);
    let f = fresnel_schlick(v_dot_h, f0_of(sp));
    let d = d_ggx(n_dot_h, ggx_alpha(sp.g.w));
    let g = g_smith(n_dot_v, n_dot_l, sp.g.w);
    let specular = f * (d * g / max(4.0 * n_dot_v * n_dot_l, 1e-7));
    let kd = (vec3f(1.0) - f) * ((1.0 - sp.c.w) * (1.0 - sp.e.w));
    let diffuse = kd * sp.c.xyz / PI;
    return Lobes((diffuse + specular) * n_dot_l, diffuse * n_dot_l);
}

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

// ---- scattering (`reference::bsdf::sample_bsdf`) ----

struct Scatter {
    dir: vec3f,
    weight: vec3f,
    diffuse: vec3f,
    ok: bool,
}

fn sample_bsdf(sp: Surface, v: vec3f, rng: ptr<function, vec2<u32>>) -> Scatter {
    var out = Scatter(vec3f(0.0), vec3f(0.0), vec3f(0.0), false);
    let n = sp.n.xyz;
    let g = sp.g.xyz;
    let frame_n = basis_of(n);
    let v_local = to_local(frame_n, v);
    if v_local.z <= 0.0 {
        return out;
    }
    let a = ggx_alpha(sp.g.w);
    let f0 = f0_of(sp);
    let f_view = max_el(fresnel_schlick(v_local.z, f0));
    let transmission = sp.e.w;
    var p_t = 0.0;
    if transmission > 0.0 {
        p_t = clamp(transmission * (1.0 - f_view), 0.05, 0.95);
    }
    if rng_f32(rng) < p_t {
        let m = to_world(frame_n, ggx_visible_normal(v_local, a, rng_vec2(rng)));
        let f_m = fresnel_schlick(clamp(dot(v, m), 0.0, 1.0), f0);
        var eta = gp_ior(sp);
        if sp.ids.z == 1u {
            eta = 1.0 / gp_ior(sp);
        }
        let share = transmission * (vec3f(1.0) - f_m) / p_t;
        let r = refract_dir(v, m, eta);
        if r.w > 0.0 {
            if dot(r.xyz, g) < 0.0 {
                out = Scatter(r.xyz, share * sp.c.xyz * ggx_g1(-dot(r.xyz, n), a), vec3f(0.0), true);
            }
            return out;
        }
        let l = mirror(v, m);
        if dot(l, g) > 0.0 {
            out = Scatter(l, share * ggx_g1(dot(l, n), a), vec3f(0.0), true);
        }
        return out;
    }
    let diffuse_share = (1.0 - f_view) * (1.0 - sp.c.w) * (1.0 - transmission) * max_el(sp.c.xyz);
    var p_spec = 1.0;
    if !(diffuse_share <= 0.0) {
        p_spec = clamp(f_view / (f_view + diffuse_share), 0.1, 0.9);
    }
    var l: vec3f;
    if rng_f32(rng) < p_spec {
        let m = to_world(frame_n, ggx_visible_normal(v_local, a, rng_vec2(rng)));
        l = mirror(v, m);
    } else {
        l = to_world(frame_n, cosine_hemisphere(rng_vec2(rng)));
    }
    let cos_l = dot(l, n);
    if cos_l <= 0.0 || dot(l, g) <= 0.0 {
        return out;
    }
    let h = normalize_exact(v + l);
    let pdf_spec = ggx_g1(v_local.z, a) * d_ggx(max(dot(n, h), 0.0), a) / (4.0 * v_local.z);
    let pdf = p_spec * pdf_spec + (1.0 - p_spec) * cos_l / PI;
    if !(pdf > 0.0 && is_finite(pdf)) {
        return out;
    }
    let norm = (1.0 - p_t) * pdf;
    let lobes = eval_lobes(sp, v, l);
    return Scatter(l, lobes.whole / norm, lobes.diffuse / norm, true);
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
