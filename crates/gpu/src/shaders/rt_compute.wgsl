// The compute path of the GPU ray tracer: the CPU's two-level 8-wide BVH, uploaded as it is
// (see rt/compute.rs for the buffers), walked one ray per invocation with the CPU's slab
// test (Ize's conservative far distance, NaN-ignoring min/max) and the CPU's watertight
// triangle test, four children or four triangles at a time in vec4 lanes.
//
// rt/compute.rs puts before this file the constants of one structure: RT_IZE (1 + 2γ₃, Ize's
// factor for the far slab distance, the CPU's), RT_TLAS_ROOT, and the stack depths
// RT_TLAS_STACK and RT_BLAS_STACK (7 entries per wide level of the deepest hierarchy, plus
// one: what a closest-hit walk can push); and writes the bind group's index for RT_GROUP.

const RT_NO_HIT: u32 = 0xffffffffu;
const RT_LEAF: u32 = 0x80000000u;
const RT_EMPTY: u32 = 0xffffffffu;
// Zero direction components are replaced by this, with their sign: the reciprocal stays
// finite (GPUs need not give ∞ for 1/0 nor NaN for 0·∞), and a ray lying in a slab's plane
// still counts as inside it, as on the CPU.
const RT_TINY: f32 = 1e-30;
const RT_BIG: f32 = 3.0e38;

// One wide node: rows of the children's bounds (min x, max x, min y, max y, min z, max z), each
// row eight floats as two vec4s, then the eight child references.
struct RtNode {
    b: array<vec4<f32>, 12>,
    c: array<vec4<u32>, 2>,
}

// Four triangles: v[3·j + axis] holds coordinate `axis` of vertex j of each lane's triangle.
struct RtBlock {
    v: array<vec4<f32>, 9>,
    prim: vec4<u32>,
}

// An instance: world to object as three rows of a 3×4 matrix, its mesh's root reference and
// where its mesh's nodes and blocks start, and its inclusion mask.
struct RtInstance {
    r0: vec4<f32>,
    r1: vec4<f32>,
    r2: vec4<f32>,
    root: u32,
    node_base: u32,
    block_base: u32,
    mask: u32,
}

@group(RT_GROUP) @binding(0) var<storage, read> rt_nodes: array<RtNode>;
@group(RT_GROUP) @binding(1) var<storage, read> rt_blocks: array<RtBlock>;
@group(RT_GROUP) @binding(2) var<storage, read> rt_instances: array<RtInstance>;

struct RtHit {
    t: f32,
    u: f32,
    v: f32,
    instance: u32,
    primitive: u32,
}

// A ray in the forms the two tests need.
struct RtRay {
    org: vec3<f32>,
    inv: vec3<f32>,
    neg: vec3<bool>,
    t_min: f32,
    k: vec3<u32>,
    shear: vec3<f32>,
    ok: bool,
}

// x86's maxps/minps, as the CPU kernels: the second operand when the first is NaN.
fn rt_max4(a: vec4<f32>, b: vec4<f32>) -> vec4<f32> {
    return select(b, a, a > b);
}

fn rt_min4(a: vec4<f32>, b: vec4<f32>) -> vec4<f32> {
    return select(b, a, a < b);
}

// NaN by its bits: compilers may assume x == x.
fn rt_is_nan(x: f32) -> bool {
    return (bitcast<u32>(x) & 0x7fffffffu) > 0x7f800000u;
}

fn rt_finite3(x: vec3<f32>) -> bool {
    return all(abs(x) <= vec3<f32>(RT_BIG));
}

fn rt_prepare(org: vec3<f32>, dir: vec3<f32>, t_min: f32, t_max: f32) -> RtRay {
    var r: RtRay;
    r.ok = rt_finite3(org) && rt_finite3(dir) && any(dir != vec3<f32>(0.0)) && t_min <= t_max;
    r.org = org;
    r.t_min = t_min;
    let s = select(vec3<f32>(1.0), vec3<f32>(-1.0), dir < vec3<f32>(0.0));
    let d = select(dir, s * RT_TINY, dir == vec3<f32>(0.0));
    r.inv = vec3<f32>(1.0) / d;
    r.neg = r.inv < vec3<f32>(0.0);
    let a = abs(dir);
    var kz = 2u;
    if a.x > a.y && a.x > a.z {
        kz = 0u;
    } else if a.y > a.z {
        kz = 1u;
    }
    var kx = (kz + 1u) % 3u;
    var ky = (kx + 1u) % 3u;
    if dir[kz] < 0.0 {
        let tmp = kx;
        kx = ky;
        ky = tmp;
    }
    r.k = vec3<u32>(kx, ky, kz);
    r.shear = vec3<f32>(dir[kx] / dir[kz], dir[ky] / dir[kz], 1.0 / dir[kz]);
    return r;
}

