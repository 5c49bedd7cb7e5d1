//! A compute stage written outside the frame reads the G-buffer through the shared WGSL
//! and writes a term in place: the path later (ray-traced) stages take.

mod common;

use glam::Vec3;
use renderlab_hybrid::deferred::PreparedScene;
use renderlab_hybrid_gpu::download::read_vec3;
use renderlab_hybrid_gpu::{wgsl, GpuDeferred};

const STAGE: &str = r#"
@group(1) @binding(1) var<storage, read_write> gbuf: array<GPoint>;
@group(1) @binding(3) var<storage, read_write> direct: array<vec4f>;

@compute @workgroup_size(8, 8, 1)
fn normals(@builtin(global_invocation_id) id: vec3u) {
    if id.x >= frame.size.x || id.y >= frame.size.y {
        return;
    }
    let i = pixel_index(id.x, id.y);
    direct[i] = vec4f(unpack_surface(gbuf[i]).n.xyz, 0.0);
}
"#;

#[test]
fn a_stage_over_the_g_buffer_writes_its_term_in_place() {
    let Some(ctx) = common::context() else { return };
    let (scene, camera) = common::scene("showcase", 48, 27);
    let prepared = PreparedScene::new(&scene);
    let mut gpu = GpuDeferred::new(&ctx, &prepared, &common::settings()).unwrap();
    assert!(gpu.bind_groups().is_none(), "no frame yet");
    let frame = gpu.render(&camera).unwrap();
    let module = ctx.device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("normals stage"),
        source: wgpu::ShaderSource::Wgsl(format!("{}\n{STAGE}", wgsl::COMMON).into()),
    });
    let pipeline = ctx.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("normals stage"),
        layout: Some(gpu.compute_layout()),
        module: &module,
        entry_point: Some("normals"),
        compilation_options: Default::default(),
        cache: None,
    });
    let (scene_group, frame_group) = gpu.bind_groups().unwrap();
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, scene_group, &[]);
        pass.set_bind_group(1, frame_group, &[]);
        pass.dispatch_workgroups(camera.width.div_ceil(8), camera.height.div_ceil(8), 1);
    }
    ctx.queue.submit([encoder.finish()]);
    ctx.check().unwrap();
    let targets = gpu.targets().unwrap();
    let written = read_vec3(&ctx, &targets.direct, targets.pixels() as usize).unwrap();
    // The stage read exactly what the frame's read-back decodes.
    for (w, g) in written.iter().zip(&frame.gbuffer) {
        assert_eq!(*w, g.map_or(Vec3::ZERO, |sp| sp.normal));
    }
    assert!(frame.gbuffer.iter().any(Option::is_some));
}
