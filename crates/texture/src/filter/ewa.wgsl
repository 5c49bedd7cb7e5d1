// Heckbert's EWA, the GPU twin of `ewa.rs` (`Ewa::sample`, `Footprint`, `Ewa::scan`) with
// the same operations in the same order: the footprint's axes, the eccentricity clamp, the
// level from the minor axis and the texel budget, Heckbert's reconstruction circle, each
// row's span from the quadratic, and the pixel filter's Gaussian weight `2^(−Q')` with the
// CPU's base-2 exponent `Q'` clamped to the support (the CPU evaluates `2^(−Q')` by a series
// within 4·10⁻⁷ of the exact value; here the GPU's `exp2`).
//
// The contract with the GPU filter frame (`renderlab-gpu`, `shaders/filter.wgsl`): it binds
// `filter_tex` (the texture's pyramid, every level as the CPU built it), `filter_sampler`
// (bilinear within a level) and the uniform `filter_params` with EWA's parameters already
// clamped to their ranges (`ewa_sigma`, `ewa_cut`, `ewa_ecc`, `ewa_texels`) and the wrap
// mode (`wrap`: 0 repeat, 1 clamp); the constants `EWA_*` are generated from the CPU's.
//
// Differences left: the CPU steps Q by forward differences on rows that cross the texture's
// edge and sums in four lanes; here Q is evaluated directly (as the CPU does inside the
// texture) and summed texel by texel, so the two differ by f32 rounding, and a weight index
// may move by one table entry (a factor e^(1/128)) where Q lies within rounding of an
// integer.

// The principal axes of the footprint (`Jacobian::axes`).
struct EwaAxes {
    major: f32,
    minor: f32,
    dir: vec2<f32>,
}

// Heckbert's implicit ellipse `A·U² + B·U·V + C·V² = F` (`Ellipse`).
struct EwaEllipse {
    a: f32,
    b: f32,
    c: f32,
    f: f32,
}

// The ellipses on one level and the lookup point in its texel coordinates (`Footprint`).
struct EwaFootprint {
    // The support.
    e: EwaEllipse,
    // The Gaussian's own conic.
    g: EwaEllipse,
    centre: vec2<f32>,
    half_v: f32,
    level: i32,
}

fn ewa_axes(ux: f32, vx: f32, uy: f32, vy: f32) -> EwaAxes {
    let m00 = ux * ux + uy * uy;
    let m01 = ux * vx + uy * vy;
    let m11 = vx * vx + vy * vy;
    let half_tr = 0.5 * (m00 + m11);
    let half_diff = 0.5 * (m00 - m11);
    let l1 = half_tr + sqrt(half_diff * half_diff + m01 * m01);
    let det = ux * vy - uy * vx;
    var l2 = 0.0;
    if l1 > 0.0 {
        l2 = min(det * det / l1, l1);
    }
    let e1 = vec2<f32>(l1 - m11, m01);
    let e2 = vec2<f32>(m01, l1 - m00);
    var e = e2;
    if dot(e1, e1) >= dot(e2, e2) {
        e = e1;
    }
    let len2 = dot(e, e);
    var dir = vec2<f32>(1.0, 0.0);
    if len2 > 0.0 && len2 <= 3.4e38 {
        dir = e / sqrt(len2);
    }
    return EwaAxes(sqrt(l1), sqrt(l2), dir);
}

// `Ellipse::from_moments`.
fn ewa_from_moments(m00: f32, m01: f32, m11: f32) -> EwaEllipse {
    return EwaEllipse(m11, -2.0 * m01, m00, m00 * m11 - m01 * m01);
}

// `⌊x⌋` and `⌈x⌉` as integers, as the CPU's `floor_i` and `ceil_i`.
fn ewa_floor_i(x: f32) -> i32 {
    let i = i32(x);
    return i - select(0, 1, f32(i) > x);
}

fn ewa_ceil_i(x: f32) -> i32 {
    let i = i32(x);
    return i + select(0, 1, f32(i) < x);
}

// `⌊log₂ x⌋` of a finite `x ≥ 1` from its exponent bits.
fn ewa_floor_log2(x: f32) -> i32 {
    return i32((bitcast<u32>(x) >> 23u) & 0xffu) - 127;
}

