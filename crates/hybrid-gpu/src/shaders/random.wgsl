// The CPU's per-pixel random streams (renderlab-hybrid's `rng`), bit for bit: SplitMix64's
// finaliser over a Weyl sequence, in 64-bit integers written as (low, high) pairs of u32,
// since WGSL has no 64-bit integers. `stratified` is the CPU's stratified 2-D point in f32
// where the CPU computes it in f64 (the points agree within a few ulps). Then the sampling
// the stages share (renderlab-scene's `sampling`): cosine-weighted directions, the normal's
// frame, GGX's visible normals, mirror reflection and refraction.

// 0x9e3779b97f4a7c15, the Weyl increment.
const RNG_GOLDEN: vec2<u32> = vec2<u32>(0x7f4a7c15u, 0x9e3779b9u);

fn u64_add(a: vec2<u32>, b: vec2<u32>) -> vec2<u32> {
    let lo = a.x + b.x;
    return vec2<u32>(lo, a.y + b.y + select(0u, 1u, lo < a.x));
}

// The full 64-bit product of two u32, from 16-bit halves.
fn u32_mul_wide(a: u32, b: u32) -> vec2<u32> {
    let a0 = a & 0xffffu;
    let a1 = a >> 16u;
    let b0 = b & 0xffffu;
    let b1 = b >> 16u;
    let p00 = a0 * b0;
    let p01 = a0 * b1;
    let p10 = a1 * b0;
    let p11 = a1 * b1;
    let lo1 = p00 + (p01 << 16u);
    let c1 = select(0u, 1u, lo1 < p00);
    let lo = lo1 + (p10 << 16u);
    let c2 = select(0u, 1u, lo < lo1);
    return vec2<u32>(lo, p11 + (p01 >> 16u) + (p10 >> 16u) + c1 + c2);
}

// The low 64 bits of a · b.
fn u64_mul(a: vec2<u32>, b: vec2<u32>) -> vec2<u32> {
    let p = u32_mul_wide(a.x, b.x);
    return vec2<u32>(p.x, p.y + a.x * b.y + a.y * b.x);
}

// a >> k for 0 < k < 32.
fn u64_shr(a: vec2<u32>, k: u32) -> vec2<u32> {
    return vec2<u32>((a.x >> k) | (a.y << (32u - k)), a.y >> k);
}

fn rng_mix(z0: vec2<u32>) -> vec2<u32> {
    var z = z0;
    z = u64_mul(z ^ u64_shr(z, 30u), vec2<u32>(0x1ce4e5b9u, 0xbf58476du));
    z = u64_mul(z ^ u64_shr(z, 27u), vec2<u32>(0x133111ebu, 0x94d049bbu));
    return z ^ u64_shr(z, 31u);
}

// Rng::new(seed, pixel, stream), given `base = seed ^ mix(stream << 56)` (the CPU computes
// it once per frame).
fn rng_new(base: vec2<u32>, pixel: u32) -> vec2<u32> {
    return rng_mix(base ^ rng_mix(u64_add(vec2<u32>(pixel, 0u), RNG_GOLDEN)));
}

// Rng::f32: the next number in [0, 1), the top 24 bits of the next output.
fn rng_f32(state: ptr<function, vec2<u32>>) -> f32 {
    *state = u64_add(*state, RNG_GOLDEN);
    let x = rng_mix(*state);
    return f32(x.y >> 8u) * (1.0 / 16777216.0);
}

fn rng_vec2(state: ptr<function, vec2<u32>>) -> vec2<f32> {
    let x = rng_f32(state);
    let y = rng_f32(state);
    return vec2<f32>(x, y);
}

// The i-th of n stratified points (a rank-1 lattice: x stratified, y by the golden ratio),
// shifted toroidally by `shift`, kept below 1.
fn stratified(i: u32, n: u32, shift: vec2<f32>) -> vec2<f32> {
    let x = (f32(i) + 0.5) / f32(n);
    let y = fract(f32(i) * 0.618034);
    let top = 1.0 - 5.9604645e-8;
    return vec2<f32>(min(fract(x + shift.x), top), min(fract(y + shift.y), top));
}

