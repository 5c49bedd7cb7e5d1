//! `renderlab noise`: the Perlin-noise lab (the texturing thesis's clouds, 3D paths, octave
//! figures, and short water and smoke animations).

use crate::args::range::{in_range, Whole};
use crate::commands::checks::{check_out_dir, create_dir};
use crate::progress::Progress;
use anyhow::{bail, Result};
use clap::Args;
use renderlab_lab::noise_lab::{
    run_noise_lab_with, CloudsConfig, MotionConfig, NoiseLabConfig, MAX_CLOUDS_SIZE,
};
use std::path::PathBuf;

/// The range of `--size`, pixels per side of the clouds image.
const SIZE: Whole<u32> = Whole::new(1, MAX_CLOUDS_SIZE);
/// The range of `--octaves`, clouds layers.
const OCTAVES: Whole<u32> = Whole::new(1, renderlab_noise::MAX_OCTAVES);

/// `renderlab noise`.
#[derive(Args, Debug)]
pub struct NoiseArgs {
    /// Output directory (created if missing).
    #[arg(long)]
    pub out: PathBuf,
    /// Small, short water and smoke animations (seconds less work; not for figures).
    #[arg(long)]
    pub quick: bool,
    /// Seed of the first clouds layer (layer k uses SEED+k). The 3D paths keep the thesis's
    /// seeds 100/101/102/200/300.
    #[arg(long, default_value_t = 100)]
    pub seed: u32,
    /// Side of the clouds image in pixels, in [`SIZE`].
    #[arg(long, default_value_t = 100, value_parser = in_range(SIZE),
          help = format!("Side of the clouds image in pixels ({SIZE}); it always covers the unit square"))]
    pub size: u32,
    /// Number of clouds layers, in [`OCTAVES`].
    #[arg(long, default_value_t = 4, value_parser = in_range(OCTAVES), help = format!(
        "Number of clouds layers ({OCTAVES}; the thesis: 4). Layer k has frequency FREQUENCY·2^k and \
         weight 2^-k; the last layer's frequency must stay below 2^24"))]
    pub octaves: u32,
    /// Frequency of the first clouds layer in lattice cells per image side (the thesis: 3).
    #[arg(long, default_value_t = 3.0)]
    pub frequency: f32,
}

/// Checks the `noise` flags the parser cannot (each error one line naming the flag).
fn noise_config(a: &NoiseArgs) -> Result<NoiseLabConfig> {
    if !(a.frequency.is_finite() && a.frequency > 0.0) {
        bail!("--frequency: {} must be a finite positive number", a.frequency);
    }
    let last = f64::from(a.frequency) * 2f64.powi(a.octaves as i32 - 1);
    if last > renderlab_noise::MAX_FREQUENCY {
        bail!(
            "--octaves/--frequency: the last layer's frequency {last} exceeds 2^24 (use fewer octaves \
             or a lower frequency)"
        );
    }
    let clouds = CloudsConfig { size: a.size, seed: a.seed, layers: a.octaves, frequency: a.frequency };
    let motion = if a.quick { MotionConfig::quick() } else { MotionConfig::default() };
    Ok(NoiseLabConfig { clouds, motion })
}

/// `renderlab noise`: the noise lab with the given clouds.
pub(crate) fn run(a: NoiseArgs) -> Result<()> {
    let cfg = noise_config(&a)?;
    check_out_dir("--out", &a.out)?;
    create_dir(&a.out)?;
    let p = Progress::new("noise");
    let summary = run_noise_lab_with(&a.out, &cfg, &|d, t, m| p.update(d, t, m))?;
    p.finish();
    for f in &summary.findings {
        println!("{f}");
    }
    println!("wrote {} and {}", summary.clouds_png.display(), summary.index.display());
    Ok(())
}