// The size of `level` by the pyramid's rule (each side halved, rounding down, never below
// 1), from level 0's: `textureDimensions` with a level that differs between the pixels of a
// quad is unreliable on some drivers (lavapipe answers with a neighbour's level).
fn ewa_level_size(level: i32) -> vec2<i32> {
    let base = textureDimensions(filter_tex, 0);
    return vec2<i32>(max(base >> vec2<u32>(u32(level)), vec2<u32>(1u)));
}

// The truncation of the reconstruction part, in its own σ: at least 3.
fn ewa_reconstruction_cut(cut: f32) -> f32 {
    return max(cut, 3.0);
}

// The footprint on `level` (`Ewa::footprint`).
fn ewa_footprint(level: i32, m: vec3<f32>, uv: vec2<f32>, inv_s2: f32, cut: f32) -> EwaFootprint {
    var recon = EWA_COARSE_RECONSTRUCTION_VARIANCE * inv_s2;
    if level == 0 {
        recon = EWA_RECONSTRUCTION_VARIANCE * inv_s2;
    }
    let s0 = vec2<f32>(textureDimensions(filter_tex, 0));
    let sl = vec2<f32>(ewa_level_size(level));
    let k = sl * (1.0 / s0);
    let j00 = m.x * k.x * k.x;
    let j01 = m.y * k.x * k.y;
    let j11 = m.z * k.y * k.y;
    let rc = ewa_reconstruction_cut(cut);
    let c2 = cut * cut / inv_s2;
    let r2 = rc * rc / inv_s2;
    let e = ewa_from_moments(c2 * j00 + r2 * recon, c2 * j01, c2 * j11 + r2 * recon);
    let g = ewa_from_moments(j00 + recon, j01, j11 + recon);
    return EwaFootprint(e, g, uv * sl - 0.5, sqrt(e.a), level);
}

// Inclusive texel range of row `j` (`Footprint::span`); empty when x > y.
fn ewa_span(fp: EwaFootprint, j: i32) -> vec2<i32> {
    let v = f32(j) - fp.centre.y;
    let d = fp.e.f * (fp.e.a - v * v);
    if !(d >= 0.0) {
        return vec2<i32>(1, 0);
    }
    let r = sqrt(d);
    let mid = -0.5 * fp.e.b * v;
    let inv_a = 1.0 / fp.e.a;
    return vec2<i32>(ewa_ceil_i((mid - r) * inv_a + fp.centre.x), ewa_floor_i((mid + r) * inv_a + fp.centre.x));
}

// The rows the support spans (`Footprint::rows`).
fn ewa_rows(fp: EwaFootprint) -> vec2<i32> {
    return vec2<i32>(ewa_ceil_i(fp.centre.y - fp.half_v), ewa_floor_i(fp.centre.y + fp.half_v));
}

// Exact number of texels inside, stopping once it passes `limit` (`Footprint::count`).
fn ewa_count(fp: EwaFootprint, limit: u32) -> u32 {
    let rows = ewa_rows(fp);
    var n = 0u;
    for (var j = rows.x; j <= rows.y; j += 1) {
        let s = ewa_span(fp, j);
        if s.y >= s.x {
            n += u32(s.y - s.x + 1);
            if n > limit {
                break;
            }
        }
    }
    return n;
}

// Texel `(x, y)` of `level`, addressed by the wrap mode.
fn ewa_texel(level: i32, x: i32, y: i32) -> vec4<f32> {
    let size = ewa_level_size(level);
    var p = vec2<i32>(x, y);
    if filter_params.wrap == 0u {
        p = ((p % size) + size) % size;
    } else {
        p = clamp(p, vec2<i32>(0), size - 1);
    }
    return textureLoad(filter_tex, p, level);
}

