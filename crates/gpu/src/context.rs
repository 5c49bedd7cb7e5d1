//! The device: finding an adapter (hardware preferred, a software one such as Mesa's
//! lavapipe allowed), opening it with the features the renderer uses, and reporting what it
//! is, so that every GPU result can say which device produced it.
//!
//! Errors the device raises while running (validation, out of memory) are caught by an error
//! handler and returned by [`GpuContext::check`] instead of wgpu's default panic; a lost
//! device is recorded by the device-lost callback and every later check returns
//! [`GpuError::DeviceLost`].

use crate::error::{GpuError, Result};
use std::sync::{Arc, Mutex};

/// What the adapter is: recorded with every GPU measurement.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AdapterReport {
    /// The adapter's name (`llvmpipe (LLVM 19.1.7, 256 bits)`, `NVIDIA H100 80GB HBM3`).
    pub name: String,
    /// The driver's name (`llvmpipe`, `NVIDIA`).
    pub driver: String,
    /// The driver's version text.
    pub driver_info: String,
    /// The graphics API in use (`vulkan`).
    pub backend: String,
    /// Whether the adapter runs on the CPU (wgpu's `DeviceType::Cpu`): its timings measure a
    /// CPU emulating a GPU, not a GPU.
    pub software: bool,
    /// Whether the device can time passes with timestamp queries.
    pub timestamps: bool,
    /// Whether the device was opened with ray queries (wgpu's `EXPERIMENTAL_RAY_QUERY`): the
    /// GPU ray tracer's query path needs them, its compute path does not.
    pub ray_query: bool,
}

impl std::fmt::Display for AdapterReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} ({} {}, {}", self.name, self.driver, self.driver_info, self.backend)?;
        if self.software {
            f.write_str(", software: a CPU emulating a GPU")?;
        }
        if !self.timestamps {
            f.write_str(", no timestamp queries")?;
        }
        f.write_str(if self.ray_query { ", ray queries" } else { ", no ray queries" })?;
        f.write_str(")")
    }
}

/// An open device and its queue.
pub struct GpuContext {
    /// The wgpu device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// What the adapter is.
    pub report: AdapterReport,
    /// The first error the device raised that no caller has collected yet.
    errors: Arc<Mutex<Option<String>>>,
    /// Why the device was lost, once it has been (it stays lost).
    lost: Arc<Mutex<Option<String>>>,
}

/// Preference order of device types: hardware first, software last (lower is preferred).
pub fn rank(t: wgpu::DeviceType) -> u8 {
    match t {
        wgpu::DeviceType::DiscreteGpu => 0,
        wgpu::DeviceType::IntegratedGpu => 1,
        wgpu::DeviceType::VirtualGpu => 2,
        wgpu::DeviceType::Other => 3,
        wgpu::DeviceType::Cpu => 4,
    }
}

impl GpuContext {
    /// Opens the best Vulkan adapter: a discrete GPU, then an integrated or virtual one, then
    /// a software adapter, with the features of [`GpuContext::features_for`].
    pub fn new() -> Result<Self> {
        // Mesa's device-select layer, loaded with the instance, prints an XDG_RUNTIME_DIR error
        // where there is no desktop session; the renderlab binary turns it off first thing in
        // `main` (a library cannot: changing the environment once threads run is unsound).
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
        desc.backends = wgpu::Backends::VULKAN;
        let instance = wgpu::Instance::new(desc);
        let adapters = pollster::block_on(instance.enumerate_adapters(wgpu::Backends::VULKAN));
        let Some(adapter) = adapters.into_iter().min_by_key(|a| rank(a.get_info().device_type)) else {
            return Err(GpuError::NoAdapter("Vulkan lists no adapter".into()));
        };
        let features = Self::features_for(&adapter)?;
        let device_desc = wgpu::DeviceDescriptor {
            label: Some("renderlab"),
            required_features: features,
            required_limits: adapter.limits(),
            experimental_features: Self::experimental_for(features),
            ..Default::default()
        };
        let name = adapter.get_info().name;
        let (device, queue) = pollster::block_on(adapter.request_device(&device_desc))
            .map_err(|e| GpuError::Device { adapter: name, reason: e.to_string() })?;
        Self::from_parts(&adapter, device, queue)
    }

    /// The features the renderer asks of `adapter`: `FLOAT32_FILTERABLE`, which it needs (its
    /// maps are 32-bit float textures, filtered by the sampler as the CPU filters them), and
    /// timestamp queries where the adapter has them (with timestamps inside passes, where it
    /// has those too), and ray queries (`EXPERIMENTAL_RAY_QUERY`, for the ray tracer's query
    /// path) where it has them. An adapter without the first is refused.
    /// A program that opens the device itself (the viewer, through its window library)
    /// requests these, with [`GpuContext::experimental_for`] of them, so that
    /// [`GpuContext::from_parts`] accepts its device and reports the same capabilities.
    pub fn features_for(adapter: &wgpu::Adapter) -> Result<wgpu::Features> {
        let have = adapter.features();
        if !have.contains(wgpu::Features::FLOAT32_FILTERABLE) {
            return Err(GpuError::MissingFeature {
                adapter: adapter.get_info().name,
                feature: "FLOAT32_FILTERABLE",
                why: "the relief maps need (32-bit float textures filtered as on the CPU)",
            });
        }
        let mut features = wgpu::Features::FLOAT32_FILTERABLE;
        if have.contains(wgpu::Features::TIMESTAMP_QUERY) {
            features |= wgpu::Features::TIMESTAMP_QUERY;
            // The viewer times egui's pass, which it does not own, from inside it.
            if have.contains(wgpu::Features::TIMESTAMP_QUERY_INSIDE_PASSES) {
                features |= wgpu::Features::TIMESTAMP_QUERY_INSIDE_PASSES;
            }
        }
        if have.contains(wgpu::Features::EXPERIMENTAL_RAY_QUERY) {
            features |= wgpu::Features::EXPERIMENTAL_RAY_QUERY;
        }
        Ok(features)
    }

