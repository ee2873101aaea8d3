//! The time left of a running sweep. The values that settle quickly (an early-stopped
//! cycle) finish first and the slow ones (chaos and sticking run to the transient's end)
//! last, so the average rate since the start promises far too little time; the rate of
//! the last few seconds is the rate of the values still running. The estimate is the
//! values left over that recent rate, once a few seconds of it are known.

use std::collections::VecDeque;

/// The span of the recent rate, in seconds.
pub const WINDOW: f64 = 4.0;
/// No estimate before this many seconds of a sweep.
pub const FIRST: f64 = 2.0;

/// Samples of (seconds since the start, values done) over the last [`WINDOW`].
#[derive(Clone, Debug, Default)]
pub struct Eta {
    samples: VecDeque<(f64, usize)>,
}

impl Eta {
    /// A new sweep: nothing known.
    pub fn reset(&mut self) {
        self.samples.clear();
    }

    /// `done` values at `t` seconds.
    pub fn sample(&mut self, t: f64, done: usize) {
        if self.samples.back().is_some_and(|&(_, d)| d == done) {
            return;
        }
        self.samples.push_back((t, done));
        // Keep one sample older than the window, so the window is always spanned.
        while self.samples.len() > 2 && self.samples[1].0 < t - WINDOW {
            self.samples.pop_front();
        }
    }

    /// Seconds left for `total` values at `now` seconds, at the rate of the last
    /// [`WINDOW`] seconds (None: too early to say, or nothing finished lately).
    pub fn left(&self, now: f64, total: usize) -> Option<f64> {
        let &(t0, d0) = self.samples.front()?;
        let &(_, d1) = self.samples.back()?;
        if now < FIRST || d1 <= d0 || d1 >= total {
            return None;
        }
        // From the oldest sample kept to now: a stall since the last value slows it.
        let span = (now - t0).clamp(1e-3, 2.0 * WINDOW);
        let rate = (d1 - d0) as f64 / span;
        Some((total - d1) as f64 / rate)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Easy values finish in the first second, the rest at a steady slower rate: the
    /// estimate follows the slow rate, not the average since the start.
    #[test]
    fn the_estimate_follows_the_recent_rate() {
        let mut e = Eta::default();
        let total = 1000;
        // 500 values in the first second, then 50 a second: 10 s more in all.
        let done_at = |t: f64| {
            if t <= 1.0 {
                (500.0 * t) as usize
            } else {
                500 + (50.0 * (t - 1.0)) as usize
            }
        };
        for k in 0..=80 {
            let t = k as f64 * 0.1;
            e.sample(t, done_at(t));
        }
        let truth = 1.0 + 500.0 / 50.0 - 8.0;
        let left = e.left(8.0, total).unwrap();
        assert!((left - truth).abs() < 0.15 * truth, "{left} vs {truth}");
        // The average since the start would say (1000 − 850) / (850 / 8) ≈ 1.4 s.
        assert!(left > 2.5);
        assert_eq!(e.left(1.0, total), None, "too early");
        assert_eq!(e.left(9.0, 500), None, "all done");
    }
}
