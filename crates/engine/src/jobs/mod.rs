//! One executor for every computation over many independent work items: the values of
//! a bifurcation diagram, the initial conditions of a basin picture, the pixels of a
//! two-parameter map, the branches of a continuation.
//!
//! A [`Job`] lists its work items and runs them in passes (a coarse pass first, then a
//! fine one); an item keeps a state from one pass to the next, so the second pass
//! continues where the first stopped. Results stream to the consumer as [`Batch`]es
//! over a channel, each tagged with the generation it was computed for.
//!
//! # Cancellation, generations and pause
//! A [`Control`] is a generation counter and a pause [`Gate`]. A job takes the counter's
//! value when it starts; workers compare the counter with it in [`Context::tick`] (every
//! few dozen events, tens of microseconds) and stop as soon as it changed, and a batch is
//! only sent while it has not. A consumer that bumps the counter and starts the next job
//! drops any batch whose generation is not the counter's current value
//! ([`Handle::is_current`]), so no stale batch is ever used. While the gate is closed the
//! workers park in `tick` without spinning and keep their progress; a cancellation also
//! ends a pause. Several jobs can share one gate (pause everything) and one counter
//! (latest wins).
//!
//! # The pool
//! An [`Executor`] owns its thread pool: jobs never run on rayon's global pool, so work
//! that must answer at once (the terminal application's orbit analysis, its phase plot)
//! runs on threads of its own and never waits behind a job, paused or not.
//!
//! # Bounded memory
//! [`Executor::start_windowed`] lets at most `window` items of the last pass run ahead of
//! what the consumer has acknowledged ([`Handle::ack`]): a consumer that writes results
//! in item order holds at most `window` of them.
//!
//! # What jobs run over
//! [`grid`]: the parameter grids (what a value or a pixel is, its system) and the shards
//! of a grid; [`picture`]: the coarse-to-fine pictures over a grid that the plane and the
//! basins fill in.

mod gate;
pub mod grid;
pub mod picture;

pub use gate::{Gate, POLL};

use crate::error::EngineError;
use std::collections::HashMap;
use std::ops::Deref;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::mpsc::{self, Receiver, Sender};
use std::sync::{Arc, Condvar, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// How many events a worker may compute between two looks at the cancellation flag.
pub const CANCEL_EVERY: u64 = 64;

/// A computation over independent work items, run in passes.
pub trait Job: Send + Sync + 'static {
    /// What an item carries from one pass to the next (e.g. a resumable orbit).
    type State: Send;
    /// What the job streams to its consumer.
    type Output: Send + 'static;

    /// The passes, each over items 0..len in natural or spread order.
    fn passes(&self) -> Vec<Pass>;

    /// Units of progress in the whole job (e.g. values of a sweep); a unit is done when
    /// a complete result for it is emitted.
    fn units(&self) -> usize;

    /// Work on `item` in pass `pass`. `state` is what the previous pass left (None in
    /// the first pass that sees the item). Call [`Context::tick`] every
    /// [`CANCEL_EVERY`] events or so and return when it says stop; hand results to
    /// [`Context::emit`].
    fn work(
        &self,
        pass: usize,
        item: usize,
        state: &mut Option<Self::State>,
        cx: &Context<'_, Self::Output>,
    );
}

/// One pass of a job: items 0..`len`, handed out in index order or spread over the
/// range (bit-reversed: every prefix covers the whole range coarsely, as a preview
/// wants).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Pass {
    /// Number of items.
    pub len: usize,
    /// Hand the items out spread over the range (bit-reversed) rather than in order.
    pub spread: bool,
}

impl Pass {
    /// Items 0..len in index order.
    pub fn natural(len: usize) -> Pass {
        Pass { len, spread: false }
    }

    /// Items 0..len spread over the range.
    pub fn spread(len: usize) -> Pass {
        Pass { len, spread: true }
    }
}

/// A generation counter and a pause gate, shared by the owner of jobs and their workers.
#[derive(Clone, Debug, Default)]
pub struct Control {
    generation: Arc<AtomicU64>,
    gate: Arc<Gate>,
}

impl Control {
    /// A fresh counter (generation 0) and an open gate.
    pub fn new() -> Control {
        Control::default()
    }

