// The scene's mesh as the compute pipeline reads it: the fragment pipeline's vertex and index
// buffers bound as storage, and one record per object. The including module writes its
// bind group's index for MESH_GROUP; binding 0 of that group is the visibility buffer, whose
// access each module declares itself.
//
// The visibility buffer holds one vec2<u32> per pixel, row 0 first: x the object whose
// surface the pixel shows (VIS_NONE where none), y the triangle's index in that object's
// mesh. Where on the triangle follows from the pixel's camera ray (`compute.wgsl`).

const VIS_NONE: u32 = 0xffffffffu;

// Vertices as `GpuVertex`: position (3), normal (3), uv (2), tangent (4), twelve floats.
@group(MESH_GROUP) @binding(1) var<storage, read> mesh_vertices: array<f32>;
// Three indices per triangle, already offset to the shared vertex buffer.
@group(MESH_GROUP) @binding(2) var<storage, read> mesh_indices: array<u32>;
// Per object: x its first index in mesh_indices, y its material.
@group(MESH_GROUP) @binding(3) var<storage, read> mesh_objects: array<vec2<u32>>;

struct MeshVertex {
    position: vec3<f32>,
    normal: vec3<f32>,
    uv: vec2<f32>,
    tangent: vec4<f32>,
}

fn mesh_vertex(i: u32) -> MeshVertex {
    let b = 12u * i;
    let f = &mesh_vertices;
    var v: MeshVertex;
    v.position = vec3<f32>((*f)[b], (*f)[b + 1u], (*f)[b + 2u]);
    v.normal = vec3<f32>((*f)[b + 3u], (*f)[b + 4u], (*f)[b + 5u]);
    v.uv = vec2<f32>((*f)[b + 6u], (*f)[b + 7u]);
    v.tangent = vec4<f32>((*f)[b + 8u], (*f)[b + 9u], (*f)[b + 10u], (*f)[b + 11u]);
    return v;
}

// The index in mesh_indices of the first vertex of triangle `primitive` of `object`.
fn mesh_first_index(object: u32, primitive: u32) -> u32 {
    return mesh_objects[object].x + 3u * primitive;
}

// The direction of the camera ray through pixel position `p` (see `Frame.ray_base`).
fn camera_ray(p: vec2<f32>) -> vec3<f32> {
    return frame.ray_base.xyz + p.x * frame.ray_dx.xyz + p.y * frame.ray_dy.xyz;
}
