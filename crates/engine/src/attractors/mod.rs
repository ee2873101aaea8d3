//! Attractors: what an orbit ends on, which starts end on the same one, and how much
//! of the state space goes to each.
//!
//! * [`identify`] takes an orbit run to the end of its transient (a [`OrbitRun`], with
//!   the sweep's early stop) and says what it settled on ([`Found`]): a cycle (its
//!   events, (n, k), the eigenvalues of its Jacobian), a stick–release cycle, a resting
//!   ball, an escape (no landing), or an unsettled orbit, sampled for
//!   [`Settle::sample`] more events: the coarse cells of (t̂, v) it visits and its
//!   exponents by QR ([`lyapunov`]).
//! * A [`Registry`] decides which starts share an attractor ([`Registry::assign`]):
//!   cycles when they have the same kind and (n, k) and, for some rotation, every event
//!   agrees to [`MATCH`] in phase (around the circle) and velocity (each converged copy
//!   is within the detection tolerance, 10⁻¹¹, of the limit cycle); unsettled orbits by
//!   the recurrence rule of Attractors.jl's `AttractorsViaRecurrences`, in the form: a
//!   start belongs to a known attractor when at least [`OVERLAP`] of its sampled events
//!   fall in cells that attractor's orbits visited (the attractor's cells then grow by
//!   the start's); among unsettled orbits the cells are [`COARSE`] ones, so that two
//!   samples of one chaotic set spread over many cells are one attractor. Resting and escaping starts each form one attractor. An unsettled
//!   orbit is chaotic when its largest exponent exceeds three standard errors and
//!   [`CHAOS_FLOOR`]; otherwise it stays "unsettled" (a cycle longer than the
//!   detector's limit, one converging too slowly for the transient, or a torus).
//! * [`basins`]: the basin picture over a grid of starts, as a job.
//!
//! Starts are placed in the box t̂0 ∈ [0, 1), w0 = v0 − f'(t̂0) ∈ [0, W] with W
//! from [`default_w_max`]; [`box_start`] spreads any number of them over it.

pub mod basins;
pub mod crisis;
pub mod global;
pub mod jumps;
pub mod known;
pub mod lyapunov;
pub mod saddles;
pub mod sampled;
pub mod separation;
pub mod statistics;
pub mod tangency;

use crate::impact::Solver;
use crate::limits;
use crate::map::{EventKind, ImpactMap, State};
use crate::run::detect::Periodicity;
use crate::run::precision::{self, Precision};
use crate::run::{Advance, OrbitRun, Outcome, Point};
use crate::system::System;
use crate::time::phase_distance;
use lyapunov::{cycle_spectrum, qr_spectrum, CycleEvent, Spectrum, Stop};
use std::collections::HashSet;

/// Two copies of a cycle are one cycle when every event agrees to this.
pub const MATCH: f64 = 1e-8;
/// Share of a start's sampled events that must fall in an attractor's cells.
pub const OVERLAP: f64 = 0.5;
/// Phase cells per period, and velocity cells per unit of velocity.
pub const CELLS_PER_PERIOD: f64 = 128.0;
/// Velocity cells per unit of velocity.
pub const CELLS_PER_VELOCITY: f64 = 64.0;
/// Cells per side of a coarse cell: unsettled orbits are matched to each other on
/// coarse cells of 4 × 4 cells (1/32 period by 1/16 velocity). Two samples of one
/// chaotic set visit different fine cells where the set is spread over many more
/// cells than a sample has events; on coarse cells they overlap.
pub const COARSE: u32 = 4;
/// An unsettled orbit is chaotic only when its largest exponent per impact exceeds this
/// (and three standard errors).
pub const CHAOS_FLOOR: f64 = 1e-3;
/// Tangent steps that align the QR vectors before an unsettled orbit is sampled.
pub const ALIGN: u64 = 200;
/// Cells of (t̂, v) an unsettled orbit's sample records at most (about 40 MB): the
/// sample's memory does not grow with its length.
pub const MAX_VISITED_CELLS: usize = 1 << 20;

