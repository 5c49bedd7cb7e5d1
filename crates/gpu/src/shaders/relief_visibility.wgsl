// The compute pipeline's primary visibility: one camera ray per pixel centre through the
// scene's BVH (the ray tracer's `rt_closest`, whose prelude comes before this file), keeping
// what the hardware rasterizer keeps: surfaces between the near and far planes, front faces
// only (counter-clockwise on screen; a back face the ray meets first is stepped over, as the
// rasterizer culls it). Writes the visibility buffer (see `relief_mesh.wgsl`), and where no
// surface shows the background, UV 0 and no layers, as the fragment pipeline's clears.

@group(1) @binding(0) var<storage, read_write> vis_buffer: array<vec2<u32>>;
@group(1) @binding(4) var out_color: texture_storage_2d<rgba32float, write>;
@group(1) @binding(5) var out_uv: texture_storage_2d<rgba32float, write>;
@group(1) @binding(6) var out_layers: texture_storage_2d<r32uint, write>;

// Back faces stepped over along one ray before the pixel counts as background.
const VIS_MAX_BACK_FACES: u32 = 16u;

@compute @workgroup_size(8, 8)
fn cs_visibility(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size) {
        return;
    }
    let d = camera_ray(vec2<f32>(id.xy) + 0.5);
    let eye = frame.eye.xyz;
    var t_min = frame.depth_range.x;
    var record = vec2<u32>(VIS_NONE, 0u);
    for (var k = 0u; k < VIS_MAX_BACK_FACES; k++) {
        let hit = rt_closest(eye, d, t_min, frame.depth_range.y, 0xffu);
        if hit.instance == RT_NO_HIT {
            break;
        }
        let first = mesh_first_index(hit.instance, hit.primitive);
        let a = mesh_vertex(mesh_indices[first]).position;
        let b = mesh_vertex(mesh_indices[first + 1u]).position;
        let c = mesh_vertex(mesh_indices[first + 2u]).position;
        if dot(cross(b - a, c - a), d) < 0.0 {
            record = vec2<u32>(hit.instance, hit.primitive);
            break;
        }
        // The next representable distance beyond this back face.
        t_min = bitcast<f32>(bitcast<u32>(hit.t) + 1u);
    }
    vis_buffer[id.y * frame.size.x + id.x] = record;
    if record.x == VIS_NONE {
        textureStore(out_color, id.xy, vec4<f32>(frame.background.xyz, 0.0));
        textureStore(out_uv, id.xy, vec4<f32>(0.0));
        textureStore(out_layers, id.xy, vec4<u32>(0u));
    }
}
