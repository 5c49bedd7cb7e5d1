//! GPU timing that holds still: many configurations (a technique on a pipeline, say) timed in
//! rounds, round robin, each round timing one batch of frames per configuration, with a
//! warm-up that lasts until successive rounds agree.
//!
//! Why: a GPU lowers its clocks while it idles, and raises them again only after some
//! sustained work. Timings taken while it climbs, or after the CPU kept it waiting, say more
//! about its clock governor than about the work. So the caller times batches of frames
//! recorded back to back (no idle gap inside a batch, see
//! [`crate::ReliefRenderer::time_batch`]), runs nothing else between batches, and this
//! procedure decides when the device has settled.
//!
//! The procedure, for `n` configurations and [`SteadySettings`] `s`:
//!
//! - **Round**: for `c = 0, 1, …, n − 1` in that order, one batch of `s.batch` frames of
//!   configuration `c`. A batch's figure is the median of its frames' times.
//! - **Warm-up**: rounds until every configuration *agrees*, or a cap. Configuration `c`
//!   agrees after round `r` when its batch figures `m` of the last `s.window` rounds all lie
//!   within `±s.tolerance` of their mean `m̄`: `|mᵢ − m̄| ≤ s.tolerance · m̄`. The warm-up
//!   ends after the first round at which every configuration agrees (so it runs at least
//!   `s.window` rounds), or when `s.max_warmup_rounds` rounds have run, or when the frames
//!   timed in warm-up add up to `s.max_warmup_ms`, whichever comes first. Warm-up frames are
//!   not measured.
//! - **Measurement**: `s.rounds` more rounds; every frame's time is a sample.
//!
//! Per configuration the report gives the samples' minimum, median, maximum, 10th and 90th
//! percentiles (linear interpolation between the closest ranks of the sorted samples, as
//! `numpy.percentile` does), and the **spread** `(p90 − p10) / median`: the relative width of
//! the middle 80 % of the samples, which one outlier does not move (max − min would). It also
//! gives the rounds of warm-up that configuration needed (the round after which it agreed at
//! every later warm-up round) and whether it agreed when the warm-up ended (`settled`).
//!
//! The procedure is generic over the batch (a closure), so that it can be tested with
//! synthetic sequences and used with timestamps or with the wall clock alike.

/// How [`time_steady`] warms up and measures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SteadySettings {
    /// Frames per batch (at least 1): recorded back to back, one batch per configuration per
    /// round.
    pub batch: u32,
    /// Measured rounds after the warm-up (at least 1).
    pub rounds: u32,
    /// Successive rounds whose batch figures must agree (at least 2).
    pub window: u32,
    /// Relative tolerance of the agreement (0.03: within ±3 % of their mean).
    pub tolerance: f64,
    /// Most warm-up rounds; reaching it leaves unsettled configurations marked so.
    pub max_warmup_rounds: u32,
    /// Most milliseconds of timed frames (the batches' own times, summed) spent in warm-up.
    pub max_warmup_ms: f64,
}

impl Default for SteadySettings {
    /// 8 frames per batch, 5 measured rounds, 3 rounds within ±3 %, at most 30 warm-up rounds
    /// or 30 s of warm-up frames.
    fn default() -> Self {
        SteadySettings {
            batch: 8,
            rounds: 5,
            window: 3,
            tolerance: 0.03,
            max_warmup_rounds: 30,
            max_warmup_ms: 30_000.0,
        }
    }
}

/// What [`time_steady`] measured for one configuration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SteadyTiming {
    /// Fastest sample, ms.
    pub min_ms: f64,
    /// Median sample, ms.
    pub median_ms: f64,
    /// Slowest sample, ms.
    pub max_ms: f64,
    /// 10th percentile, ms.
    pub p10_ms: f64,
    /// 90th percentile, ms.
    pub p90_ms: f64,
    /// `(p90 − p10) / median`.
    pub spread: f64,
    /// Measured samples (frames).
    pub samples: usize,
    /// Warm-up rounds this configuration needed: the round after which it agreed at every
    /// later warm-up round (the warm-up's length when it never did).
    pub warmup_rounds: u32,
    /// Whether it agreed when the warm-up ended.
    pub settled: bool,
}

/// What [`time_steady`] measured.
#[derive(Clone, Debug, PartialEq)]
pub struct SteadyReport {
    /// One per configuration, in order.
    pub configs: Vec<SteadyTiming>,
    /// Warm-up rounds run.
    pub warmup_rounds: u32,
    /// Whether every configuration agreed when the warm-up ended.
    pub settled: bool,
    /// Frames timed in all, warm-up and measured rounds.
    pub frames: u64,
    /// The sum of every finite frame time returned, warm-up included, ms: the device time the
    /// procedure cost (with timestamps, the GPU's own time).
    pub busy_ms: f64,
}