/// How a start is run to its attractor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settle {
    /// End of the transient, in table periods.
    pub transient: u64,
    /// Early stop on detected cycles (None: every start runs to the end of the transient
    /// and is then sampled as an unsettled orbit).
    pub periodicity: Option<Periodicity>,
    /// Events sampled after an unsettled transient (cells and exponents).
    pub sample: u64,
    /// The next-contact solver.
    pub solver: Solver,
}

impl Settle {
    /// The basin defaults: transient 5000 periods, early stop, 2000 sampled events.
    pub const BASINS: Settle = Settle {
        transient: 5_000,
        periodicity: Some(Periodicity {
            max_period: 64,
            tolerance: 1e-11,
        }),
        sample: 2_000,
        solver: Solver::Exact,
    };
}

/// The kind of an attractor.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Kind {
    /// A cycle of impacts.
    Periodic,
    /// A cycle (or orbit) that sticks to the table and is released again.
    Sticking,
    /// An unsettled orbit with a positive largest exponent.
    Chaotic,
    /// An orbit with no cycle found whose largest exponent is negative (beyond three
    /// standard errors): periodic, but with a period over
    /// [`LONG_PERIOD`](crate::run::detect::LONG_PERIOD) events, or converging too slowly
    /// for the transient. Never chaos.
    Converging,
    /// An orbit neither periodic up to the detectors' length nor shown chaotic nor
    /// converging: its exponent is zero within its error (a torus, a marginal orbit).
    Unsettled,
    /// The ball rides on the table forever.
    Resting,
    /// The ball did not land within the solver's work bound.
    Escaping,
}

impl Kind {
    /// Every kind, in output order.
    pub const ALL: [Kind; 7] = [
        Kind::Periodic,
        Kind::Sticking,
        Kind::Chaotic,
        Kind::Converging,
        Kind::Unsettled,
        Kind::Resting,
        Kind::Escaping,
    ];

    /// Lower-case name used in every output format.
    pub fn as_str(self) -> &'static str {
        match self {
            Kind::Periodic => "periodic",
            Kind::Sticking => "sticking",
            Kind::Chaotic => "chaotic",
            Kind::Converging => "converging",
            Kind::Unsettled => "unsettled",
            Kind::Resting => "resting",
            Kind::Escaping => "escaping",
        }
    }
}

/// What one start's orbit tells about its attractor.
#[derive(Clone, Debug, PartialEq)]
pub enum Signature {
    /// The events of one cycle, rotated to start at the smallest phase.
    Cycle(Vec<CycleEvent>),
    /// Sampled events per visited cell (cell, count), sorted by cell.
    Visits(Vec<(u64, u32)>),
    /// Resting on the table.
    Resting,
    /// No landing.
    Escaping,
}

/// The attractor one start ended on.
#[derive(Clone, Debug, PartialEq)]
pub struct Found {
    /// What the orbit settled on.
    pub kind: Kind,
    /// Events and table periods per cycle, for cycles.
    pub events: Option<usize>,
    /// Table periods per cycle, for cycles.
    pub periods: Option<i64>,
    /// A point on it: (phase, v) right after an event (for a cycle the event of smallest
    /// phase; for an unsettled orbit its last sampled event; for a resting ball where it
    /// came to rest).
    pub point: Option<(f64, f64)>,
    /// Both exponents, where the orbit has them.
    pub spectrum: Option<Spectrum>,
    /// What identifies the attractor among others (its cycle, or the cells it visits).
    pub signature: Signature,
    /// For a cycle: whether double precision decides it ([`Precision`]; a sticking
    /// cycle's length may be beyond it).
    pub precision: Option<Precision>,
}

impl Found {
    /// The largest exponent per impact: −∞ for sticking and resting, None where there
    /// is none (escape, grazing).
    pub fn lyapunov(&self) -> Option<f64> {
        match self.kind {
            Kind::Resting => Some(f64::NEG_INFINITY),
            Kind::Escaping => None,
            _ => self.spectrum.and_then(|s| s.largest()),
        }
    }
}

