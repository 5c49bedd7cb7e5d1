// The compute pipeline of the relief frame: one invocation per pixel reads the visibility
// buffer (written by `relief_visibility.wgsl`'s ray cast), rebuilds the pixel's surface as
// the rasterizer would have given it at the pixel's centre, and shades it with the same
// `shade` as the fragment pipeline. One dispatch per material: an invocation whose pixel
// shows another material's surface, or none, returns at once (the visibility pass wrote the
// background there).
//
// Outputs are storage textures at the pixel: colour (alpha 1), and for `cs_debug` the
// displaced UV with the pixel-depth offset (the displaced hit's distance from the eye, in z)
// and the planned layer count, as `fs_color` and `fs_debug` write them.

@group(2) @binding(0) var<storage, read> vis_buffer: array<vec2<u32>>;
@group(2) @binding(4) var out_color: texture_storage_2d<rgba32float, write>;
@group(2) @binding(5) var out_uv: texture_storage_2d<rgba32float, write>;
@group(2) @binding(6) var out_layers: texture_storage_2d<r32uint, write>;

// The surface at the centre of `pixel`, on the triangle the visibility buffer names, as the
// rasterizer would give it there. With D(p) the camera ray's direction, affine in the pixel
// position p, the ray meets the triangle's plane (normal n) at x = eye + s·D with
// s = n·(v0 − eye)/(n·D); the barycentric weights of x are g1·(x − v0) and g2·(x − v0) with
// g1 = (e2 × n)/|n|², g2 = (n × e1)/|n|², and the attributes are interpolated with them
// (perspective-correct by construction: they are the weights of the point the ray meets).
// The exact screen Jacobian of UV follows by ray differentials: ∂x/∂p = s·(∂D/∂p −
// D·(n·∂D/∂p)/(n·D)), exact because the plane is flat and D affine, and UV is affine on the
// plane.
fn surface_at(pixel: vec2<u32>, hit: vec2<u32>) -> Surface {
    let first = mesh_first_index(hit.x, hit.y);
    let a = mesh_vertex(mesh_indices[first]);
    let b = mesh_vertex(mesh_indices[first + 1u]);
    let c = mesh_vertex(mesh_indices[first + 2u]);
    let e1 = b.position - a.position;
    let e2 = c.position - a.position;
    let n = cross(e1, e2);
    let nn = dot(n, n);
    let g1 = cross(e2, n) / nn;
    let g2 = cross(n, e1) / nn;
    let d = camera_ray(vec2<f32>(pixel) + 0.5);
    let nd = dot(n, d);
    let depth = dot(n, a.position - frame.eye.xyz) / nd;
    let rel = frame.eye.xyz + depth * d - a.position;
    let u = dot(g1, rel);
    let v = dot(g2, rel);
    let w = 1.0 - u - v;
    let uv = a.uv * w + b.uv * u + c.uv * v;
    let world = a.position * w + b.position * u + c.position * v;
    let normal = a.normal * w + b.normal * u + c.normal * v;
    let tangent = a.tangent * w + b.tangent * u + c.tangent * v;
    let dx = depth * (frame.ray_dx.xyz - d * (dot(n, frame.ray_dx.xyz) / nd));
    let dy = depth * (frame.ray_dy.xyz - d * (dot(n, frame.ray_dy.xyz) / nd));
    let duv1 = b.uv - a.uv;
    let duv2 = c.uv - a.uv;
    let duv_dx = duv1 * dot(g1, dx) + duv2 * dot(g2, dx);
    let duv_dy = duv1 * dot(g1, dy) + duv2 * dot(g2, dy);
    // Per unit of u and v on the triangle: the inverse of its UV edge matrix maps (du, dv) to
    // barycentric steps; position and normal are affine in them. Only for a technique that
    // reads the curvature (`RAY_CONTEXT`).
    let uv_det = duv1.x * duv2.y - duv1.y * duv2.x;
    var curvature = vec2<f32>(0.0);
    if RAY_CONTEXT && uv_det != 0.0 {
        let bu = vec2<f32>(duv2.y, -duv1.y) / uv_det;
        let bv = vec2<f32>(-duv2.x, duv1.x) / uv_det;
        let dn1 = b.normal - a.normal;
        let dn2 = c.normal - a.normal;
        curvature = curvature_of(e1 * bu.x + e2 * bu.y, e1 * bv.x + e2 * bv.y, dn1 * bu.x + dn2 * bu.y, dn1 * bv.x + dn2 * bv.y, normal);
    }
    return surface_from(uv, duv_dx, duv_dy, world, normal, tangent, world_per_uv(e1, e2, duv1, duv2), curvature, hit.x);
}

// The visibility record of `pixel` when it shows this dispatch's material, else VIS_NONE in x.
fn visible(pixel: vec2<u32>) -> vec2<u32> {
    if any(pixel >= frame.size) {
        return vec2<u32>(VIS_NONE);
    }
    let hit = vis_buffer[pixel.y * frame.size.x + pixel.x];
    if hit.x == VIS_NONE || mesh_objects[hit.x].y != material.index {
        return vec2<u32>(VIS_NONE);
    }
    return hit;
}

// The image alone (timed runs).
@compute @workgroup_size(8, 8)
fn cs_color(@builtin(global_invocation_id) id: vec3<u32>) {
    let hit = visible(id.xy);
    if hit.x == VIS_NONE {
        return;
    }
    let s = shade(surface_at(id.xy, hit));
    // A trace that missed the relief shows the background, as the visibility pass writes it.
    textureStore(out_color, id.xy, vec4<f32>(s.color, select(0.0, 1.0, s.covered)));
}

// The image with the debug targets.
@compute @workgroup_size(8, 8)
fn cs_debug(@builtin(global_invocation_id) id: vec3<u32>) {
    let hit = visible(id.xy);
    if hit.x == VIS_NONE {
        return;
    }
    let s = shade(surface_at(id.xy, hit));
    textureStore(out_color, id.xy, vec4<f32>(s.color, select(0.0, 1.0, s.covered)));
    textureStore(out_uv, id.xy, vec4<f32>(s.uv, s.view_depth, 0.0));
    textureStore(out_layers, id.xy, vec4<u32>(s.layers, 0u, 0u, 0u));
}
