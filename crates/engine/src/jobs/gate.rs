//! The one pause gate: pausing running work without losing its progress.
//!
//! Job workers (and the terminal application's interactive workers) pass through
//! [`Gate::wait`] every few dozen events, where they also test for cancellation. While
//! the gate is closed they park on a condition variable, so paused work costs no CPU,
//! and every work item keeps its state: resuming continues each orbit where it stopped.
//! A cancellation ends the wait too: it is noticed when the canceller calls
//! [`Gate::wake`], and in any case within [`POLL`] (a generation counter can be bumped by
//! anyone, who need not know about the gate).

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Condvar, Mutex};
use std::time::{Duration, Instant};

/// Longest time a parked worker goes without re-testing for cancellation.
pub const POLL: Duration = Duration::from_millis(250);

/// Opened and closed by the owner of a sweep; shared with its workers.
#[derive(Debug, Default)]
pub struct Gate {
    closed: AtomicBool,
    state: Mutex<Paused>,
    changed: Condvar,
}

/// When the current pause began, and the total of the pauses before it.
#[derive(Debug, Default)]
struct Paused {
    since: Option<Instant>,
    total: Duration,
}

impl Gate {
    /// Pause (`true`) or resume (`false`). Repeating a state changes nothing.
    pub fn set(&self, paused: bool) {
        let mut st = self.state.lock().unwrap_or_else(|e| e.into_inner());
        match (paused, st.since) {
            (true, None) => st.since = Some(Instant::now()),
            (false, Some(t)) => {
                st.total += t.elapsed();
                st.since = None;
            }
            _ => {}
        }
        self.closed.store(paused, Ordering::SeqCst);
        self.changed.notify_all();
    }

    /// Whether the gate is closed.
    pub fn is_paused(&self) -> bool {
        self.closed.load(Ordering::SeqCst)
    }

    /// Wake parked workers so they re-test `stopped` (after a cancellation).
    pub fn wake(&self) {
        let _st = self.state.lock().unwrap_or_else(|e| e.into_inner());
        self.changed.notify_all();
    }

    /// Time spent paused so far, the current pause included.
    pub fn paused_for(&self) -> Duration {
        let st = self.state.lock().unwrap_or_else(|e| e.into_inner());
        st.total + st.since.map_or(Duration::ZERO, |t| t.elapsed())
    }

    /// Block while the gate is closed, unless `stopped` says the sweep was cancelled.
    /// Costs one relaxed load when open.
    pub fn wait(&self, stopped: impl Fn() -> bool) {
        if !self.closed.load(Ordering::Relaxed) {
            return;
        }
        let mut st = self.state.lock().unwrap_or_else(|e| e.into_inner());
        while self.closed.load(Ordering::SeqCst) && !stopped() {
            st = self
                .changed
                .wait_timeout(st, POLL)
                .unwrap_or_else(|e| e.into_inner())
                .0;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicBool;
    use std::sync::Arc;

    #[test]
    fn parks_until_resumed_and_counts_paused_time() {
        let gate = Arc::new(Gate::default());
        gate.set(true);
        let passed = Arc::new(AtomicBool::new(false));
        let (g, p) = (gate.clone(), passed.clone());
        let t = std::thread::spawn(move || {
            g.wait(|| false);
            p.store(true, Ordering::SeqCst);
        });
        std::thread::sleep(Duration::from_millis(100));
        assert!(
            !passed.load(Ordering::SeqCst),
            "the worker went through a closed gate"
        );
        gate.set(false);
        t.join().unwrap();
        assert!(passed.load(Ordering::SeqCst));
        assert!(gate.paused_for() >= Duration::from_millis(100));
    }

    #[test]
    fn a_cancellation_ends_the_wait() {
        let gate = Arc::new(Gate::default());
        gate.set(true);
        let stop = Arc::new(AtomicBool::new(false));
        let (g, s) = (gate.clone(), stop.clone());
        let t = std::thread::spawn(move || g.wait(|| s.load(Ordering::SeqCst)));
        std::thread::sleep(Duration::from_millis(50));
        let cancelled_at = Instant::now();
        stop.store(true, Ordering::SeqCst);
        gate.wake();
        t.join().unwrap();
        assert!(
            cancelled_at.elapsed() < POLL,
            "woken at once, not at the next poll"
        );
        assert!(gate.is_paused(), "the gate itself stays closed");
    }
}
