//! What one hybrid run measures: scenes, cameras, resolution, sweep, reference, timing, and
//! which shard of the rows this process renders.

use super::backend::{HybridBackend, RtChoice};
use super::sweep::SweepKind;
use crate::error::{LabError, Result};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// The K-th of N disjoint parts of a run's rows (1-based, as `--shard K/N` and a Slurm array
/// index name it).
///
/// Row `i` of the run's canonical list (scenes × cameras × sweep, in that order) belongs to
/// shard `i mod N + 1`: round robin, so that every shard gets a share of every view and of
/// every stage, and the expensive rows spread evenly. A shard renders the reference of every
/// view it has rows of (same seed, so the same reference as any other shard): each shard is
/// self-sufficient, at the price of rendering a view's reference in up to N shards.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    /// Which part, 1..=count.
    pub index: u32,
    /// How many parts.
    pub count: u32,
}

impl Shard {
    /// The whole run in one part.
    pub const WHOLE: Shard = Shard { index: 1, count: 1 };

    /// Whether row `i` of the canonical list is this shard's.
    pub fn owns(&self, i: usize) -> bool {
        i % self.count as usize + 1 == self.index as usize
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

impl FromStr for Shard {
    type Err = String;

    /// Reads `K/N` with 1 ≤ K ≤ N ≤ 100000.
    fn from_str(s: &str) -> std::result::Result<Self, String> {
        let bad = || format!("shard {s:?} must read K/N with 1 <= K <= N <= 100000 (e.g. 2/8)");
        let (k, n) = s.split_once('/').ok_or_else(bad)?;
        let (index, count) =
            (k.trim().parse::<u32>().map_err(|_| bad())?, n.trim().parse::<u32>().map_err(|_| bad())?);
        if index == 0 || index > count || count > 100_000 {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }
}

/// What to do with rows already in the output directory.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Existing {
    /// Refuse to start if the directory holds rows (the default of the command line).
    Refuse,
    /// Keep the rows of a run with the same settings and render only the missing ones.
    Resume,
    /// Delete the directory's rows and references and start again (the report's choice).
    Replace,
}

/// The numbers of a run that decide its results: as the command line gives them (in
/// [`HybridBenchConfig`]) and as the run directory records them (`run.json`, flattened into
/// [`Settings`](super::Settings), with the reference's spp rounded up to even).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunSettings {
    /// Frame width in pixels.
    pub width: u32,
    /// Frame height in pixels.
    pub height: u32,
    /// Which rows per view.
    pub sweep: SweepKind,
    /// Paths per pixel of the reference (two halves of half as many each).
    pub reference_spp: u32,
    /// Untimed frames before the timed ones.
    pub warmup: u32,
    /// Timed frames per row; the median is reported.
    pub reps: u32,
    /// Seed of every stage's and the reference's random numbers.
    pub seed: u64,
    /// Whether to write each row's image and error image (the reference is always written).
    pub write_images: bool,
    /// Which renderers draw the rows' frames.
    #[serde(default)]
    pub backend: HybridBackend,
    /// How the GPU traces rays (with a GPU backend).
    #[serde(default)]
    pub rt: RtChoice,
    /// Untimed GPU frames before each row's timed ones (with a GPU backend): a GPU's clocks
    /// climb only under sustained work, so its first frames are slower than its settled
    /// ones.
    #[serde(default = "default_gpu_warmup")]
    pub gpu_warmup: u32,
}

/// Untimed GPU frames before each row's timed ones, by default.
pub const GPU_WARMUP: u32 = 10;

fn default_gpu_warmup() -> u32 {
    GPU_WARMUP
}

impl Default for RunSettings {
    /// 320×180, the thesis's sweeps, a 64-spp reference, one warm-up and three timed
    /// frames, seed 1, images written.
    fn default() -> Self {
        Self {
            width: 320,
            height: 180,
            sweep: SweepKind::Thesis,
            reference_spp: 64,
            warmup: 1,
            reps: 3,
            seed: 1,
            write_images: true,
            backend: HybridBackend::Cpu,
            rt: RtChoice::Auto,
            gpu_warmup: GPU_WARMUP,
        }
    }
}

/// Settings of one hybrid run.
#[derive(Clone, Debug)]
pub struct HybridBenchConfig {
    /// Scene specs: built-in names or scene files.
    pub scenes: Vec<String>,
    /// Camera names to render in every scene; empty: each scene's own cameras, all of them.
    pub cameras: Vec<String>,
    /// Resolution, sweep, reference, timing, seed and images.
    pub run: RunSettings,
    /// Which part of the rows this process renders.
    pub shard: Shard,
    /// What to do with rows already there.
    pub existing: Existing,
    /// With a GPU backend: whether a missing adapter is an error (`hybrid bench --backend
    /// gpu|both`) or a stated skip that runs the CPU alone (the report, which must run on any
    /// machine).
    pub gpu_required: bool,
}

impl Default for HybridBenchConfig {
    /// Every built-in scene and camera with the default [`RunSettings`], the whole run,
    /// refusing a directory that holds rows.
    fn default() -> Self {
        Self {
            scenes: super::scenes::BUILTIN.iter().map(|s| s.to_string()).collect(),
            cameras: Vec::new(),
            run: RunSettings::default(),
            shard: Shard::WHOLE,
            existing: Existing::Refuse,
            gpu_required: true,
        }
    }
}

impl HybridBenchConfig {
    /// Checks the numbers (the scenes and cameras are checked when they are loaded).
    pub fn validate(&self) -> Result<()> {
        let bad = |m: String| Err(LabError::Hybrid(m));
        let r = &self.run;
        super::scenes::check_resolution(r.width, r.height)?;
        if self.scenes.is_empty() {
            return bad("give at least one scene".into());
        }
        if !(2..=1 << 20).contains(&r.reference_spp) {
            return bad(format!("reference spp {} must lie in 2..=1048576", r.reference_spp));
        }
        if !(1..=1000).contains(&r.reps) {
            return bad(format!("reps {} must lie in 1..=1000", r.reps));
        }
        if r.warmup > 100 {
            return bad(format!("warm-up {} must lie in 0..=100", r.warmup));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_parse_and_partition_the_rows() {
        let s: Shard = "2/3".parse().unwrap();
        assert_eq!(s, Shard { index: 2, count: 3 });
        assert_eq!(s.to_string(), "2/3");
        for bad in ["0/3", "4/3", "3", "a/b", "1/0", "", "1/200000"] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
        for n in 1..6u32 {
            for i in 0..40 {
                let owners = (1..=n).filter(|&k| Shard { index: k, count: n }.owns(i)).count();
                assert_eq!(owners, 1);
            }
        }
    }

    #[test]
    fn bad_settings_are_refused() {
        assert!(HybridBenchConfig::default().validate().is_ok());
        for cfg in [
            HybridBenchConfig { run: RunSettings { width: 0, ..Default::default() }, ..Default::default() },
            HybridBenchConfig {
                run: RunSettings { reference_spp: 1, ..Default::default() },
                ..Default::default()
            },
            HybridBenchConfig { run: RunSettings { reps: 0, ..Default::default() }, ..Default::default() },
            HybridBenchConfig { scenes: vec![], ..Default::default() },
        ] {
            assert!(cfg.validate().is_err(), "{cfg:?}");
        }
    }
}