/// Times `configs` configurations as the module describes: `batch(c, frames)` runs `frames`
/// frames of configuration `c` back to back and returns each frame's time in ms (a batch that
/// returns no time never agrees). The first error ends the procedure.
pub fn time_steady<E>(
    configs: usize,
    settings: &SteadySettings,
    mut batch: impl FnMut(usize, u32) -> std::result::Result<Vec<f64>, E>,
) -> std::result::Result<SteadyReport, E> {
    let frames = settings.batch.max(1);
    let window = settings.window.max(2) as usize;
    // Per configuration: its batch figures in warm-up, and since which round it agrees.
    let mut figures: Vec<Vec<f64>> = vec![Vec::new(); configs];
    let mut agrees_since: Vec<Option<u32>> = vec![None; configs];
    let (mut rounds, mut spent_ms, mut frames_run) = (0u32, 0.0f64, 0u64);
    let all_agree = |since: &[Option<u32>]| since.iter().all(Option::is_some);
    while configs > 0
        && rounds < settings.max_warmup_rounds
        && spent_ms < settings.max_warmup_ms
        && !(rounds > 0 && all_agree(&agrees_since))
    {
        rounds += 1;
        for c in 0..configs {
            let times = batch(c, frames)?;
            frames_run += times.len() as u64;
            spent_ms += times.iter().filter(|t| t.is_finite()).sum::<f64>();
            figures[c].push(batch_figure(times));
            if agrees(&figures[c], window, settings.tolerance) {
                agrees_since[c].get_or_insert(rounds);
            } else {
                agrees_since[c] = None;
            }
        }
    }
    let mut samples: Vec<Vec<f64>> = vec![Vec::new(); configs];
    let mut busy_ms = spent_ms;
    for _ in 0..settings.rounds.max(1) {
        for (c, s) in samples.iter_mut().enumerate() {
            let times = batch(c, frames)?;
            frames_run += times.len() as u64;
            busy_ms += times.iter().filter(|t| t.is_finite()).sum::<f64>();
            s.extend(times);
        }
    }
    let timings: Vec<SteadyTiming> = samples
        .into_iter()
        .zip(&agrees_since)
        .map(|(s, since)| summarise(s, since.unwrap_or(rounds), since.is_some()))
        .collect();
    Ok(SteadyReport {
        configs: timings,
        warmup_rounds: rounds,
        settled: all_agree(&agrees_since),
        frames: frames_run,
        busy_ms,
    })
}

/// A batch's figure: the median of its frames' times (NaN for an empty batch).
fn batch_figure(mut times: Vec<f64>) -> f64 {
    if times.is_empty() {
        return f64::NAN;
    }
    times.sort_by(f64::total_cmp);
    percentile(&times, 0.5)
}

/// Whether the last `window` figures lie within `±tolerance` of their mean (false with fewer,
/// or with any figure not finite or not positive).
fn agrees(figures: &[f64], window: usize, tolerance: f64) -> bool {
    if figures.len() < window {
        return false;
    }
    let last = &figures[figures.len() - window..];
    if last.iter().any(|m| !m.is_finite() || *m <= 0.0) {
        return false;
    }
    let mean = last.iter().sum::<f64>() / window as f64;
    last.iter().all(|m| (m - mean).abs() <= tolerance * mean)
}

/// The `q`-quantile (0 ≤ q ≤ 1) of sorted, non-empty `v`, interpolating linearly between the
/// closest ranks.
fn percentile(v: &[f64], q: f64) -> f64 {
    let pos = q * (v.len() - 1) as f64;
    let (lo, hi) = (pos.floor() as usize, pos.ceil() as usize);
    v[lo] + (v[hi] - v[lo]) * (pos - lo as f64)
}

