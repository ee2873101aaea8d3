//! `bouncemap bench`: measurements on this machine, printed as a table (or json).
//!
//! * Solver throughput: events per second of the exact and the grid solver on the same
//!   orbits (period-1, period-2, irregular sticking beyond double precision, sticking
//!   on F_D; period-1 on the sine; the
//!   median of five alternating rounds per solver), each with its accuracy against an
//!   independent reference: the closed-form (1, 1) fixed point; the (2, 2) cycle solved
//!   by Newton's method on its four defining equations ([`orbits::two_cycle`]);
//!   for the irregular and sticking orbits, one step of each solver from the same exact
//!   states, counting steps that land more than 10⁻⁶ apart (missed or misplaced
//!   impacts).
//! * Sweep timings with the exact solver on all cores: the coarse pass of a Fig. 3
//!   panel, cancel-to-idle latency, and a panel at a reduced transient with the
//!   breakdown of where the events go; `--panel NAME` times a full panel at the paper's
//!   fidelity.
//! * Two-parameter curves: every curve up to period 16 of the F_D (α, D) plane and of
//!   the sine's (α, r) plane (`bouncemap curves` with its default seeds), the median of
//!   three runs each.

use crate::config::flags::{BenchArgs, BenchFormat};
use crate::config::presets::preset;
use crate::config::table_spec::TableSpec;
use crate::config::InputError;
use crate::output::sink::Sink;
use bouncemap_engine::jobs::{available_cores, Control, Executor};
use bouncemap_engine::orbits;
use bouncemap_engine::run::Outcome;
use bouncemap_engine::sweep::{self, SweepJob, SweepSpec};
use bouncemap_engine::table::Shape;
use bouncemap_engine::{Event, EventKind, ImpactMap, State};
use bouncemap_engine::{Solver, System};
use std::io::Write;
use std::time::{Duration, Instant};

/// One orbit on which both solvers are measured.
struct Case {
    name: &'static str,
    table: &'static str,
    alpha: f64,
    r: f64,
    reference: Reference,
}

#[derive(Clone, Copy)]
enum Reference {
    FixedPoint,
    TwoCycle,
    OneStep,
}

const CASES: [Case; 5] = [
    Case {
        name: "period-1",
        table: "fd:0.1",
        alpha: 0.45,
        r: 0.8,
        reference: Reference::FixedPoint,
    },
    Case {
        name: "period-2",
        table: "fd:1",
        alpha: 0.50,
        r: 0.8,
        reference: Reference::TwoCycle,
    },
    // A long stick–release cycle whose length double precision cannot decide: many
    // chattering sequences and irregular flights (not chaos: both exponents are −∞).
    Case {
        name: "irregular",
        table: "fd:0.1",
        alpha: 0.60,
        r: 0.8,
        reference: Reference::OneStep,
    },
    Case {
        name: "sticking",
        table: "quad",
        alpha: 0.70,
        r: 0.5,
        reference: Reference::OneStep,
    },
    Case {
        name: "sine",
        table: "sine",
        alpha: 0.025,
        r: 0.8,
        reference: Reference::FixedPoint,
    },
];

struct SolverRow {
    case: &'static str,
    system: String,
    exact_rate: f64,
    grid_rate: f64,
    exact_err: f64,
    grid_err: f64,
    note: String,
}

