// The shading every lighting pass shares, written with the operations of its CPU twins:
// the thesis's BRDF (`renderlab_scene::brdf`), `Light::sample`, the raster pipeline's
// weights (`deferred::weights`), the shadow-map lookup with PCF (`stages::shadows::maps`)
// and the direct light of one surface point (`deferred::lighting::shade_direct`).

struct ShadowMap {
    view_proj: mat4x4f,
    eye_texel: vec4f,     // eye, world size of a texel (at unit distance when perspective)
    forward_ortho: vec4f, // unit axis, orthographic (1/0)
    res: vec4u,           // resolution, array (0 directional, 1 cube/spot, 2 area), layer, 0
}

@group(1) @binding(9) var<storage, read> shadow_maps: array<ShadowMap>;
@group(1) @binding(10) var directional_maps: texture_2d_array<f32>;
@group(1) @binding(14) var cube_maps: texture_2d_array<f32>;
@group(1) @binding(15) var area_maps: texture_2d_array<f32>;
// Per light: (0 no map / 1 one map / 2 cube maps, first map, cube count, 0).
@group(1) @binding(11) var<storage, read> light_shadows: array<vec4u>;

// ---- BRDF ----

fn ggx_alpha(roughness: f32) -> f32 {
    return max(roughness * roughness, 1e-3);
}

fn d_ggx(n_dot_h: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let d = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
    return a2 / (PI * d * d);
}

fn g_schlick_ggx(n_dot_v: f32, k: f32) -> f32 {
    return n_dot_v / (n_dot_v * (1.0 - k) + k);
}

fn g_smith(n_dot_v: f32, n_dot_l: f32, roughness: f32) -> f32 {
    let k = (roughness + 1.0) * (roughness + 1.0) / 8.0;
    return g_schlick_ggx(n_dot_v, k) * g_schlick_ggx(n_dot_l, k);
}

fn fresnel_schlick(cos_theta: f32, f0: vec3f) -> vec3f {
    let m = clamp(1.0 - cos_theta, 0.0, 1.0);
    let m2 = m * m;
    return f0 + (vec3f(1.0) - f0) * (m2 * m2 * m);
}

fn f0_of(sp: Surface) -> vec3f {
    let r = (gp_ior(sp) - 1.0) / (gp_ior(sp) + 1.0);
    let s = sp.c.w;
    return vec3f(r * r) * (1.0 - s) + sp.c.xyz * s;
}

