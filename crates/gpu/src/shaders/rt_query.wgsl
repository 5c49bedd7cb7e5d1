enable wgpu_ray_query;

// The query path of the GPU ray tracer: the driver's acceleration structures (one bottom
// level per mesh, a top level over the live instances; see rt/query.rs) queried with
// `rayQuery`. The `enable` directive above must open the module, so this prelude comes
// first in every shader that uses it.
//
// rt/query.rs puts after the directive RT_QUERY_EMPTY (whether the top level holds no
// instance) and writes the bind group's index for RT_GROUP.
//
// The driver reports, for the committed triangle, its distance in the world ray's units,
// DXR's barycentrics (the weights of the second and third vertex), the instance's custom
// index (the CPU instance index) and the primitive index within the driver's bottom level,
// which rt_prims maps back to the triangle's index in its mesh: bottom level m's triangles
// are listed from rt_prims[rt_mesh_base[instance]] on.

const RT_NO_HIT: u32 = 0xffffffffu;
const RT_BIG: f32 = 3.0e38;

@group(RT_GROUP) @binding(0) var rt_scene: acceleration_structure;
// Per instance: where its mesh's primitive map starts in rt_prims.
@group(RT_GROUP) @binding(1) var<storage, read> rt_mesh_base: array<u32>;
// Per driver triangle of each mesh: its index in the mesh.
@group(RT_GROUP) @binding(2) var<storage, read> rt_prims: array<u32>;

struct RtHit {
    t: f32,
    u: f32,
    v: f32,
    instance: u32,
    primitive: u32,
}

fn rt_finite3(x: vec3<f32>) -> bool {
    return all(abs(x) <= vec3<f32>(RT_BIG));
}

// The CPU's rays that hit nothing (an origin or direction not finite, a zero direction, an
// empty or NaN interval), which Vulkan also forbids handing to a ray query; and a mask that
// selects no instance. `t_min` and `t_max` are the interval after clamping.
fn rt_query_ok(origin: vec3<f32>, dir: vec3<f32>, t_min_in: f32, t_max_in: f32, t_min: f32, t_max: f32, mask: u32) -> bool {
    return !RT_QUERY_EMPTY && (mask & 0xffu) != 0u && rt_finite3(origin) && rt_finite3(dir)
        && any(dir != vec3<f32>(0.0)) && t_min_in == t_min_in && t_max_in == t_max_in
        && t_min <= t_max;
}

fn rt_closest(origin: vec3<f32>, dir: vec3<f32>, t_min_in: f32, t_max_in: f32, mask: u32) -> RtHit {
    let t_min = max(t_min_in, 0.0);
    let t_max = min(t_max_in, RT_BIG);
    var best = RtHit(t_max, 0.0, 0.0, RT_NO_HIT, RT_NO_HIT);
    if !rt_query_ok(origin, dir, t_min_in, t_max_in, t_min, t_max, mask) {
        return best;
    }
    var rq: ray_query;
    rayQueryInitialize(&rq, rt_scene, RayDesc(RAY_FLAG_FORCE_OPAQUE, mask & 0xffu, t_min, t_max, origin, dir));
    // Every triangle is opaque: the traversal commits hits itself, and Proceed returns false
    // once it is done.
    loop {
        if !rayQueryProceed(&rq) {
            break;
        }
    }
    let h = rayQueryGetCommittedIntersection(&rq);
    if h.kind == RAY_QUERY_INTERSECTION_TRIANGLE {
        let i = h.instance_custom_data;
        best = RtHit(h.t, h.barycentrics.x, h.barycentrics.y, i, rt_prims[rt_mesh_base[i] + h.primitive_index]);
    }
    return best;
}

fn rt_any(origin: vec3<f32>, dir: vec3<f32>, t_min_in: f32, t_max_in: f32, mask: u32) -> bool {
    let t_min = max(t_min_in, 0.0);
    let t_max = min(t_max_in, RT_BIG);
    if !rt_query_ok(origin, dir, t_min_in, t_max_in, t_min, t_max, mask) {
        return false;
    }
    var rq: ray_query;
    let flags = RAY_FLAG_FORCE_OPAQUE | RAY_FLAG_TERMINATE_ON_FIRST_HIT;
    rayQueryInitialize(&rq, rt_scene, RayDesc(flags, mask & 0xffu, t_min, t_max, origin, dir));
    loop {
        if !rayQueryProceed(&rq) {
            break;
        }
    }
    return rayQueryGetCommittedIntersection(&rq).kind != RAY_QUERY_INTERSECTION_NONE;
}
