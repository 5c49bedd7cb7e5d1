//! Wall-clock timing with warm-up and repetitions, summarised by the median.
//!
//! The median of several repetitions is robust to the odd interruption of a shared, noisy
//! machine; min and max show the spread. Absolute times are only comparable within one run on
//! one machine: experiments should report ratios between techniques timed the same way.

use serde::Serialize;
use std::hint::black_box;
use std::time::Instant;

/// Summary of repeated timings of one piece of work, in milliseconds.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Timing {
    /// Median time of one repetition (the mean of the middle two for an even count).
    pub median_ms: f64,
    /// Fastest repetition.
    pub min_ms: f64,
    /// Slowest repetition.
    pub max_ms: f64,
    /// Number of timed repetitions (warm-up runs excluded).
    pub reps: u32,
}

impl Timing {
    /// Summarises individual repetition times (in ms). `None` for an empty slice.
    pub fn from_samples(samples_ms: &[f64]) -> Option<Timing> {
        if samples_ms.is_empty() {
            return None;
        }
        let mut s = samples_ms.to_vec();
        let median_ms = renderlab_core::stats::median(&mut s);
        let n = s.len();
        Some(Timing { median_ms, min_ms: s[0], max_ms: s[n - 1], reps: n as u32 })
    }

    /// How many times faster this is than `other` (ratio of medians: `other / self`).
    pub fn speedup_over(&self, other: &Timing) -> f64 {
        other.median_ms / self.median_ms
    }
}

/// Runs `f` `warmup` times untimed (to fill caches, page in memory and start rayon's threads),
/// then `reps` times timed, and returns the timing summary with the result of the last run.
/// Results go through [`std::hint::black_box`] so the optimiser cannot drop the work.
/// `reps` of 0 is taken as 1 (there must be a result to return).
pub fn measure<T>(warmup: u32, reps: u32, f: impl FnMut() -> T) -> (Timing, T) {
    let start = Instant::now();
    measure_with_clock(warmup, reps, f, || u64::try_from(start.elapsed().as_nanos()).unwrap_or(u64::MAX))
}

/// [`measure`] with the clock supplied: `now_ns()` returns the current time in nanoseconds
/// from any fixed origin. Lets tests drive the statistics with a fake clock. Durations are
/// converted to milliseconds by one division, so that they print without rounding noise.
pub fn measure_with_clock<T>(
    warmup: u32,
    reps: u32,
    mut f: impl FnMut() -> T,
    mut now_ns: impl FnMut() -> u64,
) -> (Timing, T) {
    for _ in 0..warmup {
        black_box(f());
    }
    let reps = reps.max(1);
    let mut samples = Vec::with_capacity(reps as usize);
    let mut timed = || {
        let t0 = now_ns();
        let r = black_box(f());
        let t1 = now_ns();
        samples.push(t1.saturating_sub(t0) as f64 / 1e6);
        r
    };
    let mut last = timed();
    for _ in 1..reps {
        // The previous result is dropped by this assignment, outside the timed span.
        last = timed();
    }
    let timing = Timing::from_samples(&samples).unwrap_or(Timing {
        median_ms: 0.0,
        min_ms: 0.0,
        max_ms: 0.0,
        reps: 0,
    });
    (timing, last)
}

/// Times `n` items in turn: each runs `warmup` times untimed, then repetition after
/// repetition every item runs once, timed (`f(i)` runs item `i`). Returns each item's timing.
/// Interleaving keeps a disturbance of a few seconds (another process, a clock change) from
/// landing on one item's repetitions only, so ratios between items stay fair on a noisy
/// machine. Stops at the first error. `reps` of 0 is taken as 1.
pub fn measure_round_robin<E>(
    warmup: u32,
    reps: u32,
    n: usize,
    f: impl FnMut(usize) -> Result<(), E>,
) -> Result<Vec<Timing>, E> {
    let start = Instant::now();
    round_robin_with_clock(warmup, reps, n, f, || {
        u64::try_from(start.elapsed().as_nanos()).unwrap_or(u64::MAX)
    })
}

