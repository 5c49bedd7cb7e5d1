// The path tracer's scattering (renderlab-hybrid's `reference::bsdf::sample_bsdf`) and
// the sampling and BRDF helpers it needs (`renderlab_scene::sampling`, `brdf::eval_lobes`),
// written with the CPU's operations and drawing the same random numbers in the same order.
// Follows the random streams and SHADING; `reference.wgsl` follows it.

// ---- geometry helpers (renderlab_scene::sampling) ----

struct Basis {
    t: vec3f,
    b: vec3f,
    n: vec3f,
}

// `Frame::new`: glam's `any_orthonormal_pair` about the unit `n`.
fn basis_of(n: vec3f) -> Basis {
    let ts = frame_axes(n);
    return Basis(ts[0], ts[1], n);
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

fn ggx_g1(cos_theta: f32, alpha: f32) -> f32 {
    let c2 = max(cos_theta * cos_theta, 1e-12);
    let tan2 = max(1.0 - c2, 0.0) / c2;
    return 2.0 / (1.0 + sqrt(1.0 + alpha * alpha * tan2));
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
        if r.ok {
            if dot(r.dir, g) < 0.0 {
                out = Scatter(r.dir, share * sp.c.xyz * ggx_g1(-dot(r.dir, n), a), vec3f(0.0), true);
            }
            return out;
        }
        let l = mirror_dir(v, m);
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
        l = mirror_dir(v, m);
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