pub fn run(args: &BenchArgs) -> anyhow::Result<()> {
    let budget = if args.quick {
        Duration::from_millis(300)
    } else {
        Duration::from_secs(3)
    };
    let panel_full = match &args.panel {
        Some(name) => Some((
            name.clone(),
            preset(name)
                .and_then(|p| p.sweep_spec())
                .map_err(|e| InputError(format!("--panel: {e}")))?,
        )),
        None => None,
    };
    let cores = available_cores();
    let executor = Executor::all_cores()?;
    let mut rows = Vec::new();
    for c in &CASES {
        rows.push(solver_row(c, budget)?);
    }
    let base_spec = preset("fig3b")?.sweep_spec()?;
    let coarse = coarse_time(&base_spec, &executor)?;
    let cancel = cancel_latency(&base_spec, &executor)?;
    let reduced_t = if args.quick { 5_000 } else { 20_000 };
    let mut reduced = base_spec.clone();
    reduced.transient = reduced_t;
    let reduced_run = time_panel(&reduced, &executor)?;
    let full = match &panel_full {
        Some((name, spec)) => Some((name.clone(), time_panel(spec, &executor)?)),
        None => None,
    };
    let curve_runs = if args.quick { 1 } else { 3 };
    let curve_rows = curve_timings(curve_runs)?;
    let date = today();
    let mut out = Sink::stdout();
    let written = (|| -> anyhow::Result<()> {
        match args.format {
            BenchFormat::Text => {
                writeln!(out, "bouncemap bench  ({date}, {cores} cores)")?;
                writeln!(out)?;
                writeln!(
                    out,
                    "{:<9} {:<22} {:>12} {:>12} {:>7} {:>11} {:>11}  note",
                    "orbit", "system", "exact ev/s", "grid ev/s", "ratio", "exact err", "grid err"
                )?;
                for r in &rows {
                    writeln!(
                        out,
                        "{:<9} {:<22} {:>12.0} {:>12.0} {:>7.1} {:>11.1e} {:>11.1e}  {}",
                        r.case,
                        r.system,
                        r.exact_rate,
                        r.grid_rate,
                        r.exact_rate / r.grid_rate,
                        r.exact_err,
                        r.grid_err,
                        r.note
                    )?;
                }
                writeln!(out)?;
                writeln!(
                    out,
                    "targets: exact/grid >= 10 on period-1, >= 4 irregular (chattering, sticking)"
                )?;
                writeln!(out)?;
                writeln!(
                out,
                "sweep fig3b (fd:0.1, alpha 0.45..0.60, 1000 values), exact solver, {cores} cores:"
            )?;
                writeln!(
                    out,
                    "  coarse pass (every value to t = {}):   {:.3} s   (target 1 s)",
                    sweep::DEFAULT_PREVIEW,
                    coarse.as_secs_f64()
                )?;
                writeln!(
                    out,
                    "  cancel to idle:                          {:.1} ms  (target 50 ms)",
                    cancel.as_secs_f64() * 1e3
                )?;
                print_panel(&mut out, &format!("panel at T = {reduced_t}"), &reduced_run)?;
                let est = estimate_full(&reduced_run, reduced_t, sweep::PAPER_TRANSIENT);
                writeln!(out,
                "  estimated full panel at T = 5e6 (unsettled values scale with T): {:.0} s  (target 60 s)",
                est
            )?;
                writeln!(out)?;
                let runs = if curve_runs == 1 {
                    "one run".to_string()
                } else {
                    format!("median of {curve_runs} runs")
                };
                writeln!(out, "two-parameter curves up to period {CURVES_PERIOD} (`curves`, default seeds), {runs}:")?;
                for c in &curve_rows {
                    writeln!(
                        out,
                        "  {:<44} {:>3} curves {:>3} codim-2  {:.3} s  (target: seconds)",
                        c.plane, c.curves, c.codim2, c.median
                    )?;
                }
                if let Some((name, f)) = &full {
                    print_panel(
                        &mut out,
                        &format!("{name} at paper fidelity (T = 5e6, keep 100)"),
                        f,
                    )?;
                }
            }
            BenchFormat::Json => {
                let solver: Vec<_> = rows
                    .iter()
                    .map(|r| {
                        serde_json::json!({
                            "orbit": r.case, "system": r.system,
                            "exact_events_per_s": r.exact_rate, "grid_events_per_s": r.grid_rate,
                            "ratio": r.exact_rate / r.grid_rate,
                            "exact_error": r.exact_err, "grid_error": r.grid_err, "note": r.note,
                        })
                    })
                    .collect();
                let doc = serde_json::json!({
                    "date": date, "cores": cores, "quick": args.quick,
                    "solvers": solver,
                    "coarse_pass_s": coarse.as_secs_f64(),
                    "cancel_ms": cancel.as_secs_f64() * 1e3,
                    "panel_reduced": panel_json(&reduced_run, reduced_t),
                    "panel_full_estimate_s": estimate_full(&reduced_run, reduced_t, sweep::PAPER_TRANSIENT),
                    "curves": curve_rows.iter().map(|c| serde_json::json!({
                        "plane": c.plane, "max_period": CURVES_PERIOD, "curves": c.curves,
                        "codim2": c.codim2, "median_s": c.median,
                    })).collect::<Vec<_>>(),
                    "panel_full": full.as_ref().map(|(n, f)| {
                        let mut j = panel_json(f, sweep::PAPER_TRANSIENT);
                        j["preset"] = serde_json::Value::String(n.clone());
                        j
                    }),
                });
                writeln!(out, "{doc}")?;
            }
        }
        Ok(())
    })();
    out.end(written)
}