/// The cell of a point (phase, v).
pub fn cell(phase: f64, v: f64) -> u64 {
    let p = (phase * CELLS_PER_PERIOD)
        .floor()
        .clamp(0.0, CELLS_PER_PERIOD - 1.0) as u64;
    let q = (v * CELLS_PER_VELOCITY)
        .floor()
        .clamp(i32::MIN as f64, i32::MAX as f64) as i32;
    (p << 32) | u64::from(q as u32)
}

/// The coarse cell (see [`COARSE`]) a cell lies in.
pub fn coarse(c: u64) -> u64 {
    let shift = COARSE.trailing_zeros();
    let p = (c >> 32) >> shift;
    let q = (c as u32 as i32) >> shift;
    (p << 32) | u64::from(q as u32)
}

/// The default height W of the start box: twice the table's largest velocity α·max|F'|,
/// at least 1 (the (1, 1) and (1, 2) orbits leave the table with w ≈ ½ and ≈ 1), and at
/// most the largest W accepted ([`limits::W_MAX`]), so a default is always valid.
pub fn default_w_max(sys: &System) -> f64 {
    (2.0 * sys.alpha() * sys.table().velocity_bound()).clamp(1.0, limits::W_MAX.hi)
}

/// Start `s` of a set spread over the box [0, 1) × [0, W]: the additive recurrence with
/// the plastic number (Roberts' R₂ sequence), whose every prefix covers the box evenly.
/// Returns (t̂0, w0).
pub fn box_start(s: usize, w_max: f64) -> (f64, f64) {
    const G: f64 = 1.324_717_957_244_746;
    let a1 = 1.0 / G;
    let a2 = 1.0 / (G * G);
    let x = (0.5 + a1 * s as f64).fract();
    let y = (0.5 + a2 * s as f64).fract();
    (x, w_max * y)
}

/// Bytes a visited cell takes in a hash table of visits (cell and count) at its worst:
/// the table least full, the one it grows from still held, and the sorted list made of
/// it.
const VISIT_BYTES: u64 = 64;
/// Bytes a cell takes in a hash set of cells at its worst (least full, while it grows).
const CELL_BYTES: u64 = 48;
/// Bytes measuring exponents on a cycle takes per event of the cycle, at most (its
/// events, flights and tangent maps): a generous bound.
const CYCLE_BYTES_PER_EVENT: u64 = 512;

/// The most [`identify`] holds at once, in bytes, sampling `sample` events of an
/// unsettled orbit: the cells the sample visits, or the events of a cycle of up to
/// [`LONG_PERIOD`](crate::run::detect::LONG_PERIOD) events and their tangent maps (the
/// bound of a memory estimate).
pub fn identify_bytes(sample: u64) -> u64 {
    let cells = sample.min(MAX_VISITED_CELLS as u64) * VISIT_BYTES;
    cells.max(crate::run::detect::LONG_PERIOD as u64 * CYCLE_BYTES_PER_EVENT)
}

/// Run `start` to its attractor: the transient with early stop, then [`identify`].
/// None if cancelled. `keep` events before the end of the transient are returned too.
pub fn settle(
    sys: &System,
    start: State,
    settle: &Settle,
    keep: usize,
    cancelled: &mut dyn FnMut(u64) -> bool,
) -> Option<(Found, Outcome, Vec<Point>, u64)> {
    let map = ImpactMap::new(sys.clone(), settle.solver, start);
    let mut run = OrbitRun::new(map, keep, settle.periodicity);
    let end = settle.transient as i64;
    let (outcome, points) = match run.advance(end, end, cancelled) {
        Advance::Done(o, p) => (o, p),
        Advance::Checkpoint | Advance::Cancelled => return None,
    };
    let found = identify(sys, settle, &outcome, run.state(), cancelled)?;
    Some((found, outcome, points, run.events()))
}

