// Traces a buffer of rays through the ray tracer's interface (rt_closest, rt_any), one ray
// per invocation: the tests' and benchmarks' way to query the GPU structures directly.
// Follows the prelude of either path (bound in group 1).

struct BatchRay {
    origin: vec3<f32>,
    t_min: f32,
    dir: vec3<f32>,
    t_max: f32,
}

struct BatchHit {
    t: f32,
    u: f32,
    v: f32,
    instance: u32,
    primitive: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

struct BatchParams {
    count: u32,
    mask: u32,
    // Invocations per row of the dispatch grid (its x size times the workgroup size).
    row: u32,
    pad: u32,
}

@group(0) @binding(0) var<storage, read> batch_rays: array<BatchRay>;
@group(0) @binding(1) var<storage, read_write> batch_hits: array<BatchHit>;
@group(0) @binding(2) var<uniform> batch: BatchParams;

@compute @workgroup_size(64)
fn closest(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x + id.y * batch.row;
    if i >= batch.count {
        return;
    }
    let r = batch_rays[i];
    let h = rt_closest(r.origin, r.dir, r.t_min, r.t_max, batch.mask);
    batch_hits[i] = BatchHit(h.t, h.u, h.v, h.instance, h.primitive, 0u, 0u, 0u);
}

@compute @workgroup_size(64)
fn any_hit(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x + id.y * batch.row;
    if i >= batch.count {
        return;
    }
    let r = batch_rays[i];
    let hit = rt_any(r.origin, r.dir, r.t_min, r.t_max, batch.mask);
    batch_hits[i] = BatchHit(0.0, 0.0, 0.0, select(RT_NO_HIT, 0u, hit), 0u, 0u, 0u, 0u);
}
