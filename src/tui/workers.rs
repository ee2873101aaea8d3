//! Background work, latest-wins. Every job carries the generation it was started for;
//! a parameter change bumps the generation, workers check it between chunks and stop,
//! and the UI drops any message whose generation is stale. Results come back over one
//! channel as [`Msg`]. A pause gate parks the phase-plot worker without spinning.
//!
//! The diagram is fed by the engine's sweeps ([`crate::engine::sweep`]); the stability
//! panel gets its numbers through [`Analysis`], the seam to the orbit analysis.

use crate::engine::sweep::{self, PauseGate, SweepBatch, SweepSpec};
#[cfg(test)]
use crate::engine::Table;
use crate::engine::{Event, ImpactMap, Solver, State, System};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{self, Receiver, Sender};
use std::sync::{Arc, Condvar, Mutex};
use std::time::Duration;

/// One (1, k) solution.
#[derive(Clone, Debug, PartialEq)]
pub struct FixedPoint {
    pub phase: f64,
    pub v: f64,
    /// f''(t̂*).
    pub f2: f64,
    /// Eigenvalues of the Jacobian as (re, im).
    pub eig: [(f64, f64); 2],
    pub stable: bool,
}

/// A slice of the stability region in the (α, r) plane: stable α intervals at one r.
#[derive(Clone, Debug, PartialEq)]
pub struct RegionRow {
    pub r: f64,
    pub intervals: Vec<(f64, f64)>,
}

/// What the orbit analysis knows for the current system and k.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct OrbitInfo {
    pub fixed: Vec<FixedPoint>,
    /// Birth α of the (1, k) solution (where it first exists).
    pub birth: Option<f64>,
    /// α at which the stable (1, k) solution period-doubles (f'' = κ_c).
    pub pd: Option<f64>,
    /// The (2, 2k) solution's two points (phase, v), if it exists.
    pub two: Vec<(f64, f64)>,
    /// The stable region of the (1, k) solution in the (α, r) plane.
    pub region: Vec<RegionRow>,
}

/// The engine's orbit analysis, as the stability panel needs it.
pub trait Analysis: Send + Sync {
    /// The (1, k) analysis for a system (run on a worker thread, never the UI's).
    fn orbits(&self, sys: &System, k: u32, alpha_window: (f64, f64)) -> Result<OrbitInfo, String>;
}

/// Used while the engine has no orbit module: the stability panel says so instead of
/// showing made-up numbers.
pub struct Unavailable;

impl Analysis for Unavailable {
    fn orbits(&self, _sys: &System, _k: u32, _w: (f64, f64)) -> Result<OrbitInfo, String> {
        Err("not available: this build has no orbit analysis".into())
    }
}

/// Messages from workers to the UI thread.
#[derive(Debug)]
pub enum Msg {
    /// New phase-plot points; `note` when the orbit ended (resting, no landing).
    Phase {
        gen: u64,
        points: Vec<(f64, f64)>,
        done: bool,
        note: Option<String>,
    },
    /// One value's points from the sweep engine (its generation is in the batch).
    Sweep(SweepBatch),
    /// The sweep of this generation ran to its end.
    SweepDone { gen: u64 },
    Orbits {
        gen: u64,
        info: Result<OrbitInfo, String>,
    },
}

/// Parks workers while paused, without spinning.
#[derive(Default)]
pub struct Gate {
    paused: Mutex<bool>,
    cv: Condvar,
}

impl Gate {
    pub fn set(&self, paused: bool) {
        *self.paused.lock().unwrap_or_else(|e| e.into_inner()) = paused;
        self.cv.notify_all();
    }

    pub fn is_paused(&self) -> bool {
        *self.paused.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Block while paused; returns false if `gen` went stale meanwhile.
    pub fn wait(&self, gen: u64, current: &AtomicU64) -> bool {
        let mut p = self.paused.lock().unwrap_or_else(|e| e.into_inner());
        while *p && current.load(Ordering::Relaxed) == gen {
            p = self.cv.wait(p).unwrap_or_else(|e| e.into_inner());
        }
        current.load(Ordering::Relaxed) == gen
    }

    /// Wake every parked worker (after a generation bump).
    pub fn kick(&self) {
        self.cv.notify_all();
    }
}

/// Phase-plot pacing: a first burst, then steady chunks up to the cap, so that the
/// plot visibly accumulates and then goes idle.
pub const PHASE_BURST: usize = 1500;
pub const PHASE_CHUNK: usize = 250;
pub const PHASE_CAP: usize = 20_000;
pub const PHASE_PACE: Duration = Duration::from_millis(50);

/// The workers the runtime owns.
pub struct Workers {
    pub tx: Sender<Msg>,
    pub rx: Receiver<Msg>,
    pub phase_gen: Arc<AtomicU64>,
    pub sweep_gen: Arc<AtomicU64>,
    pub orbit_gen: Arc<AtomicU64>,
    pub gate: Arc<Gate>,
    /// Parks the sweep's workers while paused; they keep their progress.
    pub sweep_pause: Arc<PauseGate>,
    pub analysis: Arc<dyn Analysis>,
}

impl Workers {
    pub fn new(analysis: Arc<dyn Analysis>) -> Workers {
        let (tx, rx) = mpsc::channel();
        Workers {
            tx,
            rx,
            phase_gen: Arc::new(AtomicU64::new(0)),
            sweep_gen: Arc::new(AtomicU64::new(0)),
            orbit_gen: Arc::new(AtomicU64::new(0)),
            gate: Arc::new(Gate::default()),
            sweep_pause: Arc::new(PauseGate::default()),
            analysis,
        }
    }