/// What the orbit that ended its transient with `outcome` in `state` settled on. None
/// if cancelled.
pub fn identify(
    sys: &System,
    settle: &Settle,
    outcome: &Outcome,
    state: State,
    cancelled: &mut dyn FnMut(u64) -> bool,
) -> Option<Found> {
    // A cycle of impacts is taken onto the exact cycle by Newton's method (its evidence,
    // and what makes every start that converged to it record the same events; a long
    // cycle's events in mid-cycle are only as close as the orbit times the partial
    // products of its Jacobians).
    let state = match *outcome {
        Outcome::Periodic {
            events, periods, ..
        } => on_exact_cycle(sys, &state, events, periods).unwrap_or(state),
        _ => state,
    };
    let mut map = ImpactMap::new(sys.clone(), settle.solver, state);
    let on_cycle = map.clone();
    let halted = |outcome: &Outcome| match outcome {
        Outcome::NoLanding { .. } => Found {
            kind: Kind::Escaping,
            events: None,
            periods: None,
            point: None,
            spectrum: None,
            signature: Signature::Escaping,
            precision: None,
        },
        Outcome::Resting { phase, .. } => Found {
            kind: Kind::Resting,
            events: None,
            periods: None,
            point: Some((*phase, sys.df(*phase))),
            spectrum: Some(Spectrum::Sticking),
            signature: Signature::Resting,
            precision: None,
        },
        _ => unreachable!("only halts"),
    };
    match *outcome {
        Outcome::Resting { .. } | Outcome::NoLanding { .. } => Some(halted(outcome)),
        Outcome::Periodic {
            events, periods, ..
        } => match cycle_spectrum(&mut map, events, periods) {
            Ok((cycle, spectrum)) => {
                let sticking = cycle.iter().any(|e| e.kind != EventKind::Impact)
                    || spectrum == Spectrum::Sticking;
                let precision = if sticking {
                    precision::sticking_cycle(on_cycle, events)
                } else {
                    Some(Precision::CONTRACTING)
                };
                let cycle = canonical(cycle);
                Some(Found {
                    kind: if sticking {
                        Kind::Sticking
                    } else {
                        Kind::Periodic
                    },
                    events: Some(events),
                    periods: Some(periods),
                    point: cycle.first().map(|e| (e.phase, e.v)),
                    spectrum: Some(if sticking {
                        Spectrum::Sticking
                    } else {
                        spectrum
                    }),
                    signature: Signature::Cycle(cycle),
                    precision,
                })
            }
            // A cycle that halts: rest on the table from where it stopped.
            Err(_) => Some(halted(&Outcome::Resting {
                period: map.state().period,
                phase: map.state().phase,
            })),
        },
        Outcome::Unsettled | Outcome::Running { .. } => {
            // Cells are counted as the sample streams by: memory grows with the cells
            // visited (at most MAX_VISITED_CELLS), never with the sample's length.
            let mut visits = Visits::default();
            let mut last = None;
            let spectrum = qr_spectrum(&mut map, ALIGN, settle.sample, cancelled, &mut |e| {
                visits.add(cell(e.phase, e.v));
                last = Some((e.phase, e.v));
            });
            let spectrum = match spectrum {
                Ok(s) => s,
                Err(Stop::Cancelled) => return None,
                Err(Stop::Halted) => {
                    let st = map.state();
                    return Some(halted(&Outcome::Resting {
                        period: st.period,
                        phase: st.phase,
                    }));
                }
            };
            let kind = match spectrum {
                Spectrum::Sticking => Kind::Sticking,
                s => unsettled_kind(&s),
            };
            Some(Found {
                kind,
                events: None,
                periods: None,
                point: last,
                spectrum: Some(spectrum),
                signature: Signature::Visits(visits.sorted()),
                precision: None,
            })
        }
    }
}