// A cosine-weighted direction about local +Z.
fn cosine_hemisphere(u: vec2<f32>) -> vec3<f32> {
    let r = sqrt(u.x);
    let phi = 6.28318530717959 * u.y;
    return vec3<f32>(r * cos(phi), r * sin(phi), sqrt(max(1.0 - u.x, 0.0)));
}

// glam's `any_orthonormal_pair` (Duff et al.), with its signum (+1 for +0, −1 for −0): the
// local +X and +Y of `Frame::new(n)`, as the columns of a matrix.
fn frame_axes(n: vec3<f32>) -> mat2x3<f32> {
    let sign = select(1.0, -1.0, (bitcast<u32>(n.z) & 0x80000000u) != 0u);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    let t = vec3<f32>(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    let s = vec3<f32>(b, sign + n.y * n.y * a, -n.y);
    return mat2x3<f32>(t, s);
}

// Frame::to_world: local `v` about the unit normal `n` in world space.
fn frame_to_world(n: vec3<f32>, v: vec3<f32>) -> vec3<f32> {
    let ts = frame_axes(n);
    return ts[0] * v.x + ts[1] * v.y + n * v.z;
}

// Frame::to_local: world `v` in the frame about the unit normal `n`.
fn frame_to_local(n: vec3<f32>, v: vec3<f32>) -> vec3<f32> {
    let ts = frame_axes(n);
    return vec3<f32>(dot(v, ts[0]), dot(v, ts[1]), dot(v, n));
}

// sampling::reflect: `v` mirrored about `n` (both unit; the result leaves on v's side). Not
// WGSL's `reflect`, whose incident vector points toward the surface.
fn mirror_dir(v: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    return 2.0 * dot(v, n) * n - v;
}

// sampling::refract's result: the refracted direction, `ok` false under total internal
// reflection.
struct Refracted {
    dir: vec3<f32>,
    ok: bool,
}

// sampling::refract: the unit `v` (away from the surface, on n's side) through an interface
// of relative index `eta = n_incident / n_transmitted`. Not WGSL's `refract` (incident
// vector toward the surface, no flag).
fn refract_dir(v: vec3<f32>, n: vec3<f32>, eta: f32) -> Refracted {
    var out: Refracted;
    let cos_i = dot(v, n);
    let sin2_t = eta * eta * max(1.0 - cos_i * cos_i, 0.0);
    if sin2_t >= 1.0 {
        return out;
    }
    let cos_t = sqrt(1.0 - sin2_t);
    let d = -v * eta + n * (eta * cos_i - cos_t);
    out.dir = d * (1.0 / length(d));
    out.ok = true;
    return out;
}

// sampling::ggx_visible_normal (Heitz 2018): a microfacet normal from GGX's normals visible
// from `v_local` (local frame, +Z the normal, v_local.z > 0) with roughness `alpha`.
fn ggx_visible_normal(v_local: vec3<f32>, alpha: f32, u: vec2<f32>) -> vec3<f32> {
    let s = vec3<f32>(alpha * v_local.x, alpha * v_local.y, v_local.z);
    let vh = s * (1.0 / length(s));
    let len2 = vh.x * vh.x + vh.y * vh.y;
    var t1 = vec3<f32>(1.0, 0.0, 0.0);
    if len2 > 0.0 {
        t1 = vec3<f32>(-vh.y, vh.x, 0.0) / sqrt(len2);
    }
    let t2 = cross(vh, t1);
    let r = sqrt(u.x);
    let phi = 6.28318530717959 * u.y;
    let p1 = r * cos(phi);
    let k = 0.5 * (1.0 + vh.z);
    let p2 = (1.0 - k) * sqrt(max(1.0 - p1 * p1, 0.0)) + k * (r * sin(phi));
    let nh = t1 * p1 + t2 * p2 + vh * sqrt(max(1.0 - p1 * p1 - p2 * p2, 0.0));
    let m = vec3<f32>(alpha * nh.x, alpha * nh.y, max(nh.z, 1e-6));
    return m * (1.0 / length(m));
}