    /// A fresh counter that pauses with `gate` (shared by several controls).
    pub fn with_gate(gate: Arc<Gate>) -> Control {
        Control {
            generation: Arc::new(AtomicU64::new(0)),
            gate,
        }
    }

    /// The current generation.
    pub fn generation(&self) -> u64 {
        self.generation.load(Ordering::SeqCst)
    }

    /// Cancel whatever runs under the current generation; returns the new one.
    pub fn cancel(&self) -> u64 {
        let g = self.generation.fetch_add(1, Ordering::SeqCst) + 1;
        self.gate.wake();
        g
    }

    /// Whether `generation` is still the current one.
    pub fn is_current(&self, generation: u64) -> bool {
        self.generation() == generation
    }

    /// The pause gate.
    pub fn gate(&self) -> &Arc<Gate> {
        &self.gate
    }
}

/// One result of a job, with the generation and pass that produced it.
#[derive(Clone, Debug, PartialEq)]
pub struct Batch<T> {
    /// The generation of the [`Control`] the job ran under.
    pub generation: u64,
    /// The pass that produced it.
    pub pass: u32,
    /// The result itself.
    pub data: T,
}

impl<T> Deref for Batch<T> {
    type Target = T;
    fn deref(&self) -> &T {
        &self.data
    }
}

/// A snapshot of a job's progress.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Progress {
    /// Units with a complete result.
    pub done: usize,
    /// Units in the job.
    pub total: usize,
    /// Events computed so far (as counted by [`Context::tick`]).
    pub events: u64,
    /// Wall time, paused time left out.
    pub elapsed: Duration,
}

impl Progress {
    /// Events computed per second of (unpaused) wall time.
    pub fn events_per_second(&self) -> f64 {
        self.events as f64 / self.elapsed.as_secs_f64().max(1e-9)
    }

    /// Fraction of units done, 0..=1.
    pub fn fraction(&self) -> f64 {
        if self.total == 0 {
            1.0
        } else {
            self.done as f64 / self.total as f64
        }
    }
}

/// How a job ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Summary {
    /// The generation the job ran under.
    pub generation: u64,
    /// True if the generation changed (or the handle was dropped) before the end.
    pub cancelled: bool,
    /// Progress at the end.
    pub progress: Progress,
}

#[derive(Debug, Default)]
struct Counters {
    done: AtomicUsize,
    events: AtomicU64,
}

/// Backpressure of [`Executor::start_windowed`]: how far the last pass may run ahead.
#[derive(Debug)]
struct Window {
    size: usize,
    acked: Mutex<usize>,
    changed: Condvar,
}

/// What a worker needs to report and to know when to stop.
pub struct Context<'a, T> {
    shared: &'a Shared<T>,
    pass: u32,
}

struct Shared<T> {
    generation: u64,
    control: Control,
    abandoned: Arc<AtomicBool>,
    counters: Arc<Counters>,
    tx: Sender<Batch<T>>,
}

impl<T> Shared<T> {
    fn stopped(&self) -> bool {
        self.control.generation.load(Ordering::Relaxed) != self.generation
            || self.abandoned.load(Ordering::Relaxed)
    }
}

impl<T> Context<'_, T> {
    /// Count `events` computed since the last call, park while paused, and say whether
    /// the job must stop (cancelled, or nobody reads its results any more).
    pub fn tick(&self, events: u64) -> bool {
        self.shared
            .counters
            .events
            .fetch_add(events, Ordering::Relaxed);
        self.shared.control.gate.wait(|| self.shared.stopped());
        self.shared.stopped()
    }

    /// Whether the job must stop, without counting or parking.
    pub fn stopped(&self) -> bool {
        self.shared.stopped()
    }

    /// Hand a result to the consumer; `complete` marks a unit of progress done. Nothing
    /// is sent once the job was cancelled.
    pub fn emit(&self, data: T, complete: bool) {
        self.emit_units(data, usize::from(complete));
    }

    /// Hand a result to the consumer that completes `units` units of progress (e.g. a
    /// chunk of grid points). Nothing is sent once the job was cancelled.
    pub fn emit_units(&self, data: T, units: usize) {
        let s = self.shared;
        if s.stopped() {
            return;
        }
        s.counters.done.fetch_add(units, Ordering::Relaxed);
        let batch = Batch {
            generation: s.generation,
            pass: self.pass,
            data,
        };
        if s.tx.send(batch).is_err() {
            s.abandoned.store(true, Ordering::SeqCst);
        }
    }
}

