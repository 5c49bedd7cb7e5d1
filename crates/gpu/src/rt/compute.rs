//! The compute path: the CPU's two-level BVH copied to storage buffers as it is, and the WGSL
//! walk in `shaders/rt_compute.wgsl`.
//!
//! # Layout
//!
//! The 8-wide nodes are uploaded in the CPU's node layout less its padding (224 bytes: six rows
//! of eight child bounds, then eight child references), from the separate-array form of each
//! mesh's hierarchy (`Blas::indexed`), so the GPU walks the very tree the CPU walks. One node
//! buffer holds the top level first, then every mesh's nodes; one block buffer every mesh's
//! 4-triangle leaf blocks (160 bytes, vertices in structure-of-arrays form); an instance record
//! (64 bytes) holds the world-to-object rows, the mesh's root reference, where its nodes and
//! blocks start, and its mask. Child references stay local to their mesh, and the walk adds the
//! instance's bases. A wide node's six rows read as twelve `vec4`s, so one visit is six slab
//! tests of four children at a time; a block's rows are the four triangles' coordinates, so the
//! triangle test runs on four lanes.
//!
//! # Agreement with the CPU
//!
//! The same tree, the same slab test (Ize's conservative far distance, the NaN-ignoring
//! min/max written with `select`) and the same watertight triangle test, operation for
//! operation, with the same tie rule among equal distances. Differences are the GPU's
//! arithmetic: WGSL lets the compiler fuse a multiply and an add, the instance transform is
//! computed as three dot products where glam adds columns, and the exact f64 recomputation of
//! edge functions that round to zero is left out (no f64 on most GPUs; a zero edge function
//! counts as on the edge, which keeps the test watertight). The crate's tests state the
//! bounds that follow.
//!
//! # Stack
//!
//! A closest-hit walk pushes at most seven entries per wide level, so a stack of
//! `7·depth + 1` entries never overflows; the depths of the top level and of the deepest
//! mesh are measured at upload and written into the shader as constants, and a hierarchy
//! deeper than [`MAX_STACK`] allows is refused.

use super::accel::{AccelStats, GpuAccel, ALL_INSTANCES};
use super::path::RtPath;
use crate::context::GpuContext;
use crate::error::{GpuError, Result};
use crate::layout::storage_entry;
use renderlab_trace::node::{TriBlock, WideNode, EMPTY, WIDTH};
use renderlab_trace::traverse::backend::IZE;
use renderlab_trace::Tlas;
use std::time::Instant;
use wgpu::util::DeviceExt;

/// The WGSL walk.
pub const WGSL: &str = include_str!("../shaders/rt_compute.wgsl");

/// The largest per-invocation stack the walk is built with (entries of each level's stack).
pub const MAX_STACK: usize = 256;

/// Bytes of one uploaded wide node.
pub const NODE_BYTES: usize = 224;
/// Bytes of one uploaded leaf block.
pub const BLOCK_BYTES: usize = 160;
/// Bytes of one uploaded instance.
pub const INSTANCE_BYTES: usize = 64;

/// A wide node as 56 words: the bound rows, then the child references (local to the node's
/// level: the walk adds the instance's base).
fn node_words(n: &WideNode, out: &mut Vec<u32>) {
    for row in &n.bounds {
        out.extend(row.iter().map(|x| x.to_bits()));
    }
    out.extend_from_slice(&n.children);
}

fn block_words(b: &TriBlock, out: &mut Vec<u32>) {
    for row in &b.v {
        out.extend(row.iter().map(|x| x.to_bits()));
    }
    out.extend_from_slice(&b.prim);
}

/// Wide levels on the longest path from `root` (0 for a leaf or an empty hierarchy).
fn depth(nodes: &[WideNode], root: u32) -> usize {
    renderlab_trace::node::depth(nodes, root)
}

/// The buffers and constants of `tlas`, before they reach a device.
pub struct Flattened {
    /// Every node: the top level's, then each mesh's.
    pub nodes: Vec<u32>,
    /// Every leaf block, mesh after mesh.
    pub blocks: Vec<u32>,
    /// One record per instance.
    pub instances: Vec<u32>,
    /// The top level's root reference.
    pub tlas_root: u32,
    /// Stack entries the top-level walk needs.
    pub tlas_stack: usize,
    /// Stack entries the deepest bottom-level walk needs.
    pub blas_stack: usize,
    /// Triangles in the bottom levels.
    pub triangles: usize,
}

