//! Frame-time measurement: the CPU time of each frame's logic and UI, the
//! solver's share of it, and the interval between frames.

use std::collections::VecDeque;

/// Frames kept.
const WINDOW: usize = 240;

/// The last frames' times, s.
#[derive(Clone, Debug, Default)]
pub struct FrameStats {
    /// (frame CPU time, solver time, interval since previous frame)
    frames: VecDeque<(f64, f64, f64)>,
}

impl FrameStats {
    pub fn record(&mut self, cpu: f64, solver: f64, interval: f64) {
        if self.frames.len() == WINDOW {
            self.frames.pop_front();
        }
        self.frames.push_back((cpu, solver, interval));
    }

    pub fn len(&self) -> usize {
        self.frames.len()
    }

    pub fn is_empty(&self) -> bool {
        self.frames.is_empty()
    }

    /// CPU time of the last frame, s.
    pub fn last(&self) -> f64 {
        self.frames.back().map_or(0.0, |f| f.0)
    }

    /// CPU time of the last frame besides the solver's, s.
    pub fn last_besides_solver(&self) -> f64 {
        self.frames.back().map_or(0.0, |f| (f.0 - f.1).max(0.0))
    }

    pub fn mean(&self) -> f64 {
        if self.frames.is_empty() {
            return 0.0;
        }
        self.frames.iter().map(|f| f.0).sum::<f64>() / self.frames.len() as f64
    }

    pub fn max(&self) -> f64 {
        self.frames.iter().map(|f| f.0).fold(0.0, f64::max)
    }

    /// 95th percentile of the frame CPU time, s.
    pub fn p95(&self) -> f64 {
        let mut v: Vec<f64> = self.frames.iter().map(|f| f.0).collect();
        if v.is_empty() {
            return 0.0;
        }
        v.sort_by(f64::total_cmp);
        v[(v.len() * 95 / 100).min(v.len() - 1)]
    }

    pub fn mean_solver(&self) -> f64 {
        if self.frames.is_empty() {
            return 0.0;
        }
        self.frames.iter().map(|f| f.1).sum::<f64>() / self.frames.len() as f64
    }

    pub fn mean_interval(&self) -> f64 {
        if self.frames.is_empty() {
            return 0.0;
        }
        self.frames.iter().map(|f| f.2).sum::<f64>() / self.frames.len() as f64
    }

    pub fn clear(&mut self) {
        self.frames.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statistics_over_the_window() {
        let mut s = FrameStats::default();
        for k in 1..=100 {
            s.record(f64::from(k) * 1e-3, 0.0, 1.0 / 60.0);
        }
        assert!((s.mean() - 50.5e-3).abs() < 1e-12);
        assert_eq!(s.max(), 0.1);
        assert!((s.p95() - 0.096).abs() < 1e-12);
        for _ in 0..WINDOW {
            s.record(1e-3, 0.0, 0.0);
        }
        assert_eq!(s.len(), WINDOW);
        assert_eq!(s.max(), 1e-3);
    }
}