// The weighted sum over the texels inside the footprint (`Ewa::scan`).
fn ewa_scan(fp: EwaFootprint, inv_s2: f32, cut: f32) -> vec4<f32> {
    let rc = ewa_reconstruction_cut(cut);
    let edge = 0.5 * (rc * rc) * EWA_LOG2_E;
    let g = fp.g;
    let s = 0.5 * inv_s2 * EWA_LOG2_E / g.f;
    let qa = g.a * s;
    let qb = g.b * s;
    let qc = g.c * s;
    let rows = ewa_rows(fp);
    var acc = vec4<f32>(0.0);
    var wsum = 0.0;
    for (var j = rows.x; j <= rows.y; j += 1) {
        let span = ewa_span(fp, j);
        let v = f32(j) - fp.centre.y;
        let bv = qb * v;
        let cv = qc * v * v;
        for (var x = span.x; x <= span.y; x += 1) {
            let u = f32(x) - fp.centre.x;
            let q = (qa * u + bv) * u + cv;
            // The exponent clamped to the support.
            let wt = exp2(-min(max(q, 0.0), edge));
            acc += ewa_texel(fp.level, x, j) * wt;
            wsum += wt;
        }
    }
    if wsum > 0.0 {
        return acc / wsum;
    }
    let size = vec2<f32>(ewa_level_size(fp.level));
    return textureSampleLevel(filter_tex, filter_sampler, (fp.centre + 0.5) / size, f32(fp.level));
}

// EWA at `uv` for the footprint `duv_dx`, `duv_dy` (`Ewa::sample`).
fn ewa(uv_in: vec2<f32>, duv_dx: vec2<f32>, duv_dy: vec2<f32>) -> vec4<f32> {
    let top = i32(textureNumLevels(filter_tex)) - 1;
    let size = vec2<f32>(textureDimensions(filter_tex, 0));
    let dx = duv_dx * size;
    let dy = duv_dy * size;
    let ax = ewa_axes(dx.x, dx.y, dy.x, dy.y);
    let ecc = filter_params.ewa_ecc;
    let budget = filter_params.ewa_texels;
    let sigma = filter_params.ewa_sigma;
    let cut = filter_params.ewa_cut;
    let inv_s2 = 1.0 / (sigma * sigma);
    // A non-finite footprint, or one whose major axis exceeds four texture widths, is
    // filtered by the 1×1 top level: the texture's mean.
    let limit = 4.0 * max(size.x, size.y);
    let finite = ax.minor <= 3.4e38 && all(abs(ax.dir) <= vec2<f32>(3.4e38));
    if top == 0 || !(ax.major <= limit && finite) {
        return textureLoad(filter_tex, vec2<i32>(0), top);
    }
    // Texel coordinates kept small: one period for repeat, the footprint's reach for clamp.
    var uv = clamp(uv_in, vec2<f32>(-1.0e7), vec2<f32>(1.0e7));
    if filter_params.wrap == 0u {
        uv = uv - vec2<f32>(f32(ewa_floor_i(uv.x)), f32(ewa_floor_i(uv.y)));
    } else {
        let reach = 1.0 + ax.major / min(size.x, size.y);
        uv = clamp(uv, vec2<f32>(-reach), vec2<f32>(1.0 + reach));
    }
    let major = ax.major;
    let minor = max(ax.minor, ax.major / ecc);
    // Second moments of the reshaped footprint: R·diag(major², minor²)·Rᵀ.
    let c = ax.dir.x;
    let s = ax.dir.y;
    let a2 = major * major;
    let b2 = minor * minor;
    let m = vec3<f32>(a2 * c * c + b2 * s * s, (a2 - b2) * c * s, a2 * s * s + b2 * c * c);
    // The level on which the kernel's σ across the minor axis spans ½ to 1 texel.
    let across = 2.0 * sigma * minor;
    var level = 0;
    if across > 1.0 {
        level = min(ewa_floor_log2(across), top);
    }
    var fp = ewa_footprint(level, m, uv, inv_s2, cut);
    // Coarser while the footprint holds more texels than the budget: the area bound first,
    // then the exact count.
    let pi = 3.14159265358979;
    while level < top {
        let area = pi * sqrt(fp.e.f);
        let bound = area + pi * sqrt(fp.e.a + fp.e.c) + 0.5 * pi;
        if bound <= f32(budget) {
            break;
        }
        if area <= 1.5 * f32(budget) && ewa_count(fp, budget) <= budget {
            break;
        }
        level += 1;
        fp = ewa_footprint(level, m, uv, inv_s2, cut);
    }
    if level == top {
        return textureLoad(filter_tex, vec2<i32>(0), top);
    }
    return ewa_scan(fp, inv_s2, cut);
}
