//! Background work for the panels, latest-wins.
//!
//! Every piece of background work is addressed to a [`Target`] (the panel that shows
//! it) and runs under that target's generation counter: starting new work for a target
//! cancels the old, workers stop within milliseconds, and the UI drops any message
//! whose generation is stale. Results come back over one channel as [`Msg`]s whose body
//! only the target panel reads, so a new panel needs no new message type here.
//!
//! Two kinds of work:
//! * jobs over many items (the diagram's sweep, the basin picture, the plane) run on the engine's [`Executor`], which
//!   owns its pool; their batches are forwarded as messages, then [`JobDone`];
//! * interactive work (the phase plot, the orbit analysis) runs on a thread of its own,
//!   so it never waits behind a job, paused or not.
//!
//! One pause [`Gate`] parks everything that checks it (job workers, the phase plot):
//! paused means no CPU and no output, and every item keeps its progress.

use bouncemap_engine::jobs::{Control, Executor, Gate, Job};
use std::any::Any;
use std::collections::HashMap;
use std::sync::mpsc::{self, Receiver, Sender};
use std::sync::Arc;

/// Whose background work a message is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Target {
    Diagram,
    Phase,
    Orbits,
    Basins,
    Plane,
    Branches,
}

impl Target {
    pub const ALL: [Target; 6] = [
        Target::Diagram,
        Target::Phase,
        Target::Orbits,
        Target::Basins,
        Target::Plane,
        Target::Branches,
    ];
}

/// What a message carries; the target panel knows its type.
pub type Body = Box<dyn Any + Send>;

/// A message from background work to a panel.
pub struct Msg {
    pub to: Target,
    pub gen: u64,
    pub body: Body,
}

impl Msg {
    pub fn new<T: Send + 'static>(to: Target, gen: u64, body: T) -> Msg {
        Msg {
            to,
            gen,
            body: Box::new(body),
        }
    }
}

impl std::fmt::Debug for Msg {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Msg {{ to: {:?}, gen: {} }}", self.to, self.gen)
    }
}

/// Sent after the last batch of a job that ran to its end.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct JobDone;

/// What interactive work needs: its generation, whether it is still current, the
/// pause gate, and the way back to its panel.
pub struct Ticket {
    to: Target,
    gen: u64,
    control: Control,
    tx: Sender<Msg>,
}

impl Ticket {
    /// Whether newer work has replaced this one.
    pub fn stale(&self) -> bool {
        !self.control.is_current(self.gen)
    }

    /// Park while paused; false if the work went stale meanwhile.
    pub fn wait_if_paused(&self) -> bool {
        self.control.gate().wait(|| self.stale());
        !self.stale()
    }

    /// Send a result to the panel; false if stale or nobody listens any more.
    pub fn send<T: Send + 'static>(&self, body: T) -> bool {
        !self.stale() && self.tx.send(Msg::new(self.to, self.gen, body)).is_ok()
    }
}

/// The workers the runtime owns.
pub struct Workers {
    executor: Executor,
    gate: Arc<Gate>,
    controls: HashMap<Target, Control>,
    tx: Sender<Msg>,
    pub rx: Receiver<Msg>,
}

impl Workers {
    /// Workers whose jobs run on `executor`.
    pub fn new(executor: Executor) -> Workers {
        let (tx, rx) = mpsc::channel();
        let gate = Arc::new(Gate::default());
        let controls = Target::ALL
            .iter()
            .map(|t| (*t, Control::with_gate(gate.clone())))
            .collect();
        Workers {
            executor,
            gate,
            controls,
            tx,
            rx,
        }
    }

    fn control(&self, to: Target) -> &Control {
        &self.controls[&to]
    }

    /// Pause or resume everything that checks the gate.
    pub fn pause(&self, paused: bool) {
        self.gate.set(paused);
    }

    /// Cancel the work of `to`.
    pub fn cancel(&self, to: Target) {
        self.control(to).cancel();
    }

    /// Stop everything (quit, SIGHUP).
    pub fn cancel_all(&self) {
        for c in self.controls.values() {
            c.cancel();
        }
    }

    /// Run `work` on a thread of its own under a new generation of `to` (cancelling
    /// the previous one); returns the generation.
    pub fn spawn(&self, to: Target, name: &str, work: impl FnOnce(Ticket) + Send + 'static) -> u64 {
        let control = self.control(to).clone();
        let gen = control.cancel();
        let ticket = Ticket {
            to,
            gen,
            control,
            tx: self.tx.clone(),
        };
        let _ = std::thread::Builder::new()
            .name(name.into())
            .spawn(move || work(ticket));
        gen
    }

    /// Start `job` on the executor under a new generation of `to` (cancelling the
    /// previous one). A forwarding thread (blocked on the job's channel, so idle costs
    /// nothing) passes its batches on as messages, then [`JobDone`] if it ran to its end.
    pub fn start_job<J: Job>(&self, to: Target, job: J) -> u64 {
        let control = self.control(to).clone();
        control.cancel();
        let handle = self.executor.start(job, &control);
        let gen = handle.generation();
        let tx = self.tx.clone();
        let _ = std::thread::Builder::new()
            .name("job-forward".into())
            .spawn(move || {
                for b in handle.receiver() {
                    if handle.is_current(&b) && tx.send(Msg::new(to, gen, b)).is_err() {
                        handle.cancel();
                        return;
                    }
                }
                if !handle.wait().cancelled {
                    let _ = tx.send(Msg::new(to, gen, JobDone));
                }
            });
        gen
    }
}
