//! The GPU time of egui's own render pass, which eframe records and the viewer cannot give
//! pass-level timestamp writes: two paint callbacks, the first shape of the frame and the
//! last, write a timestamp each from inside that pass (wgpu's
//! `TIMESTAMP_QUERY_INSIDE_PASSES`). Everything egui draws lies between them: the room's
//! picture as a textured quad, the HUD, the split screen's labels. The pass's clear and store
//! lie outside. The pair is resolved in the next frame's egui encoder and read one frame
//! later still, so each reading is two frames old.
//!
//! Not on a software adapter: lavapipe records such a timestamp when it bins the pass's
//! draws, before it rasterizes them, so the pair misses nearly all the work (a small fraction
//! of what pass-level timestamps read for the same pass; `examples/egui_pass.rs` times egui's
//! pass whole on any adapter, and BENCHMARKS.md, "Viewer", has both readings).

use egui_wgpu::{CallbackResources, CallbackTrait, ScreenDescriptor};
use renderlab_gpu::{GpuContext, PassTimer};
use std::sync::{Arc, Mutex};

/// Times egui's pass from inside it (see the module documentation).
#[derive(Clone)]
pub struct EguiPassTimer {
    inner: Arc<Inner>,
}

struct Inner {
    ctx: &'static GpuContext,
    timer: PassTimer,
    state: Mutex<State>,
}

#[derive(Default)]
struct State {
    /// Both marks of a frame were painted and are not yet resolved.
    written: bool,
    /// The read buffer holds a resolved pair not yet read.
    copied: bool,
    /// The last pass time read, in milliseconds.
    last_ms: Option<f64>,
}

impl EguiPassTimer {
    /// A timer, or `None` where the device cannot write timestamps inside a render pass or
    /// is a software adapter (see the module documentation).
    pub fn new(ctx: &'static GpuContext) -> Option<Self> {
        let needed = wgpu::Features::TIMESTAMP_QUERY | wgpu::Features::TIMESTAMP_QUERY_INSIDE_PASSES;
        if ctx.report.software || !ctx.device.features().contains(needed) {
            return None;
        }
        let timer = PassTimer::new(ctx)?;
        Some(Self { inner: Arc::new(Inner { ctx, timer, state: Mutex::new(State::default()) }) })
    }

    /// Adds the frame's first mark: call before anything else is drawn this frame (it goes
    /// first into the background layer, which is painted first).
    pub fn mark_start(&self, ctx: &egui::Context) {
        self.mark(ctx, egui::LayerId::background(), 0);
    }

    /// Adds the frame's last mark: call after everything else is drawn this frame (it goes
    /// into a layer of the topmost order).
    pub fn mark_end(&self, ctx: &egui::Context) {
        self.mark(ctx, egui::LayerId::new(egui::Order::Debug, egui::Id::unique("egui pass timer end")), 1);
    }

    fn mark(&self, ctx: &egui::Context, layer: egui::LayerId, index: u32) {
        // One point: egui skips callbacks without pixels.
        let rect = egui::Rect::from_min_size(egui::Pos2::ZERO, egui::vec2(1.0, 1.0));
        let callback = Mark { index, inner: Arc::clone(&self.inner) };
        ctx.layer_painter(layer).add(egui_wgpu::Callback::new_paint_callback(rect, callback));
    }

    /// The last measured GPU time between the two marks, in milliseconds.
    pub fn last_ms(&self) -> Option<f64> {
        self.inner.state.lock().unwrap_or_else(|p| p.into_inner()).last_ms
    }
}

/// One of the two marks.
struct Mark {
    index: u32,
    inner: Arc<Inner>,
}

impl CallbackTrait for Mark {
    fn prepare(
        &self,
        _device: &wgpu::Device,
        _queue: &wgpu::Queue,
        _screen: &ScreenDescriptor,
        encoder: &mut wgpu::CommandEncoder,
        _resources: &mut CallbackResources,
    ) -> Vec<wgpu::CommandBuffer> {
        if self.index != 0 {
            return Vec::new();
        }
        let inner = &self.inner;
        let mut st = inner.state.lock().unwrap_or_else(|p| p.into_inner());
        if st.copied {
            // Submitted with an earlier frame: this waits for it.
            if let Ok(ms) = inner.timer.read_ms(inner.ctx) {
                st.last_ms = Some(ms);
            }
            st.copied = false;
        }
        if st.written {
            // Before this frame's pass in the same encoder: the last frame's pair.
            inner.timer.resolve(encoder);
            (st.written, st.copied) = (false, true);
        }
        Vec::new()
    }

    fn paint(
        &self,
        _info: egui::PaintCallbackInfo,
        pass: &mut wgpu::RenderPass<'static>,
        _resources: &CallbackResources,
    ) {
        pass.write_timestamp(self.inner.timer.query_set(), self.index);
        if self.index == 1 {
            self.inner.state.lock().unwrap_or_else(|p| p.into_inner()).written = true;
        }
    }
}