/// [`measure_round_robin`] with the clock supplied, as [`measure_with_clock`].
pub fn round_robin_with_clock<E>(
    warmup: u32,
    reps: u32,
    n: usize,
    mut f: impl FnMut(usize) -> Result<(), E>,
    mut now_ns: impl FnMut() -> u64,
) -> Result<Vec<Timing>, E> {
    for i in 0..n {
        for _ in 0..warmup {
            f(i)?;
        }
    }
    let reps = reps.max(1) as usize;
    let mut samples = vec![Vec::with_capacity(reps); n];
    for _ in 0..reps {
        for (i, s) in samples.iter_mut().enumerate() {
            let t0 = now_ns();
            black_box(f(i))?;
            s.push(now_ns().saturating_sub(t0) as f64 / 1e6);
        }
    }
    Ok(samples.iter().filter_map(|s| Timing::from_samples(s)).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::Cell;

    #[test]
    fn median_of_odd_and_even_counts() {
        let t = Timing::from_samples(&[5.0, 1.0, 3.0]).unwrap();
        assert_eq!((t.median_ms, t.min_ms, t.max_ms, t.reps), (3.0, 1.0, 5.0, 3));
        let t = Timing::from_samples(&[4.0, 1.0, 3.0, 100.0]).unwrap();
        assert_eq!(t.median_ms, 3.5);
        assert!(Timing::from_samples(&[]).is_none());
    }

    #[test]
    fn fake_clock_gives_exact_statistics() {
        // Repetition i takes durations[i] ms on the fake clock (which counts nanoseconds).
        let durations = [7_000_000u64, 2_000_000, 9_000_000, 4_000_000, 5_000_000];
        let clock = Cell::new(0u64);
        let calls = Cell::new(0u32);
        let rep = Cell::new(0usize);
        let (t, last) = measure_with_clock(
            3,
            5,
            || {
                calls.set(calls.get() + 1);
                calls.get()
            },
            || {
                // Called twice per repetition: advance on the second call.
                let now = clock.get();
                let r = rep.get();
                if r % 2 == 1 {
                    clock.set(now + durations[r / 2]);
                }
                rep.set(r + 1);
                clock.get()
            },
        );
        assert_eq!(calls.get(), 8, "3 warm-up + 5 timed calls");
        assert_eq!(last, 8, "the last call's result is returned");
        assert_eq!(t.reps, 5);
        assert_eq!((t.median_ms, t.min_ms, t.max_ms), (5.0, 2.0, 9.0));
        assert_eq!(t.speedup_over(&Timing { median_ms: 10.0, ..t }), 2.0);
    }

    #[test]
    fn real_clock_is_structurally_sound() {
        let (t, v) = measure(1, 0, || (0..1000u64).sum::<u64>());
        assert_eq!(v, 499_500);
        assert_eq!(t.reps, 1);
        assert!(t.min_ms >= 0.0 && t.min_ms <= t.median_ms && t.median_ms <= t.max_ms);
    }

    #[test]
    fn round_robin_interleaves_the_items_and_keeps_their_times_apart() {
        // Item i takes (i + 1) ms on the fake clock, except item 1's second repetition, which
        // is disturbed (+50 ms): the median keeps it out.
        let clock = Cell::new(0u64);
        let mut calls = Vec::new();
        let mut rep_of = [0u32; 3];
        let t = round_robin_with_clock(
            1,
            3,
            3,
            |i| -> Result<(), ()> {
                calls.push(i);
                rep_of[i] += 1;
                let extra = if i == 1 && rep_of[i] == 3 { 50 } else { 0 };
                clock.set(clock.get() + (i as u64 + 1 + extra) * 1_000_000);
                Ok(())
            },
            || clock.get(),
        )
        .unwrap();
        // Warm-ups item by item, then the repetitions in turn.
        assert_eq!(calls, vec![0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1, 2]);
        assert_eq!(t.iter().map(|t| t.median_ms).collect::<Vec<_>>(), vec![1.0, 2.0, 3.0]);
        assert_eq!(t[1].max_ms, 52.0);
        assert!(t.iter().all(|t| t.reps == 3));
        // An error stops the run and is returned.
        let mut n = 0;
        let step = |_| {
            n += 1;
            if n == 3 {
                Err("stop")
            } else {
                Ok(())
            }
        };
        assert_eq!(round_robin_with_clock(0, 2, 2, step, || 0).unwrap_err(), "stop");
        assert_eq!(n, 3, "nothing runs after the error");
    }
}