/// Doubled branches are followed up to this period in the curves' timing.
const CURVES_PERIOD: usize = 16;

/// The timing of one plane's two-parameter curves.
struct CurveRow {
    plane: &'static str,
    curves: usize,
    codim2: usize,
    median: f64,
}

/// Every curve up to [`CURVES_PERIOD`] of the F_D (α, D) plane and the sine's (α, r)
/// plane, each timed `runs` times (the median).
fn curve_timings(runs: usize) -> Result<Vec<CurveRow>, InputError> {
    use bouncemap_engine::jobs::grid::SweepParam;
    use bouncemap_engine::orbits::curves::{curves, Plane, Seeds};
    let planes = [
        (
            "fd: alpha 0.4..0.7, D 0..1 (r = 0.8)",
            Plane {
                table: bouncemap_engine::Table::fd(1.0)?,
                r: 0.8,
                alpha: (0.4, 0.7),
                second: SweepParam::D,
                window: (0.0, 1.0),
            },
            1.0,
        ),
        (
            "sine: alpha 0.01..0.5, r 0.2..0.95",
            Plane {
                table: bouncemap_engine::Table::sine(),
                r: 0.8,
                alpha: (0.01, 0.5),
                second: SweepParam::R,
                window: (0.2, 0.95),
            },
            0.8,
        ),
    ];
    let mut out = Vec::new();
    for (name, plane, at) in planes {
        let seeds = Seeds::FromFixed {
            k: 1,
            max_period: CURVES_PERIOD,
            at,
            count: crate::config::rules::CURVE_SEEDS.default as usize,
        };
        let mut times = Vec::new();
        let mut found = None;
        for _ in 0..runs.max(1) {
            let t = Instant::now();
            found = Some(curves(&plane, seeds)?);
            times.push(t.elapsed().as_secs_f64());
        }
        times.sort_by(f64::total_cmp);
        let found = found.expect("at least one run");
        out.push(CurveRow {
            plane: name,
            curves: found.curves.len(),
            codim2: found.codim2.len(),
            median: times[times.len() / 2],
        });
    }
    Ok(out)
}

/// Measured run of a whole panel.
struct PanelRun {
    wall: Duration,
    values: usize,
    periodic: usize,
    unsettled: usize,
    sticking: usize,
    resting: usize,
    events_total: u64,
    events_unsettled: u64,
}

fn time_panel(spec: &SweepSpec, executor: &Executor) -> Result<PanelRun, InputError> {
    let t = Instant::now();
    let res = sweep::collect(spec, executor)?;
    let wall = t.elapsed();
    let mut r = PanelRun {
        wall,
        values: res.len(),
        periodic: 0,
        unsettled: 0,
        sticking: 0,
        resting: 0,
        events_total: 0,
        events_unsettled: 0,
    };
    for b in &res {
        r.events_total += b.events;
        match b.outcome {
            Outcome::Periodic { .. } => r.periodic += 1,
            Outcome::Unsettled => {
                r.unsettled += 1;
                r.events_unsettled += b.events;
            }
            Outcome::Resting { .. } => r.resting += 1,
            _ => {}
        }
        r.sticking += usize::from(b.sticking);
    }
    Ok(r)
}