/// The state on the exact (n, k) impact cycle next to `state` (right after an impact):
/// Newton's method on the exact map from it; None if it does not converge to a cycle
/// within 10⁻⁶ of the state (a sticking cycle, or not a cycle).
fn on_exact_cycle(sys: &System, state: &State, n: usize, k: i64) -> Option<State> {
    let cp = crate::orbits::periodic::cycle(sys, n, u32::try_from(k).ok()?, state.phase, state.v)
        .ok()?;
    let close = crate::time::phase_distance(cp.phases[0], state.phase) < 1e-6
        && (cp.velocities[0] - state.v).abs() < 1e-6;
    if !close {
        return None;
    }
    State::launch(sys, state.period, cp.phases[0], cp.velocities[0], 0.0).ok()
}

/// Chaotic, converging or unsettled, from an unsettled orbit's exponents: the largest
/// beyond [`CHAOS_FLOOR`] and three standard errors above zero, below zero, or neither.
fn unsettled_kind(s: &Spectrum) -> Kind {
    match s {
        Spectrum::Finite(e) => {
            let margin = CHAOS_FLOOR.max(3.0 * e.stderr[0]);
            if e.per_impact[0] > margin {
                Kind::Chaotic
            } else if e.per_impact[0] < -margin {
                Kind::Converging
            } else {
                Kind::Unsettled
            }
        }
        _ => Kind::Unsettled,
    }
}

/// The cells an unsettled orbit's sample visits, with their counts (saturating), as
/// the sample streams by. At most [`MAX_VISITED_CELLS`] cells are held: beyond, only
/// the cells already met are counted (an orbit is then identified by the first ones).
#[derive(Default)]
struct Visits(std::collections::HashMap<u64, u32>);

impl Visits {
    fn add(&mut self, cell: u64) {
        let full = self.0.len() >= MAX_VISITED_CELLS;
        match self.0.get_mut(&cell) {
            Some(n) => *n = n.saturating_add(1),
            None if !full => {
                self.0.insert(cell, 1);
            }
            None => {}
        }
    }

    /// (cell, count), sorted by cell.
    fn sorted(self) -> Vec<(u64, u32)> {
        let mut out: Vec<(u64, u32)> = self.0.into_iter().collect();
        out.sort_unstable();
        out
    }
}

/// Rotate a cycle to start at its impact (else event) of smallest phase.
fn canonical(mut cycle: Vec<CycleEvent>) -> Vec<CycleEvent> {
    let key = |e: &CycleEvent| (e.kind != EventKind::Impact, e.phase);
    if let Some(start) = (0..cycle.len()).min_by(|&a, &b| {
        key(&cycle[a])
            .partial_cmp(&key(&cycle[b]))
            .unwrap_or(std::cmp::Ordering::Equal)
    }) {
        cycle.rotate_left(start);
    }
    cycle
}

/// Whether two cycles are one: same length and, for some rotation, every event of the
/// same kind and within [`MATCH`].
fn same_cycle(a: &[CycleEvent], b: &[CycleEvent]) -> bool {
    if a.len() != b.len() || a.is_empty() {
        return false;
    }
    let n = a.len();
    (0..n).any(|rot| {
        (0..n).all(|i| {
            let (x, y) = (&a[i], &b[(i + rot) % n]);
            x.kind == y.kind
                && phase_distance(x.phase, y.phase) <= MATCH
                && (x.v - y.v).abs() <= MATCH
        })
    })
}

/// An attractor found by one or more starts.
#[derive(Clone, Debug, PartialEq)]
pub struct Attractor {
    /// What the attractor is.
    pub kind: Kind,
    /// Events per cycle, for cycles.
    pub events: Option<usize>,
    /// Table periods per cycle, for cycles.
    pub periods: Option<i64>,
    /// A point on it (of the first start that found it).
    pub point: Option<(f64, f64)>,
    /// Its exponents (of the first start that found it).
    pub spectrum: Option<Spectrum>,
    /// For a cycle: whether double precision decides it (of the first start).
    pub precision: Option<Precision>,
    /// The largest exponent per impact: exact for cycles, the mean over its starts for
    /// an unsettled attractor.
    pub lyapunov: Option<f64>,
    /// Starts that ended on it.
    pub starts: usize,
    cycle: Vec<CycleEvent>,
    cells: HashSet<u64>,
    /// The coarse cells of `cells`.
    coarse: HashSet<u64>,
    /// Sum and count of the largest exponents of its unsettled starts.
    exponent_sum: f64,
    exponent_count: usize,
}