fn brdf_eval(sp: Surface, v: vec3f, l: vec3f) -> vec3f {
    let n = sp.n.xyz;
    let n_dot_l = dot(n, l);
    let n_dot_v = dot(n, v);
    if n_dot_l <= 0.0 || n_dot_v <= 0.0 {
        return vec3f(0.0);
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
    return (diffuse + specular) * n_dot_l;
}

// ---- weights of the raster pipeline's indirect terms ----

fn diffuse_albedo(sp: Surface, v: vec3f) -> vec3f {
    let f = fresnel_schlick(max(dot(sp.n.xyz, v), 0.0), f0_of(sp));
    return (vec3f(1.0) - f) * ((1.0 - sp.c.w) * (1.0 - sp.e.w)) * sp.c.xyz;
}

fn specular_weight(sp: Surface, n_dot_v: f32) -> vec3f {
    let c0 = vec4f(-1.0, -0.0275, -0.572, 0.022);
    let c1 = vec4f(1.0, 0.0425, 1.04, -0.04);
    let r = c0 * sp.g.w + c1;
    let a004 = min(r.x * r.x, exp2(-9.28 * max(n_dot_v, 0.0))) * r.x + r.y;
    let a = -1.04 * a004 + r.z;
    let b = 1.04 * a004 + r.w;
    return max(f0_of(sp) * a + vec3f(b), vec3f(0.0));
}

// ---- lights ----

struct LightSample {
    to_light: vec3f,
    distance: f32,
    radiance: vec3f,
}

fn light_kind(l: Light) -> u32 {
    return bitcast<u32>(l.position_kind.w);
}

fn light_sample(l: Light, p: vec3f, u: vec2f) -> LightSample {
    let energy = l.color_range.xyz * l.direction_intensity.w;
    let kind = light_kind(l);
    var out: LightSample;
    if kind == 2u {
        out.to_light = -l.direction_intensity.xyz;
        out.distance = F32_MAX;
        out.radiance = energy;
        return out;
    }
    if kind == 3u {
        let half_u = l.half_u_inner.xyz;
        let half_v = l.half_v_outer.xyz;
        let q = l.position_kind.xyz + half_u * (2.0 * u.x - 1.0) + half_v * (2.0 * u.y - 1.0);
        let nn = cross(half_u, half_v);
        let area = 4.0 * length(nn);
        let n = normalize_exact(nn);
        let d = q - p;
        let dist2 = max(dot(d, d), 1e-12);
        let dist = sqrt(dist2);
        out.to_light = d / dist;
        out.distance = dist;
        let cos_l = max(dot(-out.to_light, n), 0.0);
        out.radiance = energy * (cos_l * area / dist2);
        return out;
    }
    let d = l.position_kind.xyz - p;
    let dist2 = max(dot(d, d), 1e-12);
    let dist = sqrt(dist2);
    out.to_light = d / dist;
    out.distance = dist;
    var falloff = 1.0;
    let range = l.color_range.w;
    if range > 0.0 {
        let r = dist / range;
        let x = r * r * r * r;
        let c = clamp(1.0 - x, 0.0, 1.0);
        falloff = c * c;
    }
    if kind == 1u {
        let cd = dot(-out.to_light, l.direction_intensity.xyz);
        let ci = cos(l.half_u_inner.w);
        let co = cos(l.half_v_outer.w);
        let t = clamp((cd - co) / max(ci - co, 1e-6), 0.0, 1.0);
        falloff = falloff * (t * t);
    }
    out.radiance = energy * (falloff / dist2);
    return out;
}

// ---- shadow maps ----

fn map_depth(m: ShadowMap, x: i32, y: i32) -> f32 {
    let layer = i32(m.res.z);
    if m.res.y == 0u {
        return textureLoad(directional_maps, vec2i(x, y), layer, 0).x;
    }
    if m.res.y == 1u {
        return textureLoad(cube_maps, vec2i(x, y), layer, 0).x;
    }
    return textureLoad(area_maps, vec2i(x, y), layer, 0).x;
}

fn map_lookup(m: ShadowMap, point: vec3f, normal: vec3f, to_light: vec3f) -> f32 {
    let h = m.view_proj * vec4f(point, 1.0);
    let d = dot(point - m.eye_texel.xyz, m.forward_ortho.xyz);
    if h.w <= 0.0 || d <= 0.0 {
        return 1.0;
    }
    let ndc = h.xy / h.w;
    if !(abs(ndc.x) <= 1.0 && abs(ndc.y) <= 1.0) {
        return 1.0;
    }
    let res = i32(m.res.x);
    let fres = f32(m.res.x);
    let tx = clamp(i32(floor((ndc.x + 1.0) * 0.5 * fres)), 0, res - 1);
    let ty = clamp(i32(floor((1.0 - ndc.y) * 0.5 * fres)), 0, res - 1);
    var size = m.eye_texel.w;
    if m.forward_ortho.w == 0.0 {
        size = size * d;
    }
    let c = clamp(abs(dot(normal, to_light)), 1e-4, 1.0);
    let tan_t = min(sqrt(1.0 - c * c) / c, 10.0);
    let r = i32(frame.params.z);
    let bias = size * (frame.shadow.x + frame.shadow.y * f32(max(r, 1)) * tan_t);
    var lit = 0u;
    for (var y = ty - r; y <= ty + r; y++) {
        for (var x = tx - r; x <= tx + r; x++) {
            if d - bias <= map_depth(m, clamp(x, 0, res - 1), clamp(y, 0, res - 1)) {
                lit += 1u;
            }
        }
    }
    let side = 2 * r + 1;
    return f32(lit) / f32(side * side);
}

fn cube_face(d: vec3f) -> u32 {
    let a = abs(d);
    if a.x >= a.y && a.x >= a.z {
        return select(1u, 0u, d.x >= 0.0);
    }
    if a.y >= a.z {
        return select(3u, 2u, d.y >= 0.0);
    }
    return select(5u, 4u, d.z >= 0.0);
}

// The lit fraction of `point` (geometric normal `normal`) for light `li` from its maps.
fn shadow_visibility(li: u32, l: Light, point: vec3f, normal: vec3f) -> f32 {
    if frame.ssr_steps.z == 0u {
        return 1.0;
    }
    let ls = light_shadows[li];
    let directional = light_kind(l) == 2u;
    if ls.x == 1u {
        let m = shadow_maps[ls.y];
        var to_light = -l.direction_intensity.xyz;
        if !directional {
            to_light = normalize_or_zero(m.eye_texel.xyz - point);
        }
        return map_lookup(m, point, normal, to_light);
    }
    if ls.x == 2u {
        var sum = 0.0;
        for (var c = 0u; c < ls.z; c++) {
            let base = ls.y + 6u * c;
            let eye = shadow_maps[base].eye_texel.xyz;
            let face = cube_face(point - eye);
            var to_light = -l.direction_intensity.xyz;
            if !directional {
                to_light = normalize_or_zero(eye - point);
            }
            sum += map_lookup(shadow_maps[base + face], point, normal, to_light);
        }
        return sum / f32(ls.z);
    }
    return 1.0;
}

// ---- direct light ----

fn shade_direct(sp: Surface, v: vec3f) -> vec3f {
    var sum = vec3f(0.0);
    let p = sp.p.xyz;
    for (var li = 0u; li < frame.size.z; li++) {
        let l = lights[li];
        var n = 1u;
        if light_kind(l) == 3u {
            n = max(frame.size.w, 1u);
        }
        let count = n * n;
        var vis = -1.0;
        var light_sum = vec3f(0.0);
        for (var s = 0u; s < count; s++) {
            let u = vec2f((f32(s % n) + 0.5) / f32(n), (f32(s / n) + 0.5) / f32(n));
            let ls = light_sample(l, p, u);
            if all(ls.radiance == vec3f(0.0)) {
                continue;
            }
            let f = brdf_eval(sp, v, ls.to_light);
            if all(f == vec3f(0.0)) {
                continue;
            }
            if vis < 0.0 {
                vis = shadow_visibility(li, l, p, sp.g.xyz);
            }
            light_sum += f * ls.radiance * vis;
        }
        sum += light_sum / f32(count);
    }
    return sum;
}