fn print_panel(out: &mut impl Write, title: &str, r: &PanelRun) -> std::io::Result<()> {
    writeln!(
        out,

        "  {title}: {:.2} s  ({} values: {} periodic, {} unsettled, {} sticking, {} resting; {:.3e} events, {:.0}% in unsettled values, {:.2} M events/s)",
        r.wall.as_secs_f64(),
        r.values,
        r.periodic,
        r.unsettled,
        r.sticking,
        r.resting,
        r.events_total as f64,
        100.0 * r.events_unsettled as f64 / (r.events_total.max(1)) as f64,
        r.events_total as f64 / r.wall.as_secs_f64() / 1e6
    )
}

fn panel_json(r: &PanelRun, transient: u64) -> serde_json::Value {
    serde_json::json!({
        "transient": transient, "wall_s": r.wall.as_secs_f64(), "values": r.values,
        "periodic": r.periodic, "unsettled": r.unsettled, "sticking": r.sticking,
        "resting": r.resting, "events": r.events_total, "events_unsettled": r.events_unsettled,
    })
}

/// Full-panel time if the unsettled values' work grows in proportion to T and the
/// rest stays (periodic values stop early).
fn estimate_full(r: &PanelRun, t_small: u64, t_full: u64) -> f64 {
    let frac = r.events_unsettled as f64 / r.events_total.max(1) as f64;
    let w = r.wall.as_secs_f64();
    w * (1.0 - frac) + w * frac * (t_full as f64 / t_small as f64)
}

fn coarse_time(spec: &SweepSpec, executor: &Executor) -> Result<Duration, InputError> {
    let job = SweepJob::new(spec.clone())?.preview(sweep::DEFAULT_PREVIEW);
    let t = Instant::now();
    let h = executor.start(job, &Control::new());
    let mut pass0 = 0;
    let total = h.progress().total;
    let mut at = t.elapsed();
    for b in h.receiver() {
        if b.pass == 0 {
            pass0 += 1;
            if pass0 == total {
                at = t.elapsed();
                h.cancel();
            }
        }
    }
    h.wait();
    Ok(at)
}

fn cancel_latency(spec: &SweepSpec, executor: &Executor) -> Result<Duration, InputError> {
    let h = sweep::start(spec.clone(), executor, &Control::new())?;
    std::thread::sleep(Duration::from_millis(500));
    let t = Instant::now();
    h.cancel();
    while !h.is_finished() {
        std::thread::sleep(Duration::from_micros(200));
    }
    let d = t.elapsed();
    h.wait();
    Ok(d)
}

fn system_of(c: &Case) -> Result<System, InputError> {
    let table = TableSpec::parse(c.table).map_err(InputError)?.load()?;
    Ok(System::new(table, c.alpha, c.r)?)
}

fn start_state(sys: &System) -> State {
    State::start(sys, 0.0, None, 0.0).expect("default start is valid")
}

/// One solver's map, timed in rounds.
struct Timed {
    sys: System,
    solver: Solver,
    map: ImpactMap,
    /// The last four events, oldest first once full (a ring: no per-event shuffling).
    last: [Option<Event>; 4],
    next: usize,
    rates: Vec<f64>,
}

impl Timed {
    fn new(sys: &System, solver: Solver) -> Timed {
        let mut map = ImpactMap::new(sys.clone(), solver, start_state(sys));
        for _ in 0..5_000 {
            if map.step().is_err() {
                break;
            }
        }
        Timed {
            sys: sys.clone(),
            solver,
            map,
            last: [None; 4],
            next: 0,
            rates: Vec::new(),
        }
    }

    /// Step for `budget`, in blocks of 1000 events, and record the rate.
    fn round(&mut self, budget: Duration) {
        let t = Instant::now();
        let mut n = 0u64;
        while t.elapsed() < budget {
            for _ in 0..1000 {
                match self.map.step() {
                    Ok(e) => {
                        self.last[self.next] = Some(e);
                        self.next = (self.next + 1) % 4;
                    }
                    Err(_) => {
                        let start = start_state(&self.sys);
                        self.map = ImpactMap::new(self.sys.clone(), self.solver, start);
                    }
                }
            }
            n += 1000;
        }
        self.rates.push(n as f64 / t.elapsed().as_secs_f64());
    }