impl Attractor {
    /// Its events per cycle as "(n, k)"; None where there is no cycle or where double
    /// precision cannot decide its length ([`Precision::resolved`]).
    pub fn period_label(&self) -> Option<String> {
        self.period().map(|(n, k)| format!("({n}, {k})"))
    }

    /// Its (n, k); None where there is no cycle or where double precision cannot
    /// decide its length.
    pub fn period(&self) -> Option<(usize, i64)> {
        resolved_period(self.events, self.periods, self.precision)
    }

    /// Whether it is a cycle whose length double precision cannot decide.
    pub fn unresolved(&self) -> bool {
        self.precision.is_some_and(|p| !p.resolved)
    }

    /// A cycle's events (phase, v), in order along it; empty for any other attractor.
    pub fn cycle_points(&self) -> Vec<(f64, f64)> {
        self.cycle.iter().map(|e| (e.phase, e.v)).collect()
    }

    /// The points (phase, v) that stand for it: a cycle's events; for an orbit
    /// identified by the cells it visits, the centres of those cells (sorted); for a
    /// resting ball, where it rests; nothing for an escape.
    pub fn points(&self) -> Vec<(f64, f64)> {
        if !self.cycle.is_empty() {
            return self.cycle.iter().map(|e| (e.phase, e.v)).collect();
        }
        if !self.cells.is_empty() {
            let mut cells: Vec<u64> = self.cells.iter().copied().collect();
            cells.sort_unstable();
            return cells.into_iter().map(cell_centre).collect();
        }
        self.point.into_iter().collect()
    }
}

/// A cycle's (n, k) from its `events` and `periods`, None where there is no cycle or
/// where double precision cannot decide its length ([`Precision::resolved`]).
pub fn resolved_period(
    events: Option<usize>,
    periods: Option<i64>,
    precision: Option<Precision>,
) -> Option<(usize, i64)> {
    if precision.is_some_and(|p| !p.resolved) {
        return None;
    }
    Some((events?, periods?))
}

/// The centre (phase, v) of a [`cell`].
pub fn cell_centre(c: u64) -> (f64, f64) {
    let p = (c >> 32) as f64;
    let q = f64::from(c as u32 as i32);
    ((p + 0.5) / CELLS_PER_PERIOD, (q + 0.5) / CELLS_PER_VELOCITY)
}

/// The attractors found so far and how many starts went to each.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Registry {
    attractors: Vec<Attractor>,
    starts: usize,
}

impl Registry {
    /// An empty registry.
    pub fn new() -> Registry {
        Registry::default()
    }

    /// The most a registry of `starts` starts holds, in bytes, each an unsettled orbit
    /// sampled over `sample` events (every start an attractor of its own, with the cells
    /// of its sample and as many coarse cells at most): the bound of a memory estimate.
    pub fn bytes(starts: usize, sample: u64) -> u64 {
        let cells = 2 * sample.min(MAX_VISITED_CELLS as u64) * CELL_BYTES;
        starts as u64 * (std::mem::size_of::<Attractor>() as u64 + cells)
    }

    /// The attractors, in the order they were first found (their ids).
    pub fn attractors(&self) -> &[Attractor] {
        &self.attractors
    }

    /// Starts assigned so far.
    pub fn starts(&self) -> usize {
        self.starts
    }

    /// The share of the assigned starts that went to attractor `id`.
    pub fn fraction(&self, id: usize) -> f64 {
        self.attractors[id].starts as f64 / self.starts.max(1) as f64
    }

    /// The attractor that `found` belongs to (a new one if none matches): its id.
    pub fn assign(&mut self, found: &Found) -> usize {
        self.starts += 1;
        self.place(found, 1)
    }

