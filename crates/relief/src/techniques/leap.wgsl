// Space leaping on the min-depth pyramid, the GPU twin of `leap.rs` (its march
// `march::leap`): the same iterations with the same operations in the same order. The pyramid
// is `pyramid_map` (its levels side by side in one texture, read with `textureLoad`, with
// `Material.pyramid_levels` levels); a bilinear cell's four texels come from one
// `textureGather` of the depth map at the point between them, which returns the stored
// numbers unfiltered, with the sampler's repeat wrap.
// Parameter 0: STEPS.

// How far past a cell boundary a leap lands (`LEAP_NUDGE`, 2⁻²¹).
const LEAP_NUDGE: f32 = 4.76837158203125e-7;
// The quadratic term counts as zero below this relative size.
const LEAP_QUADRATIC_EPS: f32 = 1e-7;
// Stands for +∞ (WGSL has no infinite literal): larger than any depth.
const LEAP_FAR: f32 = 3.0e38;

// The cell of coordinate `v`, the lower one at a boundary the ray leaves downward (`cell`).
fn leap_cell(v: f32, k: f32) -> f32 {
    let f = floor(v);
    return select(f, f - 1.0, v == f && k < 0.0);
}

// The ray parameter still to go until it leaves the cell `[lo, lo + s)`, `inv` = 1/k
// (`to_exit`).
fn leap_to_exit(x: f32, lo: f32, s: f32, k: f32, inv: f32) -> f32 {
    if k > 0.0 {
        return (lo + s - x) * inv;
    }
    if k < 0.0 {
        return (lo - x) * inv;
    }
    return LEAP_FAR;
}

// The smallest depth of cell `c` of level `level` (`DepthPyramid::min_depth`, wrapped), from
// the pyramid's atlas: level 0 at the origin, level k ≥ 1 at (w, h − 2·(h >> k)) for a depth
// map of w × h texels.
fn leap_min_depth(level: u32, c: vec2<f32>) -> f32 {
    let base = vec2<i32>(textureDimensions(depth_map));
    let n = base >> vec2<u32>(level);
    // As in `complexity_at`: coordinates beyond ±2^30 never occur on the scene's surfaces.
    if !(all(abs(c) < vec2<f32>(1073741824.0))) {
        return 0.0;
    }
    let q = ((vec2<i32>(c) % n) + n) % n;
    var origin = vec2<i32>(0);
    if level > 0u {
        origin = vec2<i32>(base.x, base.y - 2 * (base.y >> level));
    }
    return textureLoad(pyramid_map, origin + q, 0).r;
}

// The first τ in [0, span] where d + τ − D(f + k·τ) ≥ 0 in the bilinear cell of texel `c`,
// or −1 (`patch_crossing`).
fn leap_patch(c: vec2<f32>, f: vec2<f32>, k: vec2<f32>, d: f32, span: f32) -> f32 {
    let size = vec2<f32>(textureDimensions(depth_map));
    // Gather order: (x0, y1), (x1, y1), (x1, y0), (x0, y0).
    let g = textureGather(0, depth_map, map_sampler, (c + 1.0) / size);
    let d00 = g.w;
    let d10 = g.z;
    let d01 = g.x;
    let d11 = g.y;
    let bx = d10 - d00;
    let by = d01 - d00;
    let e = d11 - d10 - d01 + d00;
    let dd0 = d00 + bx * f.x + by * f.y + e * f.x * f.y;
    let dd1 = bx * k.x + by * k.y + e * (f.x * k.y + f.y * k.x);
    let dd2 = e * k.x * k.y;
    let c0 = d - dd0;
    if c0 >= 0.0 {
        return 0.0;
    }
    let c1 = 1.0 - dd1;
    let c2 = -dd2;
    var root: f32;
    if abs(c2) <= LEAP_QUADRATIC_EPS * max(abs(c1), -c0) {
        if !(c1 > 0.0) {
            return -1.0;
        }
        root = -c0 / c1;
    } else {
        let disc = c1 * c1 - 4.0 * c2 * c0;
        if disc < 0.0 {
            return -1.0;
        }
        let r = sqrt(disc);
        let q = -0.5 * (c1 + select(r, -r, c1 < 0.0));
        if q == 0.0 {
            return -1.0;
        }
        let r1 = q / c2;
        let r2 = c0 / q;
        let lo = min(r1, r2);
        let hi = max(r1, r2);
        root = select(hi, lo, lo >= 0.0);
    }
    if root >= 0.0 && root <= span {
        return root;
    }
    return -1.0;
}

// The highest level the ray needs (`ray_top`): the first whose cells are at least twice the
// ray's horizontal run plus one texel, at most `top`, found by doubling.
fn leap_ray_top(top: u32, k: vec2<f32>) -> u32 {
    let run = 2.0 * (max(abs(k.x), abs(k.y)) + 1.0);
    var level = 0u;
    while level < top && f32(1u << level) < run {
        level += 1u;
    }
    return level;
}

fn trace(uv0: vec2<f32>, view_ts: vec3<f32>) -> Hit {
    let steps = param(0u);
    let size = vec2<f32>(textureDimensions(depth_map));
    let dp = uv_per_depth(view_ts);
    let p0 = uv0 * size - 0.5;
    let k = dp * size;
    // 1/0 is never used (the k = 0 branch returns first); the select keeps it finite.
    let inv = vec2<f32>(1.0) / select(k, vec2<f32>(1.0), k == vec2<f32>(0.0));
    let top = leap_ray_top(material.pyramid_levels - 1u, k);
    var level = top;
    var d = 0.0;
    var n = 0u;
    loop {
        if n >= steps || !(d < 1.0) {
            break;
        }
        n += 1u;
        let s = f32(1u << level);
        // 2^−level from its exponent bits (`inv_s` on the CPU).
        let inv_s = bitcast<f32>((127u - level) << 23u);
        let x = p0 + k * d;
        let c = vec2<f32>(leap_cell(x.x * inv_s, k.x), leap_cell(x.y * inv_s, k.y));
        let m = leap_min_depth(level, c);
        let exit = d + min(leap_to_exit(x.x, c.x * s, s, k.x, inv.x), leap_to_exit(x.y, c.y * s, s, k.y, inv.y));
        if d < m {
            if m < exit {
                d = m;
                level = select(0u, level - 1u, level > 0u);
            } else {
                d = exit + LEAP_NUDGE;
                level = min(level + 1u, top);
            }
        } else if level > 0u {
            level -= 1u;
        } else {
            let f = x - c;
            let span = max(min(exit, 1.0) - d, 0.0);
            let t = leap_patch(c, f, k, d, span);
            if t >= 0.0 {
                let depth = d + t;
                return Hit(uv0 + dp * depth, depth, n);
            }
            d = exit + LEAP_NUDGE;
            level = min(top, 1u);
        }
    }
    let depth = min(d, 1.0);
    return Hit(uv0 + dp * depth, depth, n);
}
