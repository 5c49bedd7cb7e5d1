//! `renderlab texture …`: the texture lab's two commands, one file each; what both accept
//! (the user's texture, the frame's side) is in `texture/inputs.rs`.

pub(crate) mod bench;
mod inputs;
pub(crate) mod render;

use clap::Subcommand;

/// `renderlab texture …`.
#[derive(Subcommand, Debug)]
pub enum TextureCommand {
    /// Render every test scene (checkerboard plane to the horizon, the thesis's quad, a quad at
    /// several tilts, a zone plate) with every filter; time it (ns per pixel), count its texel
    /// fetches and measure PSNR, SSIM and FLIP against a supersampled reference under two
    /// pixel-filter models (the --model Gaussian, σ = 0.5 px cut at 3σ by default, and the box);
    /// the reference is refined until its own noise sits 10 dB below the best filter's error.
    /// Then the σ study (EWA and the reference at σ 0.35–0.6, cut 2σ and 3σ) and every
    /// perspective-mapping mode side by side. Writes results.json, results.csv, noise.csv,
    /// sigma.csv, images and index.html to --out.
    Bench(bench::TextureBenchArgs),
    /// Render one test scene with one filter (or the reference) to a PNG.
    Render(render::TextureRenderArgs),
}