    /// [`Self::assign`] for an orbit that is not one of the starts counted (a seed: a
    /// point of an attractor found at a neighbouring parameter): the attractor it
    /// belongs to is found or added, with no start counted.
    pub fn seed(&mut self, found: &Found) -> usize {
        self.place(found, 0)
    }

    fn place(&mut self, found: &Found, count: usize) -> usize {
        let id = self.find(found).unwrap_or_else(|| {
            self.attractors.push(Attractor {
                kind: found.kind,
                events: found.events,
                periods: found.periods,
                point: found.point,
                spectrum: found.spectrum,
                precision: found.precision,
                lyapunov: found.lyapunov(),
                starts: 0,
                cycle: match &found.signature {
                    Signature::Cycle(c) => c.clone(),
                    _ => Vec::new(),
                },
                cells: match &found.signature {
                    Signature::Cycle(c) => c.iter().map(|e| cell(e.phase, e.v)).collect(),
                    _ => HashSet::new(),
                },
                coarse: match &found.signature {
                    Signature::Cycle(c) => c.iter().map(|e| coarse(cell(e.phase, e.v))).collect(),
                    _ => HashSet::new(),
                },
                exponent_sum: 0.0,
                exponent_count: 0,
            });
            self.attractors.len() - 1
        });
        let a = &mut self.attractors[id];
        a.starts += count;
        if let Signature::Visits(v) = &found.signature {
            a.cells.extend(v.iter().map(|(c, _)| *c));
            a.coarse.extend(v.iter().map(|(c, _)| coarse(*c)));
            if matches!(a.kind, Kind::Chaotic | Kind::Converging | Kind::Unsettled) {
                if let Some(Spectrum::Finite(e)) = found.spectrum {
                    a.exponent_sum += e.per_impact[0];
                    a.exponent_count += 1;
                    let mean = a.exponent_sum / a.exponent_count as f64;
                    a.lyapunov = Some(mean);
                }
                // The mean over its starts decides between chaotic, converging and
                // unsettled.
                if let Some(Spectrum::Finite(mut e)) = a.spectrum {
                    e.per_impact[0] = a.lyapunov.unwrap_or(e.per_impact[0]);
                    a.kind = unsettled_kind(&Spectrum::Finite(e));
                }
            }
        }
        id
    }

    fn find(&self, found: &Found) -> Option<usize> {
        match &found.signature {
            Signature::Resting => self.attractors.iter().position(|a| a.kind == Kind::Resting),
            Signature::Escaping => self
                .attractors
                .iter()
                .position(|a| a.kind == Kind::Escaping),
            Signature::Cycle(c) => self.attractors.iter().position(|a| {
                a.kind == found.kind
                    && a.events == found.events
                    && a.periods == found.periods
                    && same_cycle(&a.cycle, c)
            }),
            Signature::Visits(v) => {
                let total: u32 = v.iter().map(|(_, n)| n).sum();
                let mut best: Option<(usize, f64)> = None;
                for (id, a) in self.attractors.iter().enumerate() {
                    // An unsettled or converging orbit may be a slow approach to a known
                    // cycle; a sticking orbit whose cycle was not detected (longer than
                    // the detector's reach, or still converging) may be on a known
                    // sticking cycle; a chaotic one only joins its own kinds.
                    let eligible = match a.kind {
                        Kind::Resting | Kind::Escaping => false,
                        Kind::Periodic => matches!(found.kind, Kind::Unsettled | Kind::Converging),
                        Kind::Sticking => found.kind != Kind::Chaotic,
                        Kind::Chaotic | Kind::Converging | Kind::Unsettled => {
                            found.kind != Kind::Sticking
                        }
                    };
                    if !eligible || total == 0 {
                        continue;
                    }
                    // Unsettled orbits among themselves on coarse cells; onto a
                    // cycle on its own cells.
                    let unsettled =
                        |k: Kind| matches!(k, Kind::Chaotic | Kind::Converging | Kind::Unsettled);
                    let on_coarse = unsettled(a.kind) && unsettled(found.kind);
                    let inside: u32 = v
                        .iter()
                        .filter(|(c, _)| {
                            if on_coarse {
                                a.coarse.contains(&coarse(*c))
                            } else {
                                a.cells.contains(c)
                            }
                        })
                        .map(|(_, n)| n)
                        .sum();
                    let share = f64::from(inside) / f64::from(total);
                    if share >= OVERLAP && best.is_none_or(|(_, s)| share > s) {
                        best = Some((id, share));
                    }
                }
                best.map(|(id, _)| id)
            }
        }
    }