    /// The token a device descriptor requesting `features` needs: wgpu refuses a device whose
    /// features include an experimental one (ray queries) unless the descriptor carries the
    /// enabled token, and the token is given only where one is requested.
    pub fn experimental_for(features: wgpu::Features) -> wgpu::ExperimentalFeatures {
        if features.intersects(wgpu::Features::all_experimental_mask()) {
            // SAFETY: the token is the caller's acceptance that wgpu's experimental features
            // may still have bugs. The renderer requests one, ray queries (`features_for`),
            // used by the ray tracer's query path alone, which builds its structures through
            // wgpu's validated API (no raw instance buffers) and is tested against the CPU's
            // hierarchy; a device without experimental features never gets the token.
            unsafe { wgpu::ExperimentalFeatures::enabled() }
        } else {
            wgpu::ExperimentalFeatures::disabled()
        }
    }

    /// A context over a device that someone else opened on `adapter` (the viewer's window
    /// library opens the device that draws the window, and the renderer must draw on that
    /// same device to hand its frames to the window without a copy through the CPU). The
    /// device must have `FLOAT32_FILTERABLE` (see [`GpuContext::features_for`]); timestamps
    /// and ray queries are used where the device was opened with them. Installs the error handler that
    /// [`GpuContext::check`] reads, in place of wgpu's default panic.
    pub fn from_parts(adapter: &wgpu::Adapter, device: wgpu::Device, queue: wgpu::Queue) -> Result<Self> {
        let info = adapter.get_info();
        let features = device.features();
        if !features.contains(wgpu::Features::FLOAT32_FILTERABLE) {
            return Err(GpuError::MissingFeature {
                adapter: info.name,
                feature: "FLOAT32_FILTERABLE",
                why: "the relief maps need (the device was opened without it)",
            });
        }
        let timestamps = features.contains(wgpu::Features::TIMESTAMP_QUERY);
        let errors = Arc::new(Mutex::new(None::<String>));
        let sink = Arc::clone(&errors);
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            let mut slot = sink.lock().unwrap_or_else(|p| p.into_inner());
            slot.get_or_insert_with(|| one_line(&e.to_string()));
        }));
        let lost = Arc::new(Mutex::new(None::<String>));
        let lost_sink = Arc::clone(&lost);
        device.set_device_lost_callback(move |reason, message| {
            let mut slot = lost_sink.lock().unwrap_or_else(|p| p.into_inner());
            slot.get_or_insert_with(|| format!("{reason:?}: {}", one_line(&message)));
        });
        let report = AdapterReport {
            name: info.name,
            driver: info.driver,
            driver_info: info.driver_info,
            backend: info.backend.to_string(),
            software: info.device_type == wgpu::DeviceType::Cpu,
            timestamps,
            ray_query: features.contains(wgpu::Features::EXPERIMENTAL_RAY_QUERY),
        };
        Ok(Self { device, queue, report, errors, lost })
    }

    /// [`GpuError::DeviceLost`] once the device has been lost (on every call after: a lost
    /// device stays lost), else the first error the device raised since the last check, as
    /// an error; `Ok` if none.
    pub fn check(&self) -> Result<()> {
        if let Some(why) = self.lost.lock().unwrap_or_else(|p| p.into_inner()).as_ref() {
            return Err(GpuError::DeviceLost(why.clone()));
        }
        let mut slot = self.errors.lock().unwrap_or_else(|p| p.into_inner());
        match slot.take() {
            Some(e) => Err(GpuError::Runtime(e)),
            None => Ok(()),
        }
    }

    /// Waits until the device has finished all submitted work.
    pub fn wait(&self) -> Result<()> {
        if let Err(e) = self.device.poll(wgpu::PollType::wait_indefinitely()) {
            // A lost device says so rather than giving the poll's own error.
            self.check()?;
            return Err(GpuError::Runtime(one_line(&e.to_string())));
        }
        self.check()
    }

    /// The largest texture side the device accepts.
    pub fn max_texture_side(&self) -> u32 {
        self.device.limits().max_texture_dimension_2d
    }

    /// Refuses a `width × height` texture named `what` that the device cannot hold.
    pub fn check_size(&self, what: &str, width: u32, height: u32) -> Result<()> {
        let max = self.max_texture_side();
        if width > max || height > max {
            return Err(GpuError::TooLarge { what: what.to_string(), width, height, max });
        }
        Ok(())
    }
}

/// wgpu's multi-line error reports folded into one line.
pub(crate) fn one_line(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}