/// Runs jobs on a pool of its own.
#[derive(Clone, Debug)]
pub struct Executor {
    pool: Arc<rayon::ThreadPool>,
}

impl Executor {
    /// An executor with `threads` worker threads.
    pub fn new(threads: usize) -> Result<Executor, EngineError> {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads.max(1))
            .thread_name(|i| format!("job-{i}"))
            .build()
            .map_err(|e| {
                EngineError::Inconsistent(format!("cannot start {threads} worker threads: {e}"))
            })?;
        Ok(Executor {
            pool: Arc::new(pool),
        })
    }

    /// An executor with one thread per core.
    pub fn all_cores() -> Result<Executor, EngineError> {
        Executor::new(available_cores())
    }

    /// Worker threads.
    pub fn threads(&self) -> usize {
        self.pool.current_num_threads()
    }

    /// Start `job` in the background under `control`'s current generation.
    pub fn start<J: Job>(&self, job: J, control: &Control) -> Handle<J::Output> {
        self.launch(job, control, None)
    }

    /// [`Self::start`], with the last pass running at most `window` items ahead of
    /// what the consumer acknowledged with [`Handle::ack`] (bounded memory for a
    /// consumer that writes results in item order).
    pub fn start_windowed<J: Job>(
        &self,
        job: J,
        control: &Control,
        window: usize,
    ) -> Handle<J::Output> {
        self.launch(job, control, Some(window.max(1)))
    }

    /// Run `job` to its end, handing every current batch to `on_batch` on the calling
    /// thread as it arrives.
    pub fn run<J: Job>(
        &self,
        job: J,
        control: &Control,
        mut on_batch: impl FnMut(Batch<J::Output>),
    ) -> Summary {
        let handle = self.start(job, control);
        for b in handle.receiver() {
            if handle.is_current(&b) {
                on_batch(b);
            }
        }
        handle.wait()
    }

    fn launch<J: Job>(
        &self,
        job: J,
        control: &Control,
        window: Option<usize>,
    ) -> Handle<J::Output> {
        let generation = control.generation();
        let (tx, rx) = mpsc::channel();
        let counters = Arc::new(Counters::default());
        let abandoned = Arc::new(AtomicBool::new(false));
        let total = job.units();
        let started = Instant::now();
        let paused_before = control.gate.paused_for();
        let window = window.map(|size| {
            Arc::new(Window {
                size,
                acked: Mutex::new(0),
                changed: Condvar::new(),
            })
        });
        let shared = Shared {
            generation,
            control: control.clone(),
            abandoned: abandoned.clone(),
            counters: counters.clone(),
            tx,
        };
        let pool = self.pool.clone();
        let win = window.clone();
        let thread = std::thread::Builder::new()
            .name("job".into())
            .spawn(move || {
                pool.install(|| run_passes(&job, &shared, win.as_deref()));
                let paused = shared
                    .control
                    .gate
                    .paused_for()
                    .saturating_sub(paused_before);
                Summary {
                    generation,
                    cancelled: shared.stopped(),
                    progress: Progress {
                        done: shared.counters.done.load(Ordering::Relaxed),
                        total,
                        events: shared.counters.events.load(Ordering::Relaxed),
                        elapsed: started.elapsed().saturating_sub(paused),
                    },
                }
            })
            .expect("the system can start a thread");
        Handle {
            generation,
            control: control.clone(),
            abandoned,
            receiver: rx,
            counters,
            total,
            started,
            paused_before,
            window,
            thread: Some(thread),
        }
    }
}

/// Cores of this machine (1 if unknown).
pub fn available_cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

