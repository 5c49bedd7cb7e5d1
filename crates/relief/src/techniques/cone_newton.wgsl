// Newton-finished relaxed cone stepping on the packed map, the GPU twin of `cone_newton.rs`
// (its scalar step, `march::cone_newton::step_scalar`, with the same operations in the same
// order): one packed fetch per step gives the bilinear depth, its gradient and the cone
// ratio; a ray stops once a Newton step on the fetched patch would move it less than the
// tolerance; otherwise it takes relaxed cone steps (straight to Newton's estimate near the
// surface), and a crossing is refined by Illinois false position.
// Parameters 0, 1, 2: STEPS, SECANT, TOL (hundredths of a texel).

// The phases of `march::cone_newton`.
const CN_CONE: i32 = 0;
const CN_REFINE_0: i32 = 1;
const CN_REFINE_A: i32 = 2;
const CN_REFINE_B: i32 = 3;

// `a < b ? a : b` and `a > b ? a : b`, as the CPU's `mn` and `mx` (`minps`, `maxps`).
fn cn_min(a: f32, b: f32) -> f32 {
    return select(b, a, a < b);
}

fn cn_max(a: f32, b: f32) -> f32 {
    return select(b, a, a > b);
}

// The false-position estimate inside the bracket (`interp`).
fn cn_interp(a: f32, fa: f32, b: f32, fb: f32) -> f32 {
    let den = fb - fa;
    if den > 1e-12 {
        return cn_min(cn_max((a * fb - b * fa) / den, a), b);
    }
    return 0.5 * (a + b);
}

fn trace(uv0: vec2<f32>, view_ts: vec3<f32>) -> Hit {
    let steps = param(0u);
    let secant = param(1u);
    let tol = f32(param(2u)) / 100.0;
    // The ray (`Ray::new`): entry and direction in texels of the (unpadded) packed grid.
    let dp = uv_per_depth(view_ts);
    let size = vec2<f32>(textureDimensions(packed_map) - vec2<u32>(1u));
    let s = sqrt(dot(dp, dp));
    let texels_per_depth = s * max(size.x, size.y);
    let eps = clamp(tol / max(texels_per_depth, 1e-3), 1e-6, CN_MAX_EPS);
    let px = uv0.x * size.x - 0.5;
    let py = uv0.y * size.y - 0.5;
    let tu = dp.x * size.x;
    let tv = dp.y * size.y;
    // The state (`State::new`).
    var t = 0.0;
    var a = 0.0;
    var fa = -1.0;
    var b = 1.0;
    var fb = 0.0;
    var k = 0;
    var phase = select(CN_CONE, CN_REFINE_0, steps == 0u);
    // Each step fetches once; the CPU's loop ends within STEPS cone and SECANT refinement
    // steps, and this bound only makes that explicit.
    var result = 1.0;
    for (var iter = 0u; iter <= steps + secant + 1u; iter += 1u) {
        var c = t;
        if phase != CN_CONE {
            c = cn_interp(a, fa, b, fb);
        }
        let smp = packed_at(px + tu * c, py + tv * c);
        let f = c - smp.depth;
        // d f / d t along the ray on this bilinear patch: Newton's step is −f / fp.
        let fp = 1.0 - (smp.ddx * tu + smp.ddy * tv);
        let gap = -f;
        let rcp = 1.0 / fp;
        if phase == CN_CONE {
            if f >= 0.0 {
                // Crossed: the crossing lies in [a, c].
                if c <= 0.0 {
                    result = 0.0;
                    break;
                }
                if f <= eps * cn_max(fp, CN_MIN_SLOPE) {
                    // Just below the surface: a Newton step back, no fetch.
                    result = select(c, cn_min(cn_max(c - f * rcp, a), c), fp >= CN_MIN_SLOPE);
                    break;
                }
                if secant == 0u {
                    result = c;
                    break;
                }
                b = c;
                fb = f;
                k = 0;
                phase = CN_REFINE_0;
            } else if fp >= CN_MIN_SLOPE && gap <= eps * fp {
                // Close above the surface: one Newton step on the fetched patch, no fetch.
                result = cn_min(c + gap * rcp, 1.0);
                break;
            } else if k + 1 >= i32(steps) {
                // Out of steps: the best guess without another fetch.
                result = cn_min(c + gap * select(1.0, rcp, fp > 1.0), 1.0);
                break;
            } else {
                a = c;
                fa = f;
                let r = smp.ratio;
                var cone = gap;
                if s > 0.0 {
                    cone = r * gap / (s + r);
                }
                // Near the surface, straight to the Newton estimate of the hit (a fetch there
                // checks it), even beyond the cone.
                var step = cone;
                if fp >= CN_MIN_SLOPE && gap <= eps * fp * CN_JUMP {
                    step = cn_max(cone, gap * rcp);
                }
                t = cn_min(c + cn_max(step, CN_MIN_STEP), 1.0);
                k += 1;
            }
        } else {
            if abs(f) <= eps * cn_max(fp, CN_MIN_SLOPE) {
                result = select(c, cn_min(cn_max(c - f * rcp, a), b), fp >= CN_MIN_SLOPE);
                break;
            }
            if f >= 0.0 {
                b = c;
                fb = f;
                if phase == CN_REFINE_B {
                    fa *= 0.5;
                }
                phase = CN_REFINE_B;
            } else {
                a = c;
                fa = f;
                if phase == CN_REFINE_A {
                    fb *= 0.5;
                }
                phase = CN_REFINE_A;
            }
            k += 1;
            if k >= i32(secant) {
                result = cn_interp(a, fa, b, fb);
                break;
            }
        }
    }
    return Hit(uv0 + dp * result, result, steps);
}