/// One configuration's measured samples summarised (NaN figures where there are none).
fn summarise(mut s: Vec<f64>, warmup_rounds: u32, settled: bool) -> SteadyTiming {
    s.sort_by(f64::total_cmp);
    let at = |q| if s.is_empty() { f64::NAN } else { percentile(&s, q) };
    let (median, p10, p90) = (at(0.5), at(0.1), at(0.9));
    SteadyTiming {
        min_ms: s.first().copied().unwrap_or(f64::NAN),
        median_ms: median,
        max_ms: s.last().copied().unwrap_or(f64::NAN),
        p10_ms: p10,
        p90_ms: p90,
        spread: (p90 - p10) / median,
        samples: s.len(),
        warmup_rounds,
        settled,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::convert::Infallible;

    fn settings() -> SteadySettings {
        SteadySettings { batch: 4, rounds: 5, ..SteadySettings::default() }
    }

    #[test]
    fn a_clock_that_ramps_then_holds_is_measured_once_it_holds() {
        // Config 0 speeds up over 4 batches (frames of 10, 8, 6, 4 ms), then holds at 2 ms;
        // config 1 holds at 5 ms throughout.
        let mut calls = [0u32; 2];
        let r = time_steady(2, &settings(), |c, frames| {
            calls[c] += 1;
            let ms = if c == 1 { 5.0 } else { (10.0 - 2.0 * (calls[c] - 1) as f64).max(2.0) };
            Ok::<_, Infallible>(vec![ms; frames as usize])
        })
        .unwrap();
        // Batch 5 is the first at 2 ms; rounds 5, 6, 7 are the first three that agree.
        assert_eq!(r.warmup_rounds, 7);
        assert!(r.settled);
        let (ramp, flat) = (r.configs[0], r.configs[1]);
        assert_eq!((ramp.warmup_rounds, ramp.settled), (7, true));
        assert_eq!((flat.warmup_rounds, flat.settled), (3, true), "agreed from the first window on");
        assert_eq!((ramp.median_ms, ramp.min_ms, ramp.max_ms, ramp.spread), (2.0, 2.0, 2.0, 0.0));
        assert_eq!(flat.median_ms, 5.0);
        assert_eq!((ramp.samples, flat.samples), (20, 20), "5 rounds of 4 frames");
        assert_eq!(calls, [12, 12], "7 warm-up rounds and 5 measured");
        // Every frame counted: 12 batches of 4 frames each; config 0's warm-up frames took
        // 4·(10 + 8 + 6 + 4 + 2 + 2 + 2) ms, its measured ones 20·2, config 1's 48·5.
        assert_eq!(r.frames, 96);
        assert_eq!(r.busy_ms, 4.0 * 34.0 + 40.0 + 240.0);
    }

    #[test]
    fn a_sequence_that_never_settles_stops_at_the_cap_unsettled() {
        let mut n = 0u32;
        let cap = SteadySettings { max_warmup_rounds: 12, ..settings() };
        let r = time_steady(1, &cap, |_, frames| {
            n += 1;
            // Alternates 1 ms and 2 ms: never within ±3 %.
            Ok::<_, Infallible>(vec![1.0 + (n % 2) as f64; frames as usize])
        })
        .unwrap();
        assert_eq!(r.warmup_rounds, 12);
        assert!(!r.settled && !r.configs[0].settled);
        assert_eq!(r.configs[0].warmup_rounds, 12);
        assert_eq!(n, 12 + 5);
        // Measured batches: 3 of 2 ms and 2 of 1 ms (calls 13..=17).
        let t = r.configs[0];
        assert_eq!((t.min_ms, t.median_ms, t.max_ms), (1.0, 2.0, 2.0));
    }

    #[test]
    fn the_warm_up_time_cap_ends_the_warm_up() {
        let capped = SteadySettings { max_warmup_ms: 100.0, ..settings() };
        // Batches of 4 frames of 10 ms alternating with 20 ms: 40, 80 ms per batch.
        let mut n = 0u32;
        let r = time_steady(1, &capped, |_, frames| {
            n += 1;
            Ok::<_, Infallible>(vec![10.0 * (1 + n % 2) as f64; frames as usize])
        })
        .unwrap();
        assert_eq!(r.warmup_rounds, 2, "80 + 40 ms reach the 100 ms cap after two rounds");
        assert!(!r.settled);
    }

    #[test]
    fn rounds_visit_every_config_in_turn() {
        let mut order = Vec::new();
        let s = SteadySettings { batch: 3, rounds: 2, ..SteadySettings::default() };
        let r = time_steady(3, &s, |c, frames| {
            order.push((c, frames));
            Ok::<_, Infallible>(vec![1.0; frames as usize])
        })
        .unwrap();
        assert_eq!(r.warmup_rounds, 3, "constant times agree after the first window");
        let round: Vec<(usize, u32)> = (0..3).map(|c| (c, 3)).collect();
        assert_eq!(order, round.repeat(5), "3 warm-up rounds, then 2 measured, each 0, 1, 2");
    }

    #[test]
    fn spread_is_the_middle_eighty_percent_over_the_median() {
        // Samples 1..=11 ms: median 6, p10 2, p90 10.
        let t = summarise((1..=11).rev().map(f64::from).collect(), 3, true);
        assert_eq!((t.min_ms, t.p10_ms, t.median_ms, t.p90_ms, t.max_ms), (1.0, 2.0, 6.0, 10.0, 11.0));
        assert_eq!(t.spread, 8.0 / 6.0);
        let empty = summarise(Vec::new(), 0, false);
        assert!(empty.median_ms.is_nan() && empty.samples == 0);
    }

    #[test]
    fn agreement_is_within_the_tolerance_of_the_mean() {
        assert!(agrees(&[9.0, 100.0, 102.0, 98.0], 3, 0.03));
        assert!(!agrees(&[100.0, 104.0, 96.0], 3, 0.03), "±4 % of the mean");
        assert!(!agrees(&[100.0, 100.0], 3, 0.03), "fewer than the window");
        assert!(!agrees(&[f64::NAN, 1.0, 1.0], 3, 0.03));
        assert_eq!(batch_figure(vec![3.0, 1.0, 2.0, 10.0]), 2.5);
    }

    #[test]
    fn errors_end_the_procedure() {
        let r = time_steady(2, &settings(), |c, _| if c == 1 { Err("lost") } else { Ok(vec![1.0]) });
        assert_eq!(r, Err("lost"));
    }
}
