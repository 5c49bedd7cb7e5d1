//! Process set-up before any thread starts: quieting Mesa's Vulkan device-select layer.

/// Turns off Mesa's implicit Vulkan layer `VK_LAYER_MESA_device_select` for this process
/// where it would print `error: XDG_RUNTIME_DIR is invalid or not set in the environment.`
/// (twice, on every GPU, viewer and report run, success included).
///
/// The layer reorders the Vulkan devices so that the desktop's default GPU comes first; to
/// find it, it opens a Wayland connection, and libwayland prints that line when
/// `XDG_RUNTIME_DIR` is unset or not an absolute path (ssh sessions, containers, CI), the
/// connection then failing anyway. renderlab ranks the adapters itself
/// (`renderlab_gpu::context::rank`), so the layer changes nothing it chooses. Its manifest
/// (`/usr/share/vulkan/implicit_layer.d/VkLayer_MESA_device_select.json`) names
/// `disable_environment: NODEVICE_SELECT=1`, which the Vulkan loader reads when the instance
/// is created. Left alone: a valid `XDG_RUNTIME_DIR` (no message), a Wayland socket given
/// by absolute path, a user's own `NODEVICE_SELECT`, and `MESA_VK_DEVICE_SELECT` (a device
/// chosen through the layer).
///
/// Must run first in `main`, while the process has one thread: changing the environment
/// while another thread may read it is undefined behaviour in the C library (the wgpu
/// instance, rayon's pool and the window library all start threads later).
pub fn quiet_device_select_layer() {
    let set = |name: &str| std::env::var_os(name).is_some_and(|v| !v.is_empty());
    let absolute = |name: &str| std::env::var_os(name).is_some_and(|v| v.to_string_lossy().starts_with('/'));
    if set("NODEVICE_SELECT") || set("MESA_VK_DEVICE_SELECT") || absolute("XDG_RUNTIME_DIR") {
        return;
    }
    if absolute("WAYLAND_DISPLAY") {
        return;
    }
    std::env::set_var("NODEVICE_SELECT", "1");
}