/// Flattens `tlas` into the compute path's buffers; `masks[i]` is instance `i`'s mask.
pub fn flatten(tlas: &Tlas, masks: &[u8]) -> Flattened {
    let mut nodes = Vec::new();
    for n in tlas.nodes() {
        node_words(n, &mut nodes);
    }
    let mut node_base = Vec::with_capacity(tlas.meshes().len());
    let mut block_base = Vec::with_capacity(tlas.meshes().len());
    let mut blocks = Vec::new();
    let (mut blas_depth, mut triangles) = (0, 0);
    let mut roots = Vec::with_capacity(tlas.meshes().len());
    for mesh in tlas.meshes() {
        node_base.push((nodes.len() / (NODE_BYTES / 4)) as u32);
        block_base.push((blocks.len() / (BLOCK_BYTES / 4)) as u32);
        let tree = mesh.indexed();
        for n in &tree.nodes {
            node_words(n, &mut nodes);
        }
        for b in &tree.blocks {
            block_words(b, &mut blocks);
        }
        blas_depth = blas_depth.max(depth(&tree.nodes, tree.root));
        roots.push(tree.root);
        triangles += mesh.hittable_count();
    }
    let mut instances = Vec::with_capacity(tlas.placed().len() * INSTANCE_BYTES / 4);
    for (i, p) in tlas.placed().iter().enumerate() {
        let m = p.world_to_object;
        let (c, t) = (m.matrix3, m.translation);
        for r in 0..3 {
            instances.extend([c.x_axis[r], c.y_axis[r], c.z_axis[r], t[r]].map(f32::to_bits));
        }
        let mesh = p.mesh as usize;
        let root = roots.get(mesh).copied().unwrap_or(EMPTY);
        let mask = masks.get(i).copied().unwrap_or(ALL_INSTANCES as u8) as u32;
        instances.extend([root, node_base[mesh], block_base[mesh], mask]);
    }
    let stack = |d: usize| (WIDTH - 1) * d + 1;
    Flattened {
        nodes,
        blocks,
        instances,
        tlas_root: tlas.root(),
        tlas_stack: stack(depth(tlas.nodes(), tlas.root())),
        blas_stack: stack(blas_depth),
        triangles,
    }
}

impl Flattened {
    /// The WGSL prelude for bind group `group`: this structure's constants and the walk.
    pub fn wgsl(&self, group: u32) -> String {
        format!(
            "const RT_IZE: f32 = {IZE:?};\nconst RT_TLAS_ROOT: u32 = {}u;\nconst RT_TLAS_STACK: u32 = {}u;\nconst RT_BLAS_STACK: u32 = {}u;\n{}",
            self.tlas_root,
            self.tlas_stack,
            self.blas_stack,
            WGSL.replace("RT_GROUP", &group.to_string())
        )
    }
}

/// The bind group layout of the compute path: three read-only storage buffers.
fn layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let entry =
        |binding| storage_entry(binding, true, wgpu::ShaderStages::COMPUTE | wgpu::ShaderStages::FRAGMENT);
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("rt compute"),
        entries: &[entry(0), entry(1), entry(2)],
    })
}

/// Builds the compute path's [`GpuAccel`] (see [`GpuAccel::build`]).
pub(crate) fn build(ctx: &GpuContext, tlas: &Tlas, masks: &[u8], group: u32) -> Result<GpuAccel> {
    let start = Instant::now();
    let flat = flatten(tlas, masks);
    if flat.tlas_stack > MAX_STACK || flat.blas_stack > MAX_STACK {
        return Err(GpuError::Scene(format!(
            "the scene's BVH needs a traversal stack of {} entries, more than the GPU walk's {MAX_STACK}",
            flat.tlas_stack.max(flat.blas_stack)
        )));
    }
    let limits = ctx.device.limits();
    let max = limits.max_storage_buffer_binding_size.min(limits.max_buffer_size);
    let mut bytes = 0u64;
    let mut buffer = |label: &str, words: &[u32], unit: usize| -> Result<wgpu::Buffer> {
        let size = words.len() as u64 * 4;
        if size > max {
            return Err(GpuError::Scene(format!(
                "the scene's {label} take {size} bytes, over this device's {max}-byte storage buffers"
            )));
        }
        bytes += size;
        // A binding may not be empty: an empty level gets one unused record.
        let padded;
        let contents: &[u32] = if words.is_empty() {
            padded = vec![0u32; unit / 4];
            &padded
        } else {
            words
        };
        Ok(ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytemuck::cast_slice(contents),
            usage: wgpu::BufferUsages::STORAGE,
        }))
    };
    let nodes = buffer("BVH nodes", &flat.nodes, NODE_BYTES)?;
    let blocks = buffer("BVH leaf blocks", &flat.blocks, BLOCK_BYTES)?;
    let instances = buffer("BVH instances", &flat.instances, INSTANCE_BYTES)?;
    let layout = layout(&ctx.device);
    let bind_group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("rt compute"),
        layout: &layout,
        entries: &[
            wgpu::BindGroupEntry { binding: 0, resource: nodes.as_entire_binding() },
            wgpu::BindGroupEntry { binding: 1, resource: blocks.as_entire_binding() },
            wgpu::BindGroupEntry { binding: 2, resource: instances.as_entire_binding() },
        ],
    });
    ctx.check()?;
    let stats = AccelStats {
        bytes,
        instances: tlas.placed().len(),
        triangles: flat.triangles,
        build_ms: start.elapsed().as_secs_f64() * 1e3,
    };
    Ok(GpuAccel { path: RtPath::Compute, group, layout, bind_group, wgsl: flat.wgsl(group), stats })
}