    /// The median rate over the rounds, and the last events.
    fn result(mut self) -> (f64, Vec<Event>) {
        self.rates.sort_by(f64::total_cmp);
        let median = self.rates[self.rates.len() / 2];
        let last = (0..4)
            .filter_map(|k| self.last[(self.next + k) % 4])
            .collect();
        (median, last)
    }
}

/// Events per second of the exact and the grid solver on the case's orbit (the median
/// of five rounds, the two solvers alternating so a drift of the machine's speed
/// affects both alike), and each settled orbit's last events.
fn rates(sys: &System, budget: Duration) -> ((f64, Vec<Event>), (f64, Vec<Event>)) {
    const ROUNDS: u32 = 5;
    let mut exact = Timed::new(sys, Solver::Exact);
    let mut grid = Timed::new(sys, Solver::Grid);
    for _ in 0..ROUNDS {
        exact.round(budget / ROUNDS);
        grid.round(budget / ROUNDS);
    }
    (exact.result(), grid.result())
}

fn solver_row(c: &Case, budget: Duration) -> Result<SolverRow, InputError> {
    let sys = system_of(c)?;
    let ((er, elast), (gr, glast)) = rates(&sys, budget);
    let (ee, ge, note) = match c.reference {
        Reference::FixedPoint => {
            let t = fixed_point_phase(&sys);
            let err = |l: &[Event]| {
                l.iter()
                    .map(|e| (e.phase - t).abs().max((e.v - 0.5).abs()))
                    .fold(0.0, f64::max)
            };
            (
                err(&elast),
                err(&glast),
                format!("max |error| vs closed-form t* = {t:.12}, v* = 1/2"),
            )
        }
        Reference::TwoCycle => {
            let reference = orbits::two_cycle(&sys, 1)
                .ok()
                .map(|tc| (tc.phase0, tc.phase1, tc.v0, tc.v1));
            let err = |l: &[Event]| match reference {
                Some((t0, t1, v0, v1)) => l
                    .iter()
                    .map(|e| {
                        let a = (e.phase - t0).abs().max((e.v - v0).abs());
                        let b = (e.phase - t1).abs().max((e.v - v1).abs());
                        a.min(b)
                    })
                    .fold(0.0, f64::max),
                None => f64::NAN,
            };
            (
                err(&elast),
                err(&glast),
                "max |error| vs Newton solution of the (2,2) equations".into(),
            )
        }
        Reference::OneStep => {
            let (max_diff, bad, steps) = one_step_comparison(&sys, 20_000);
            (
                0.0,
                max_diff,
                format!(
                    "grid vs exact from the same {steps} states: {bad} steps land > 1e-6 apart"
                ),
            )
        }
    };
    Ok(SolverRow {
        case: c.name,
        system: format!("{} a={} r={}", c.table, c.alpha, c.r),
        exact_rate: er,
        grid_rate: gr,
        exact_err: ee,
        grid_err: ge,
        note,
    })
}

/// The stable (1, 1) fixed point's phase in closed form, where
/// f'(t*) = ½ (1 − r)/(1 + r) and f''(t*) < 0: on F_D the smaller root of
/// α(3D t² − (2 + D) t + ½) = ½ (1 − r)/(1 + r) on the first piece; on the sine
/// 2πα cos 2πt* = ½ (1 − r)/(1 + r) with sin 2πt* > 0.
fn fixed_point_phase(sys: &System) -> f64 {
    let a = sys.alpha();
    let target = 0.5 * (1.0 - sys.r()) / (1.0 + sys.r());
    if matches!(sys.table().shape(), Shape::Sine) {
        let tau = 2.0 * std::f64::consts::PI;
        return (target / (tau * a)).acos() / tau;
    }
    let d = sys.table().d().unwrap_or(0.0);
    let (qa, qb, qc) = (3.0 * d * a, -(2.0 + d) * a, 0.5 * a - target);
    if qa == 0.0 {
        -qc / qb
    } else {
        (-qb - (qb * qb - 4.0 * qa * qc).sqrt()) / (2.0 * qa)
    }
}