    /// The ids ranked for output: largest basin first, then by kind, period and point.
    /// `ranked()[i]` is the id shown as number i + 1.
    pub fn ranked(&self) -> Vec<usize> {
        let mut ids: Vec<usize> = (0..self.attractors.len()).collect();
        ids.sort_by(|&x, &y| {
            let (a, b) = (&self.attractors[x], &self.attractors[y]);
            b.starts
                .cmp(&a.starts)
                .then(a.kind.cmp(&b.kind))
                .then(a.events.cmp(&b.events))
                .then(a.periods.cmp(&b.periods))
                .then(
                    a.point
                        .map(|p| p.0)
                        .partial_cmp(&b.point.map(|p| p.0))
                        .unwrap_or(std::cmp::Ordering::Equal),
                )
        });
        ids
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::run::start::launch;
    use crate::table::Table;

    #[test]
    fn box_starts_cover_the_box() {
        // Every one of 8×8 cells holds one of the first 200 starts (a random set of
        // 200 leaves about 3 of 64 cells empty), and 64 starts reach 50 of them.
        let mut seen = [[false; 8]; 8];
        for s in 0..64 {
            let (t, w) = box_start(s, 2.0);
            seen[(t * 8.0) as usize][(w * 4.0) as usize] = true;
        }
        assert!(seen.iter().flatten().filter(|&&b| b).count() >= 50);
        for s in 0..200 {
            let (t, w) = box_start(s, 2.0);
            assert!((0.0..1.0).contains(&t) && (0.0..2.0).contains(&w));
            seen[(t * 8.0) as usize][(w * 4.0) as usize] = true;
        }
        assert!(seen.iter().flatten().all(|&b| b));
    }

    #[test]
    fn cycles_match_under_rotation_and_not_beyond_the_tolerance() {
        let e = |phase, v| CycleEvent {
            kind: EventKind::Impact,
            phase,
            v,
        };
        let a = vec![e(0.1, 0.5), e(0.7, 0.4)];
        let b = vec![e(0.7 + 1e-9, 0.4), e(0.1, 0.5)];
        assert!(same_cycle(&a, &b));
        let c = vec![e(0.7 + 1e-6, 0.4), e(0.1, 0.5)];
        assert!(!same_cycle(&a, &c));
        // Across the phase origin.
        assert!(same_cycle(&[e(1.0 - 1e-10, 0.5)], &[e(1e-10, 0.5)]));
    }

    #[test]
    fn two_starts_on_the_same_cycle_share_an_attractor() {
        // fd:0.1 at α = 0.45: the stable (1, 1) orbit, reached from different starts.
        let sys = System::new(Table::fd(0.1).unwrap(), 0.45, 0.8).unwrap();
        let mut reg = Registry::new();
        let mut ids = Vec::new();
        for (t0, w0) in [(0.1, 0.45), (0.15, 0.44), (0.2, 0.43)] {
            let start = launch(&sys, t0, w0).unwrap();
            let (found, ..) = settle(&sys, start, &Settle::BASINS, 1, &mut |_| false).unwrap();
            assert_eq!(found.kind, Kind::Periodic, "{found:?}");
            ids.push(reg.assign(&found));
        }
        assert_eq!(ids, vec![0, 0, 0]);
        assert_eq!(reg.fraction(0), 1.0);
    }
}
