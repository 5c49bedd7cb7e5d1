//! How the lab names the device a record ran on, in its tables and results.

use renderlab_gpu::AdapterReport;

/// How an adapter is named in tables: `CPU-emulated GPU (lavapipe)` for Mesa's lavapipe (the
/// driver reports itself as llvmpipe), `CPU-emulated GPU (NAME)` for another software
/// adapter, `GPU (NAME)` for hardware.
pub fn device_label(report: &AdapterReport) -> String {
    let lavapipe = [&report.name, &report.driver].iter().any(|s| s.to_lowercase().contains("llvmpipe"));
    match (report.software, lavapipe) {
        (true, true) => "CPU-emulated GPU (lavapipe)".to_string(),
        (true, false) => format!("CPU-emulated GPU ({})", report.name),
        (false, _) => format!("GPU ({})", report.name),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn report(name: &str, driver: &str, software: bool) -> AdapterReport {
        AdapterReport {
            name: name.into(),
            driver: driver.into(),
            driver_info: String::new(),
            backend: "vulkan".into(),
            software,
            timestamps: true,
            ray_query: false,
        }
    }

    #[test]
    fn software_adapters_are_labelled_cpu_emulated() {
        assert_eq!(
            device_label(&report("llvmpipe (LLVM 15.0.6, 256 bits)", "llvmpipe", true)),
            "CPU-emulated GPU (lavapipe)"
        );
        assert_eq!(
            device_label(&report("SwiftShader", "swiftshader", true)),
            "CPU-emulated GPU (SwiftShader)"
        );
        assert_eq!(device_label(&report("NVIDIA H100", "NVIDIA", false)), "GPU (NVIDIA H100)");
    }
}
