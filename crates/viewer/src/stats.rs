//! The FPS readout's statistics: the current rate and the minimum, mean and maximum since the
//! last reset (key C), as the thesis's `FpsTracker` keeps them, and the GPU pass time.

/// Frame-rate statistics over the frames since the last reset.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FrameStats {
    frames: u64,
    seconds: f64,
    current_fps: f64,
    min_fps: f64,
    max_fps: f64,
    gpu_ms: Option<f64>,
    gpu_ms_sum: f64,
    gpu_frames: u64,
}

impl FrameStats {
    /// Records one frame that took `dt` seconds (ignored unless finite and positive) and,
    /// where timestamps measured it, the relief pass's GPU time.
    pub fn record(&mut self, dt: f64, gpu_ms: Option<f64>) {
        if let Some(ms) = gpu_ms.filter(|m| m.is_finite() && *m >= 0.0) {
            self.gpu_ms = Some(ms);
            self.gpu_ms_sum += ms;
            self.gpu_frames += 1;
        }
        if !(dt.is_finite() && dt > 0.0) {
            return;
        }
        let fps = 1.0 / dt;
        self.current_fps = fps;
        if self.frames == 0 {
            (self.min_fps, self.max_fps) = (fps, fps);
        } else {
            self.min_fps = self.min_fps.min(fps);
            self.max_fps = self.max_fps.max(fps);
        }
        self.frames += 1;
        self.seconds += dt;
    }

    /// Forgets everything recorded (key C).
    pub fn reset(&mut self) {
        *self = Self::default();
    }

    /// Frames recorded since the reset.
    pub fn frames(&self) -> u64 {
        self.frames
    }

    /// The last frame's rate.
    pub fn current(&self) -> f64 {
        self.current_fps
    }

    /// The slowest frame's rate.
    pub fn min(&self) -> f64 {
        self.min_fps
    }

    /// The fastest frame's rate.
    pub fn max(&self) -> f64 {
        self.max_fps
    }

    /// The mean rate: frames over total time (not the mean of the rates, which slow frames
    /// would weigh too little).
    pub fn avg(&self) -> f64 {
        if self.seconds > 0.0 {
            self.frames as f64 / self.seconds
        } else {
            0.0
        }
    }

    /// The last frame's relief pass on the GPU, in milliseconds.
    pub fn gpu_ms(&self) -> Option<f64> {
        self.gpu_ms
    }

    /// The mean GPU pass time since the reset.
    pub fn gpu_ms_avg(&self) -> Option<f64> {
        (self.gpu_frames > 0).then(|| self.gpu_ms_sum / self.gpu_frames as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statistics_follow_the_frames_and_reset() {
        let mut s = FrameStats::default();
        for dt in [0.01, 0.02, 0.04, f64::NAN, 0.0] {
            s.record(dt, Some(1.0));
        }
        assert_eq!(s.frames(), 3);
        assert!((s.current() - 25.0).abs() < 1e-9);
        assert!((s.min() - 25.0).abs() < 1e-9 && (s.max() - 100.0).abs() < 1e-9);
        assert!((s.avg() - 3.0 / 0.07).abs() < 1e-9);
        assert_eq!(s.gpu_ms_avg(), Some(1.0));
        s.reset();
        assert_eq!((s.frames(), s.avg(), s.gpu_ms()), (0, 0.0, None));
    }
}