// The slab test of children 4h … 4h+3 of node n: entry distances, and which are entered
// (as a vec4 of 0/1 so that the caller can count).
struct RtSlabs {
    near: vec4<f32>,
    hit: vec4<bool>,
}

fn rt_slabs(n: u32, h: u32, r: RtRay, t_max: f32) -> RtSlabs {
    let lox = rt_nodes[n].b[h];
    let hix = rt_nodes[n].b[2u + h];
    let loy = rt_nodes[n].b[4u + h];
    let hiy = rt_nodes[n].b[6u + h];
    let loz = rt_nodes[n].b[8u + h];
    let hiz = rt_nodes[n].b[10u + h];
    let nx = (select(lox, hix, r.neg.x) - r.org.x) * r.inv.x;
    let fx = (select(hix, lox, r.neg.x) - r.org.x) * r.inv.x;
    let ny = (select(loy, hiy, r.neg.y) - r.org.y) * r.inv.y;
    let fy = (select(hiy, loy, r.neg.y) - r.org.y) * r.inv.y;
    let nz = (select(loz, hiz, r.neg.z) - r.org.z) * r.inv.z;
    let fz = (select(hiz, loz, r.neg.z) - r.org.z) * r.inv.z;
    let near = rt_max4(nx, rt_max4(ny, rt_max4(nz, vec4<f32>(r.t_min))));
    let far = rt_min4(fx, rt_min4(fy, rt_min4(fz, vec4<f32>(t_max)))) * RT_IZE;
    var s: RtSlabs;
    s.near = near;
    s.hit = near <= far;
    return s;
}

// The watertight test of the four triangles of block b: distances and barycentrics per lane,
// and which lanes hit within [t_min, t_max].
struct RtTris {
    t: vec4<f32>,
    u: vec4<f32>,
    v: vec4<f32>,
    hit: vec4<bool>,
}

fn rt_block(b: u32, r: RtRay, t_max: f32) -> RtTris {
    let kx = r.k.x;
    let ky = r.k.y;
    let kz = r.k.z;
    let o = r.org;
    let a_x = rt_blocks[b].v[kx] - o[kx];
    let a_y = rt_blocks[b].v[ky] - o[ky];
    let a_z = rt_blocks[b].v[kz] - o[kz];
    let b_x = rt_blocks[b].v[3u + kx] - o[kx];
    let b_y = rt_blocks[b].v[3u + ky] - o[ky];
    let b_z = rt_blocks[b].v[3u + kz] - o[kz];
    let c_x = rt_blocks[b].v[6u + kx] - o[kx];
    let c_y = rt_blocks[b].v[6u + ky] - o[ky];
    let c_z = rt_blocks[b].v[6u + kz] - o[kz];
    let sx = r.shear.x;
    let sy = r.shear.y;
    let sz = r.shear.z;
    let ax = a_x - sx * a_z;
    let ay = a_y - sy * a_z;
    let bx = b_x - sx * b_z;
    let by = b_y - sy * b_z;
    let cx = c_x - sx * c_z;
    let cy = c_y - sy * c_z;
    let eu = cx * by - cy * bx;
    let ev = ax * cy - ay * cx;
    let ew = bx * ay - by * ax;
    let zero = vec4<f32>(0.0);
    let neg = (eu < zero) | (ev < zero) | (ew < zero);
    let pos = (eu > zero) | (ev > zero) | (ew > zero);
    let det = eu + ev + ew;
    let tt = eu * (sz * a_z) + ev * (sz * b_z) + ew * (sz * c_z);
    let safe = select(det, vec4<f32>(1.0), det == zero);
    let rcp = vec4<f32>(1.0) / safe;
    var out: RtTris;
    out.t = tt * rcp;
    out.u = ev * rcp;
    out.v = ew * rcp;
    let used = rt_blocks[b].prim != vec4<u32>(RT_NO_HIT);
    out.hit = used & !(neg & pos) & (det != zero) & (out.t >= vec4<f32>(r.t_min)) & (out.t <= vec4<f32>(t_max));
    return out;
}