fn run_passes<J: Job>(job: &J, shared: &Shared<J::Output>, window: Option<&Window>) {
    // Only the items that carry something to the next pass hold a state.
    let states: Mutex<HashMap<usize, J::State>> = Mutex::new(HashMap::new());
    let passes = job.passes();
    let last = passes.len().saturating_sub(1);
    for (p, pass) in passes.iter().enumerate() {
        if shared.stopped() {
            return;
        }
        let cx = Context {
            shared,
            pass: p as u32,
        };
        let order = pass.spread.then(|| bit_reversed_order(pass.len));
        let win = if p == last { window } else { None };
        for_each(pass.len, shared, win, &|k| {
            let item = order.as_ref().map_or(k, |o| o[k]);
            let mut slot = states
                .lock()
                .unwrap_or_else(|e| e.into_inner())
                .remove(&item);
            job.work(p, item, &mut slot, &cx);
            if let Some(st) = slot {
                states
                    .lock()
                    .unwrap_or_else(|e| e.into_inner())
                    .insert(item, st);
            }
        });
    }
}

/// Run `f(k)` for k in 0..n on every thread of the current pool, handing out k in order
/// from a shared counter, until done or stopped.
fn for_each<T: Send>(
    n: usize,
    shared: &Shared<T>,
    window: Option<&Window>,
    f: &(dyn Fn(usize) + Sync),
) {
    let next = AtomicUsize::new(0);
    let workers = rayon::current_num_threads().clamp(1, n.max(1));
    rayon::scope(|s| {
        for _ in 0..workers {
            s.spawn(|_| loop {
                if shared.stopped() {
                    return;
                }
                let k = next.fetch_add(1, Ordering::Relaxed);
                if k >= n {
                    return;
                }
                if let Some(w) = window {
                    let mut acked = w.acked.lock().unwrap_or_else(|e| e.into_inner());
                    while k >= *acked + w.size && !shared.stopped() {
                        acked = w
                            .changed
                            .wait_timeout(acked, POLL)
                            .unwrap_or_else(|e| e.into_inner())
                            .0;
                    }
                }
                f(k);
            });
        }
    });
}

/// A running job.
#[derive(Debug)]
pub struct Handle<T> {
    generation: u64,
    control: Control,
    abandoned: Arc<AtomicBool>,
    receiver: Receiver<Batch<T>>,
    counters: Arc<Counters>,
    total: usize,
    started: Instant,
    paused_before: Duration,
    window: Option<Arc<Window>>,
    thread: Option<JoinHandle<Summary>>,
}

impl<T> Handle<T> {
    /// The generation this job runs under.
    pub fn generation(&self) -> u64 {
        self.generation
    }

    /// The batch stream; it disconnects when the job ends or is cancelled.
    pub fn receiver(&self) -> &Receiver<Batch<T>> {
        &self.receiver
    }

    /// Whether a batch belongs to the generation that is current now.
    pub fn is_current(&self, batch: &Batch<T>) -> bool {
        self.control.is_current(batch.generation)
    }

    /// Every batch waiting in the channel that belongs to the current generation,
    /// without blocking.
    pub fn drain(&self) -> Vec<Batch<T>> {
        self.receiver
            .try_iter()
            .filter(|b| self.is_current(b))
            .collect()
    }

    /// Cancel this job (and anything else running under the same generation) by
    /// advancing the control's counter, unless a newer generation already runs.
    pub fn cancel(&self) {
        let _ = self.control.generation.compare_exchange(
            self.generation,
            self.generation + 1,
            Ordering::SeqCst,
            Ordering::SeqCst,
        );
        self.control.gate.wake();
    }

    /// The consumer has used the first `items` items of the last pass's order (a
    /// windowed job may then run further ahead).
    pub fn ack(&self, items: usize) {
        if let Some(w) = &self.window {
            let mut a = w.acked.lock().unwrap_or_else(|e| e.into_inner());
            if items > *a {
                *a = items;
                w.changed.notify_all();
            }
        }
    }

    /// Progress so far.
    pub fn progress(&self) -> Progress {
        let paused = self
            .control
            .gate
            .paused_for()
            .saturating_sub(self.paused_before);
        Progress {
            done: self.counters.done.load(Ordering::Relaxed),
            total: self.total,
            events: self.counters.events.load(Ordering::Relaxed),
            elapsed: self.started.elapsed().saturating_sub(paused),
        }
    }