/// From each of `n` consecutive states of the exact orbit, one step of each solver:
/// (largest landing time difference, steps landing > 1e-6 apart, steps compared).
fn one_step_comparison(sys: &System, n: usize) -> (f64, usize, usize) {
    let mut exact = ImpactMap::new(sys.clone(), Solver::Exact, start_state(sys));
    for _ in 0..5_000 {
        if exact.step().is_err() {
            return (f64::NAN, 0, 0);
        }
    }
    let (mut max_diff, mut bad, mut compared) = (0.0f64, 0usize, 0usize);
    for _ in 0..n {
        let s = *exact.state();
        let Ok(e) = exact.step() else { break };
        // Compare flights only: the grid solver has no sticking of its own.
        if s.mode() != bouncemap_engine::Mode::Flying || e.kind != EventKind::Impact {
            continue;
        }
        let mut grid = ImpactMap::new(sys.clone(), Solver::Grid, s);
        let Ok(g) = grid.step() else {
            bad += 1;
            continue;
        };
        compared += 1;
        let d = (g.period - e.period) as f64 + (g.phase - e.phase);
        max_diff = max_diff.max(d.abs());
        if d.abs() > 1e-6 {
            bad += 1;
        }
    }
    (max_diff, bad, compared)
}

/// Today's date (UTC) as YYYY-MM-DD.
fn today() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs()) as i64;
    let days = secs.div_euclid(86_400);
    // Civil from days (Howard Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!("{y:04}-{m:02}-{d:02}")
}

#[cfg(test)]
mod tests {
    use super::*;
    use bouncemap_engine::Table;

    #[test]
    fn fixed_point_phase_satisfies_the_defining_equation() {
        let sys = System::new(Table::fd(0.1).unwrap(), 0.45, 0.8).unwrap();
        let t = fixed_point_phase(&sys);
        assert!((sys.df(t) - 0.5 * 0.2 / 1.8).abs() < 1e-14);
        assert!(sys.jet(t)[2] < 0.0 && t < 0.5);
        let sys = System::new(Table::sine(), 0.025, 0.8).unwrap();
        let t = fixed_point_phase(&sys);
        assert!((sys.df(t) - 0.5 * 0.2 / 1.8).abs() < 1e-14);
        assert!(sys.jet(t)[2] < 0.0);
        // The exact map returns to it after one period.
        let st = State::launch(&sys, 0, t, 0.5, 0.0).unwrap();
        let e = ImpactMap::new(sys, Solver::Exact, st).step().unwrap();
        assert_eq!(e.period, 1);
        assert!((e.phase - t).abs() < 1e-13 && (e.v - 0.5).abs() < 1e-13);
    }

    #[test]
    fn two_cycle_reference_is_a_genuine_cycle_of_the_map() {
        // fd:1, α = 0.5 (past α_PD ≈ 0.4838): the reference the period-2 row uses must be
        // a genuine 2-cycle, which the exact map then reproduces.
        let sys = System::new(Table::fd(1.0).unwrap(), 0.5, 0.8).unwrap();
        let tc = orbits::two_cycle(&sys, 1).unwrap();
        let (t0, t1, v0, v1) = (tc.phase0, tc.phase1, tc.v0, tc.v1);
        assert!((t1 - t0).abs() > 1e-3, "collapsed onto the fixed point");
        let st = State::launch(&sys, 0, t0, v0, 0.0).unwrap();
        let e = ImpactMap::new(sys, Solver::Exact, st).step().unwrap();
        assert!((e.phase - t1).abs() < 1e-12 && (e.v - v1).abs() < 1e-12);
    }

    #[test]
    fn today_is_a_date() {
        let d = today();
        assert_eq!(d.len(), 10);
        assert!(d.starts_with("20"));
    }

    #[test]
    fn cases_use_valid_tables() {
        for c in &CASES {
            system_of(c).unwrap();
        }
        assert!(Table::fd(0.1).is_ok());
    }
}