// Hit::precedes: nearer, and at equal distances the smaller (instance, primitive).
fn rt_precedes(t: f32, instance: u32, primitive: u32, best: RtHit) -> bool {
    return t < best.t || (t == best.t && (instance < best.instance || (instance == best.instance && primitive < best.primitive)));
}

// The ray of instance i in its object space (the direction not renormalised).
fn rt_enter(i: u32, org: vec3<f32>, dir: vec3<f32>, t_min: f32, t_max: f32) -> RtRay {
    let m = rt_instances[i];
    let o = vec3<f32>(dot(m.r0.xyz, org) + m.r0.w, dot(m.r1.xyz, org) + m.r1.w, dot(m.r2.xyz, org) + m.r2.w);
    let d = vec3<f32>(dot(m.r0.xyz, dir), dot(m.r1.xyz, dir), dot(m.r2.xyz, dir));
    return rt_prepare(o, d, t_min, t_max);
}

// The closest hit in instance i's mesh, lowering best and *t_max.
fn rt_blas_closest(i: u32, r: RtRay, best: ptr<function, RtHit>, t_max: ptr<function, f32>) {
    let root = rt_instances[i].root;
    if root == RT_EMPTY {
        return;
    }
    let nb = rt_instances[i].node_base;
    let bb = rt_instances[i].block_base;
    var stack_node: array<u32, RT_BLAS_STACK>;
    var stack_dist: array<f32, RT_BLAS_STACK>;
    var sp = 0u;
    var cur = root;
    loop {
        if (cur & RT_LEAF) == 0u {
            let n = nb + cur;
            var kids: array<u32, 8>;
            var dists: array<f32, 8>;
            var count = 0u;
            for (var h = 0u; h < 2u; h++) {
                let s = rt_slabs(n, h, r, *t_max);
                let c = rt_nodes[n].c[h];
                for (var l = 0u; l < 4u; l++) {
                    if s.hit[l] {
                        // Insertion by entry distance, farthest first.
                        var j = count;
                        while j > 0u && dists[j - 1u] < s.near[l] {
                            kids[j] = kids[j - 1u];
                            dists[j] = dists[j - 1u];
                            j--;
                        }
                        kids[j] = c[l];
                        dists[j] = s.near[l];
                        count++;
                    }
                }
            }
            if count > 0u {
                for (var j = 0u; j + 1u < count; j++) {
                    stack_node[sp] = kids[j];
                    stack_dist[sp] = dists[j];
                    sp++;
                }
                cur = kids[count - 1u];
                continue;
            }
        } else {
            let b = bb + (cur & ~RT_LEAF);
            let tris = rt_block(b, r, *t_max);
            let prims = rt_blocks[b].prim;
            for (var l = 0u; l < 4u; l++) {
                if tris.hit[l] && rt_precedes(tris.t[l], i, prims[l], *best) {
                    *best = RtHit(tris.t[l], tris.u[l], tris.v[l], i, prims[l]);
                    *t_max = tris.t[l];
                }
            }
        }
        // Pop the nearest pending entry still within reach.
        var next = RT_EMPTY;
        while sp > 0u {
            sp--;
            if stack_dist[sp] <= *t_max * RT_IZE {
                next = stack_node[sp];
                break;
            }
        }
        if next == RT_EMPTY {
            break;
        }
        cur = next;
    }
}

// Whether instance i's mesh has any hit before t_max.
fn rt_blas_any(i: u32, r: RtRay, t_max: f32) -> bool {
    let root = rt_instances[i].root;
    if root == RT_EMPTY {
        return false;
    }
    let nb = rt_instances[i].node_base;
    let bb = rt_instances[i].block_base;
    var stack: array<u32, RT_BLAS_STACK>;
    var sp = 0u;
    var cur = root;
    loop {
        if (cur & RT_LEAF) == 0u {
            let n = nb + cur;
            var first = RT_EMPTY;
            for (var h = 0u; h < 2u; h++) {
                let s = rt_slabs(n, h, r, t_max);
                let c = rt_nodes[n].c[h];
                for (var l = 0u; l < 4u; l++) {
                    if s.hit[l] {
                        if first == RT_EMPTY {
                            first = c[l];
                        } else {
                            stack[sp] = c[l];
                            sp++;
                        }
                    }
                }
            }
            if first != RT_EMPTY {
                cur = first;
                continue;
            }
        } else {
            let tris = rt_block(bb + (cur & ~RT_LEAF), r, t_max);
            if any(tris.hit) {
                return true;
            }
        }
        if sp == 0u {
            return false;
        }
        sp--;
        cur = stack[sp];
    }
    return false;
}