    /// Whether every worker has stopped.
    pub fn is_finished(&self) -> bool {
        self.thread.as_ref().is_none_or(|t| t.is_finished())
    }

    /// Wait for the workers to stop and return the summary.
    pub fn wait(mut self) -> Summary {
        let t = self.thread.take().expect("joined once");
        match t.join() {
            Ok(s) => s,
            Err(p) => std::panic::resume_unwind(p),
        }
    }
}

impl<T> Drop for Handle<T> {
    fn drop(&mut self) {
        // Nobody will read the batches: stop the workers without touching the shared
        // counter (a newer job may already run under it).
        self.abandoned.store(true, Ordering::SeqCst);
        self.control.gate.wake();
        if let Some(w) = &self.window {
            w.changed.notify_all();
        }
    }
}

/// Positions 0..n in bit-reversed order: every prefix is spread over the whole range.
pub fn bit_reversed_order(n: usize) -> Vec<usize> {
    if n <= 1 {
        return (0..n).collect();
    }
    let bits = usize::BITS - (n - 1).leading_zeros();
    let mut v: Vec<usize> = (0..n).collect();
    v.sort_by_key(|&i| i.reverse_bits() >> (usize::BITS - bits));
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Sums 0..=item in steps, emitting the result; pass 0 goes half way, pass 1 ends.
    struct Sums {
        n: usize,
    }

    impl Job for Sums {
        type State = (u64, u64);
        type Output = (usize, u64, bool);
        fn passes(&self) -> Vec<Pass> {
            vec![Pass::spread(self.n), Pass::natural(self.n)]
        }
        fn units(&self) -> usize {
            self.n
        }
        fn work(
            &self,
            pass: usize,
            item: usize,
            st: &mut Option<(u64, u64)>,
            cx: &Context<'_, Self::Output>,
        ) {
            let (mut i, mut sum) = st.take().unwrap_or((0, 0));
            let end = if pass == 0 {
                item as u64 / 2
            } else {
                item as u64
            };
            while i <= end {
                sum += i;
                i += 1;
                if cx.tick(1) {
                    return;
                }
            }
            *st = Some((i, sum));
            cx.emit((item, sum, pass == 1), pass == 1);
        }
    }

    #[test]
    fn passes_resume_item_state_and_stream_every_result() {
        let ex = Executor::new(2).unwrap();
        let control = Control::new();
        let mut finals = vec![None; 50];
        let mut previews = 0;
        let summary = ex.run(Sums { n: 50 }, &control, |b| {
            let (item, sum, complete) = b.data;
            if complete {
                finals[item] = Some(sum);
            } else {
                previews += 1;
            }
        });
        assert!(!summary.cancelled);
        assert_eq!(summary.progress.done, 50);
        assert_eq!(previews, 50);
        for (n, s) in finals.iter().enumerate() {
            // Closed form: 0 + 1 + ... + n, with no term counted twice across passes.
            assert_eq!(*s, Some((n * (n + 1) / 2) as u64), "item {n}");
        }
    }

    #[test]
    fn a_window_holds_the_last_pass_to_the_acknowledged_items() {
        let ex = Executor::new(2).unwrap();
        let control = Control::new();
        let h = ex.start_windowed(Sums { n: 40 }, &control, 4);
        let mut seen = Vec::new();
        // Without acknowledgements, at most 4 items of the last pass come out.
        let deadline = Instant::now() + Duration::from_millis(300);
        while Instant::now() < deadline {
            if let Ok(b) = h.receiver().recv_timeout(Duration::from_millis(20)) {
                if b.data.2 {
                    seen.push(b.data.0);
                }
            }
        }
        seen.sort();
        assert_eq!(seen, vec![0, 1, 2, 3]);
        h.ack(40);
        let mut rest = 0;
        for b in h.receiver() {
            rest += usize::from(b.data.2);
        }
        assert_eq!(rest, 36);
        h.wait();
    }

    #[test]
    fn bit_reversed_order_is_a_permutation_that_spreads() {
        let o = bit_reversed_order(10);
        let mut s = o.clone();
        s.sort();
        assert_eq!(s, (0..10).collect::<Vec<_>>());
        assert_eq!(&o[..4], &[0, 8, 4, 2]);
    }
}