    /// Stop everything (quit, SIGHUP): bump every generation and wake parked workers.
    pub fn cancel_all(&self) {
        self.phase_gen.fetch_add(1, Ordering::SeqCst);
        self.sweep_gen.fetch_add(1, Ordering::SeqCst);
        self.orbit_gen.fetch_add(1, Ordering::SeqCst);
        self.gate.kick();
    }

    /// Restart the phase plot from `state`; returns the new generation.
    pub fn start_phase(&self, sys: System, state: State) -> u64 {
        let gen = self.phase_gen.fetch_add(1, Ordering::SeqCst) + 1;
        self.gate.kick();
        let current = self.phase_gen.clone();
        let gate = self.gate.clone();
        let tx = self.tx.clone();
        std::thread::Builder::new()
            .name("phase-plot".into())
            .spawn(move || phase_worker(sys, state, gen, &current, &gate, &tx))
            .ok();
        gen
    }

    /// Cancel the running sweep (new parameters while paused, quit); a paused one
    /// stops at once too.
    pub fn cancel_sweep(&self) {
        self.sweep_gen.fetch_add(1, Ordering::SeqCst);
        self.sweep_pause.wake();
    }

    /// Cancel the running sweep and start `spec` under a new generation. A forwarding
    /// thread (blocked on the engine's channel, so idle costs nothing) passes its
    /// batches on as [`Msg::Sweep`]. Returns the generation, or the engine's refusal.
    pub fn start_sweep(&self, spec: SweepSpec) -> (u64, Result<(), String>) {
        let gen = self.sweep_gen.fetch_add(1, Ordering::SeqCst) + 1;
        let handle =
            match sweep::start_pausable(spec, self.sweep_gen.clone(), self.sweep_pause.clone()) {
                Ok(h) => h,
                Err(e) => return (gen, Err(e.to_string())),
            };
        let gen = handle.generation();
        let tx = self.tx.clone();
        std::thread::Builder::new()
            .name("sweep-forward".into())
            .spawn(move || {
                for b in handle.receiver() {
                    if handle.is_current(&b) && tx.send(Msg::Sweep(b)).is_err() {
                        handle.cancel();
                        return;
                    }
                }
                let summary = handle.wait();
                if !summary.cancelled {
                    let _ = tx.send(Msg::SweepDone { gen });
                }
            })
            .ok();
        (gen, Ok(()))
    }

    /// Recompute the orbit analysis on the rayon pool; returns the new generation.
    pub fn start_orbits(&self, sys: System, k: u32, window: (f64, f64)) -> u64 {
        let gen = self.orbit_gen.fetch_add(1, Ordering::SeqCst) + 1;
        let current = self.orbit_gen.clone();
        let analysis = self.analysis.clone();
        let tx = self.tx.clone();
        rayon::spawn(move || {
            if current.load(Ordering::Relaxed) != gen {
                return;
            }
            let info = analysis.orbits(&sys, k, window);
            if current.load(Ordering::Relaxed) == gen {
                let _ = tx.send(Msg::Orbits { gen, info });
            }
        });
        gen
    }
}

/// Iterate the map from `state`, sending (phase, v) after every event.
pub fn phase_worker(
    sys: System,
    state: State,
    gen: u64,
    current: &AtomicU64,
    gate: &Gate,
    tx: &Sender<Msg>,
) {
    let mut map = ImpactMap::new(sys, Solver::Exact, state);
    let mut sent = 0usize;
    while sent < PHASE_CAP {
        if !gate.wait(gen, current) {
            return;
        }
        let n = if sent == 0 { PHASE_BURST } else { PHASE_CHUNK };
        let mut points = Vec::with_capacity(n);
        let mut note = None;
        for _ in 0..n {
            match map.step() {
                Ok(Event { phase, v, .. }) => points.push((phase, v)),
                Err(h) => {
                    note = Some(h.to_string());
                    break;
                }
            }
        }
        sent += points.len();
        let done = note.is_some() || sent >= PHASE_CAP;
        if current.load(Ordering::Relaxed) != gen
            || tx
                .send(Msg::Phase {
                    gen,
                    points,
                    done,
                    note,
                })
                .is_err()
            || done
        {
            return;
        }
        std::thread::sleep(PHASE_PACE);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn phase_worker_streams_the_same_points_as_the_map() {
        let sys = System::new(Table::fd(0.1).unwrap(), 0.45, 0.8).unwrap();
        let st = State::launch(&sys, 0, 0.0, sys.df(0.0) + 0.5, 0.0).unwrap();
        let (tx, rx) = mpsc::channel();
        let current = AtomicU64::new(1);
        let gate = Gate::default();
        // Stop after the first chunk by going stale once it is sent.
        std::thread::scope(|s| {
            s.spawn(|| phase_worker(sys.clone(), st, 1, &current, &gate, &tx));
            let first = rx.recv().unwrap();
            current.store(2, Ordering::SeqCst);
            let Msg::Phase { gen, points, .. } = first else {
                panic!("unexpected message")
            };
            assert_eq!(gen, 1);
            assert_eq!(points.len(), PHASE_BURST);
            let mut map = ImpactMap::new(sys.clone(), Solver::Exact, st);
            for p in points.iter().take(50) {
                let e = map.step().unwrap();
                assert_eq!(*p, (e.phase, e.v));
            }
        });
    }

    #[test]
    fn paused_gate_parks_until_resumed_or_stale() {
        let gate = Arc::new(Gate::default());
        gate.set(true);
        let current = Arc::new(AtomicU64::new(7));
        let (g, c) = (gate.clone(), current.clone());
        let h = std::thread::spawn(move || g.wait(7, &c));
        std::thread::sleep(Duration::from_millis(30));
        assert!(!h.is_finished());
        current.store(8, Ordering::SeqCst);
        gate.kick();
        assert!(!h.join().unwrap());
        gate.set(false);
        assert!(gate.wait(8, &current));
    }
}