fn rt_closest(origin: vec3<f32>, dir: vec3<f32>, t_min_in: f32, t_max_in: f32, mask: u32) -> RtHit {
    let t_min = max(t_min_in, 0.0);
    var t_max = min(t_max_in, RT_BIG);
    var best = RtHit(t_max, 0.0, 0.0, RT_NO_HIT, RT_NO_HIT);
    let r = rt_prepare(origin, dir, t_min, t_max);
    if !r.ok || RT_TLAS_ROOT == RT_EMPTY || rt_is_nan(t_min_in) || rt_is_nan(t_max_in) {
        return best;
    }
    var stack_node: array<u32, RT_TLAS_STACK>;
    var stack_dist: array<f32, RT_TLAS_STACK>;
    var sp = 0u;
    var cur = RT_TLAS_ROOT;
    loop {
        if (cur & RT_LEAF) == 0u {
            var kids: array<u32, 8>;
            var dists: array<f32, 8>;
            var count = 0u;
            for (var h = 0u; h < 2u; h++) {
                let s = rt_slabs(cur, h, r, t_max);
                let c = rt_nodes[cur].c[h];
                for (var l = 0u; l < 4u; l++) {
                    if s.hit[l] {
                        var j = count;
                        while j > 0u && dists[j - 1u] < s.near[l] {
                            kids[j] = kids[j - 1u];
                            dists[j] = dists[j - 1u];
                            j--;
                        }
                        kids[j] = c[l];
                        dists[j] = s.near[l];
                        count++;
                    }
                }
            }
            if count > 0u {
                for (var j = 0u; j + 1u < count; j++) {
                    stack_node[sp] = kids[j];
                    stack_dist[sp] = dists[j];
                    sp++;
                }
                cur = kids[count - 1u];
                continue;
            }
        } else {
            let i = cur & ~RT_LEAF;
            if (rt_instances[i].mask & mask) != 0u {
                let ri = rt_enter(i, origin, dir, t_min, t_max);
                if ri.ok {
                    rt_blas_closest(i, ri, &best, &t_max);
                }
            }
        }
        var next = RT_EMPTY;
        while sp > 0u {
            sp--;
            if stack_dist[sp] <= t_max * RT_IZE {
                next = stack_node[sp];
                break;
            }
        }
        if next == RT_EMPTY {
            break;
        }
        cur = next;
    }
    return best;
}

fn rt_any(origin: vec3<f32>, dir: vec3<f32>, t_min_in: f32, t_max_in: f32, mask: u32) -> bool {
    let t_min = max(t_min_in, 0.0);
    let t_max = min(t_max_in, RT_BIG);
    let r = rt_prepare(origin, dir, t_min, t_max);
    if !r.ok || RT_TLAS_ROOT == RT_EMPTY || rt_is_nan(t_min_in) || rt_is_nan(t_max_in) {
        return false;
    }
    var stack: array<u32, RT_TLAS_STACK>;
    var sp = 0u;
    var cur = RT_TLAS_ROOT;
    loop {
        if (cur & RT_LEAF) == 0u {
            var first = RT_EMPTY;
            for (var h = 0u; h < 2u; h++) {
                let s = rt_slabs(cur, h, r, t_max);
                let c = rt_nodes[cur].c[h];
                for (var l = 0u; l < 4u; l++) {
                    if s.hit[l] {
                        if first == RT_EMPTY {
                            first = c[l];
                        } else {
                            stack[sp] = c[l];
                            sp++;
                        }
                    }
                }
            }
            if first != RT_EMPTY {
                cur = first;
                continue;
            }
        } else {
            let i = cur & ~RT_LEAF;
            if (rt_instances[i].mask & mask) != 0u {
                let ri = rt_enter(i, origin, dir, t_min, t_max);
                if ri.ok && rt_blas_any(i, ri, t_max) {
                    return true;
                }
            }
        }
        if sp == 0u {
            return false;
        }
        sp--;
        cur = stack[sp];
    }
    return false;
}
