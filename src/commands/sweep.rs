//! `bouncemap sweep`: a bifurcation diagram computed headless, written as csv, json or
//! braille text; presets for the paper's Fig. 3 panels; `--shard I/N` parts.
//!
//! csv: one row per recorded point, values in index order:
//! `index,<param>,phase,v,kind,period,table_periods,status,sticking` where `<param>` is
//! `alpha`, `r` or `d`, `period` is the detected cycle length in events (empty when no
//! cycle was detected), `table_periods` the table periods per cycle, `status` one of
//! periodic | unsettled | resting | no-landing and `sticking` whether the value's points
//! include a stick or a release. A value without any point still gets one row, with
//! empty phase, v and kind.

use crate::cli::{parse_f64, InitialArgs, SolverArg};
use crate::engine::sweep::{
    self, Outcome, Periodicity, Shard, SweepBatch, SweepParam, SweepSpec, PAPER_KEEP,
    PAPER_TRANSIENT,
};
use crate::engine::system::{check_alpha, check_r};
use crate::engine::Table;
use crate::input::{load_table, InputError};
use crate::output::{csv_row, json_num};
use clap::{Args, ValueEnum};
use serde::Deserialize;
use std::io::{self, BufWriter, IsTerminal, Write};
use std::sync::atomic::AtomicU64;
use std::sync::Arc;
use std::time::Duration;

/// Output format of `sweep`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Default)]
pub enum SweepFormat {
    /// One row per recorded point.
    #[default]
    Csv,
    /// One object per value with its points.
    Json,
    /// The diagram as braille text.
    Braille,
}

/// The swept parameter on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ParamArg {
    Alpha,
    R,
    D,
}

/// `bouncemap sweep`.
#[derive(Args, Debug, Clone)]
#[command(allow_negative_numbers = true)]
pub struct SweepArgs {
    /// Load settings from a preset (fig3a … fig3f); other flags override them.
    #[arg(long, value_name = "NAME")]
    pub preset: Option<String>,
    /// Table shape: sine, quad, cubic, fd:D or PATH.toml [default: fd:0.1].
    #[arg(long, value_name = "TABLE")]
    pub table: Option<String>,
    /// Amplitude α: a number, or the swept window LO..HI [default: 0.45].
    #[arg(long, value_name = "A|LO..HI")]
    pub alpha: Option<String>,
    /// Restitution r: a number, or the swept window LO..HI [default: 0.8].
    #[arg(long, value_name = "R|LO..HI")]
    pub r: Option<String>,
    /// D of the fd:D table: a number, or the swept window LO..HI.
    #[arg(long, value_name = "D|LO..HI")]
    pub d: Option<String>,
    /// The swept parameter [default: the one given as a window].
    #[arg(long, value_enum)]
    pub param: Option<ParamArg>,
    /// Number of parameter values [default: 1000].
    #[arg(long, value_parser = parse_steps, value_name = "N")]
    pub steps: Option<usize>,
    /// End of the transient T in table periods; points are the last events before T
    /// [default: 5000000, the paper's].
    #[arg(long, value_parser = parse_transient, value_name = "PERIODS")]
    pub transient: Option<u64>,
    /// Events recorded per value [default: 100].
    #[arg(long, value_parser = parse_keep, value_name = "M")]
    pub keep: Option<usize>,
    #[command(flatten)]
    pub initial: InitialArgs,
    /// Next-impact solver [default: exact].
    #[arg(long, value_enum)]
    pub solver: Option<SolverArg>,
    /// Warm start: each value starts from its neighbour's final state.
    #[arg(long)]
    pub warm: bool,
    /// Start each value slightly off its (1,1) fixed point (phase t* + 0.001, v = 1/2),
    /// as the paper does, instead of --t0/--v0/--z0 (presets do this).
    #[arg(long)]
    pub near_fixed_point: bool,
    /// Run every value to the full transient (no periodicity early stop).
    #[arg(long)]
    pub no_early_stop: bool,
    /// Longest cycle (in events) the early stop detects.
    #[arg(long, default_value_t = 64, value_parser = parse_max_period, value_name = "P")]
    pub max_period: usize,
    /// Agreement in phase and velocity promised by the early stop.
    #[arg(long, default_value_t = 1e-11, value_parser = parse_tolerance, value_name = "TOL")]
    pub tolerance: f64,
    /// Output format.
    #[arg(long, value_enum, default_value_t = SweepFormat::Csv)]
    pub format: SweepFormat,
    /// Write to FILE instead of stdout.
    #[arg(long, value_name = "FILE")]
    pub out: Option<String>,
    /// Compute only the I-th of N interleaved parts (1 ≤ I ≤ N); join them with `merge`.
    #[arg(long, value_parser = parse_shard, value_name = "I/N")]
    pub shard: Option<Shard>,
    /// Braille width in characters [default: the terminal's].
    #[arg(long, value_parser = parse_cells, value_name = "COLS")]
    pub width: Option<u16>,
    /// Braille height in lines [default: the terminal's].
    #[arg(long, value_parser = parse_cells, value_name = "LINES")]
    pub height: Option<u16>,
    /// Worker threads [default: all cores].
    #[arg(long, value_parser = parse_threads, value_name = "N")]
    pub threads: Option<usize>,
}

/// A preset file in `assets/presets/`.
#[derive(Deserialize, Debug, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Preset {
    /// What the preset shows.
    pub description: String,
    pub table: String,
    pub param: String,
    /// The swept window [lo, hi].
    pub window: [f64; 2],
    pub alpha: Option<f64>,
    pub r: Option<f64>,
    pub steps: usize,
    pub transient: u64,
    pub keep: usize,
    /// `near-fixed-point` (the paper's start) or `state` (t0, v0, z0).
    pub start: Option<String>,
}

/// The presets shipped with the binary: (name, file text).
pub const PRESETS: [(&str, &str); 6] = [
    ("fig3a", include_str!("../../assets/presets/fig3a.toml")),
    ("fig3b", include_str!("../../assets/presets/fig3b.toml")),
    ("fig3c", include_str!("../../assets/presets/fig3c.toml")),
    ("fig3d", include_str!("../../assets/presets/fig3d.toml")),
    ("fig3e", include_str!("../../assets/presets/fig3e.toml")),
    ("fig3f", include_str!("../../assets/presets/fig3f.toml")),
];

/// Parse the preset called `name`.
pub fn preset(name: &str) -> Result<Preset, InputError> {
    let names: Vec<&str> = PRESETS.iter().map(|p| p.0).collect();
    let text = PRESETS
        .iter()
        .find(|p| p.0 == name)
        .map(|p| p.1)
        .ok_or_else(|| {
            InputError(format!(
                "--preset: unknown preset '{name}': valid {}",
                names.join(", ")
            ))
        })?;
    toml::from_str(text).map_err(|e| {
        InputError(format!(
            "--preset {name}: {}",
            e.to_string().replace('\n', " ")
        ))
    })
}

/// A number or a window LO..HI.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Setting {
    Fixed(f64),
    Window(f64, f64),
}

fn parse_setting(flag: &str, s: &str) -> Result<Setting, InputError> {
    if let Some((a, b)) = s.split_once("..") {
        let lo = parse_f64(a).map_err(|e| InputError(format!("--{flag} {s}: {e}")))?;
        let hi = parse_f64(b).map_err(|e| InputError(format!("--{flag} {s}: {e}")))?;
        if lo > hi {
            return Err(InputError(format!(
                "--{flag} {s}: the window is empty: valid LO..HI with LO ≤ HI"
            )));
        }
        Ok(Setting::Window(lo, hi))
    } else {
        let x = parse_f64(s).map_err(|e| {
            InputError(format!(
                "--{flag} {s}: {e}: valid a number or a window LO..HI"
            ))
        })?;
        Ok(Setting::Fixed(x))
    }
}

fn check_value(flag: &str, x: f64) -> Result<(), InputError> {
    let ok = match flag {
        "alpha" => check_alpha(x).is_ok(),
        "r" => check_r(x).is_ok(),
        _ => (0.0..=1.0).contains(&x),
    };
    if ok {
        Ok(())
    } else {
        let range = match flag {
            "alpha" => "(0, 1000]",
            "r" => "(0, 1)",
            _ => "[0, 1]",
        };
        Err(InputError(format!(
            "--{flag} {x} is out of range: valid {range}"
        )))
    }
}

/// Turn the flags (and the preset) into a sweep specification.
pub fn spec_from(args: &SweepArgs) -> Result<SweepSpec, InputError> {
    let p = match &args.preset {
        Some(name) => Some(preset(name)?),
        None => None,
    };
    let pr = p.as_ref();
    let mut alpha = args.alpha.clone();
    let mut r = args.r.clone();
    let d = args.d.clone();
    let mut param = args.param;
    if let Some(p) = pr {
        let w = format!("{}..{}", p.window[0], p.window[1]);
        let pparam = match p.param.as_str() {
            "alpha" => ParamArg::Alpha,
            "r" => ParamArg::R,
            _ => ParamArg::D,
        };
        param = param.or(Some(pparam));
        match pparam {
            ParamArg::Alpha => alpha = alpha.or(Some(w)),
            ParamArg::R => r = r.or(Some(w)),
            ParamArg::D => {}
        }
        alpha = alpha.or(p.alpha.map(|x| x.to_string()));
        r = r.or(p.r.map(|x| x.to_string()));
    }
    let settings = [
        ("alpha", alpha.as_deref()),
        ("r", r.as_deref()),
        ("d", d.as_deref()),
    ]
    .map(|(f, s)| (f, s.map(|s| parse_setting(f, s)).transpose()));
    let mut parsed = Vec::new();
    for (f, s) in settings {
        parsed.push((f, s?));
    }
    let windows: Vec<&str> = parsed
        .iter()
        .filter(|(_, s)| matches!(s, Some(Setting::Window(..))))
        .map(|(f, _)| *f)
        .collect();
    let param = match param {
        Some(p) => p,
        None => match windows.as_slice() {
            [one] => match *one {
                "alpha" => ParamArg::Alpha,
                "r" => ParamArg::R,
                _ => ParamArg::D,
            },
            [] => {
                return Err(InputError(
                    "sweep: no window given: give the swept parameter as LO..HI, e.g. --alpha 0.45..0.6"
                        .into(),
                ))
            }
            _ => {
                return Err(InputError(format!(
                    "sweep: windows given for {}: valid a window for exactly one of --alpha, --r, --d",
                    windows.join(" and ")
                )))
            }
        },
    };
    let pname = match param {
        ParamArg::Alpha => "alpha",
        ParamArg::R => "r",
        ParamArg::D => "d",
    };
    let mut window = None;
    let mut fixed = |f: &str, default: Option<f64>| -> Result<Option<f64>, InputError> {
        let s = parsed.iter().find(|(g, _)| *g == f).and_then(|(_, s)| *s);
        match s {
            Some(Setting::Window(lo, hi)) if f == pname => {
                check_value(f, lo)?;
                check_value(f, hi)?;
                window = Some((lo, hi));
                Ok(None)
            }
            Some(Setting::Window(lo, hi)) => Err(InputError(format!(
                "--{f} {lo}..{hi}: only the swept parameter ({pname}) takes a window: valid a number"
            ))),
            None if f == pname => Err(InputError(format!(
                "--{f}: the swept parameter needs a window: valid LO..HI, e.g. --{f} 0.4..0.6"
            ))),
            Some(Setting::Fixed(x)) if f == pname => Err(InputError(format!(
                "--{f} {x}: the swept parameter needs a window: valid LO..HI"
            ))),
            Some(Setting::Fixed(x)) => {
                check_value(f, x)?;
                Ok(Some(x))
            }
            None => Ok(default),
        }
    };
    let alpha_v = fixed("alpha", Some(0.45))?;
    let r_v = fixed("r", Some(0.8))?;
    let d_v = fixed("d", None)?;
    let (lo, hi) = window.expect("the swept parameter's window was checked");
    let table_arg = args.table.clone().or(pr.map(|p| p.table.clone()));
    let table =
        match (param, &table_arg, d_v) {
            (ParamArg::D, Some(t), _) => {
                let t = load_table(t)?;
                if t.d().is_none() {
                    return Err(InputError(format!(
                        "--table {}: sweeping D needs an fd:D table: valid fd:D, quad or cubic",
                        t.name()
                    )));
                }
                t
            }
            (ParamArg::D, None, _) => Table::fd(lo)?,
            (_, Some(_), Some(_)) => return Err(InputError(
                "--d: give either --table or --d, not both: valid --d D alone means --table fd:D"
                    .into(),
            )),
            (_, None, Some(dv)) => Table::fd(dv)?,
            (_, Some(t), None) => load_table(t)?,
            (_, None, None) => Table::fd(0.1)?,
        };
    let sp = match param {
        ParamArg::Alpha => SweepParam::Alpha,
        ParamArg::R => SweepParam::R,
        ParamArg::D => SweepParam::D,
    };
    let mut spec = SweepSpec::new(
        table,
        sp,
        lo,
        hi,
        args.steps.or(pr.map(|p| p.steps)).unwrap_or(1000),
    );
    spec.alpha = alpha_v.unwrap_or(0.45);
    spec.r = r_v.unwrap_or(0.8);
    spec.initial = sweep::InitialSpec {
        t0: args.initial.t0,
        v0: args.initial.v0,
        z0: args.initial.z0,
        near_fixed_point: args.near_fixed_point
            || pr.is_some_and(|p| p.start.as_deref() == Some("near-fixed-point")),
    };
    spec.transient = args
        .transient
        .or(pr.map(|p| p.transient))
        .unwrap_or(PAPER_TRANSIENT);
    spec.keep = args.keep.or(pr.map(|p| p.keep)).unwrap_or(PAPER_KEEP);
    spec.solver = args.solver.unwrap_or_default().into();
    spec.warm_start = args.warm;
    spec.periodicity = (!args.no_early_stop).then_some(Periodicity {
        max_period: args.max_period,
        tolerance: args.tolerance,
    });
    spec.preview = 0;
    spec.shard = args.shard.unwrap_or(Shard::WHOLE);
    spec.threads = args.threads;
    spec.validate()
        .map_err(|e| InputError(format!("sweep: {e}")))?;
    Ok(spec)
}

pub fn run(args: &SweepArgs) -> anyhow::Result<()> {
    let spec = spec_from(args)?;
    let size = braille_size(args);
    let mut out: Box<dyn Write> = match &args.out {
        Some(path) => Box::new(BufWriter::new(
            std::fs::File::create(path)
                .map_err(|e| InputError(format!("--out: cannot create {path}: {e}")))?,
        )),
        None => Box::new(BufWriter::new(io::stdout().lock())),
    };
    let results = compute(&spec)?;
    match args.format {
        SweepFormat::Csv => write_csv(&mut out, &spec, &results)?,
        SweepFormat::Json => write_json(&mut out, &spec, &results)?,
        SweepFormat::Braille => {
            for line in braille_diagram(&spec, &results, size.0, size.1) {
                writeln!(out, "{line}")?;
            }
        }
    }
    out.flush()?;
    Ok(())
}

/// Run the sweep, drawing a progress bar on stderr when it is a terminal.
fn compute(spec: &SweepSpec) -> anyhow::Result<Vec<SweepBatch>> {
    let show = io::stderr().is_terminal();
    let handle = sweep::start(spec.clone(), Arc::new(AtomicU64::new(0)))
        .map_err(|e| InputError(format!("sweep: {e}")))?;
    let mut results = Vec::new();
    loop {
        match handle.receiver().recv_timeout(Duration::from_millis(200)) {
            Ok(b) => {
                if b.complete {
                    results.push(b);
                }
            }
            Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {}
            Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => break,
        }
        if show {
            let p = handle.progress();
            let width = 30;
            let filled = (p.fraction() * width as f64) as usize;
            eprint!(
                "\r\x1b[2Ksweep [{}{}] {}/{} values  {:.2} M events/s  {:.0} s",
                "#".repeat(filled),
                "-".repeat(width - filled),
                p.values_done,
                p.values_total,
                p.events_per_second() / 1e6,
                p.elapsed.as_secs_f64()
            );
        }
    }
    if show {
        eprint!("\r\x1b[2K");
    }
    handle.wait();
    results.sort_by_key(|b| b.index);
    Ok(results)
}

fn period_fields(o: &Outcome) -> (String, String) {
    match o {
        Outcome::Periodic {
            events, periods, ..
        } => (events.to_string(), periods.to_string()),
        _ => (String::new(), String::new()),
    }
}

/// The csv header for a sweep of `param`.
pub fn csv_header(param: SweepParam) -> Vec<String> {
    [
        "index",
        param.as_str(),
        "phase",
        "v",
        "kind",
        "period",
        "table_periods",
        "status",
        "sticking",
    ]
    .map(String::from)
    .to_vec()
}

fn write_csv<W: Write>(out: &mut W, spec: &SweepSpec, results: &[SweepBatch]) -> io::Result<()> {
    csv_row(out, &csv_header(spec.param))?;
    for b in results {
        let (per, k) = period_fields(&b.outcome);
        let head = [b.index.to_string(), b.value.to_string()];
        let tail = [
            per,
            k,
            b.outcome.as_str().to_string(),
            b.sticking.to_string(),
        ];
        let rows: Vec<[String; 3]> = if b.points.is_empty() {
            vec![[String::new(), String::new(), String::new()]]
        } else {
            b.points
                .iter()
                .map(|p| {
                    [
                        p.phase.to_string(),
                        p.v.to_string(),
                        p.kind.as_str().to_string(),
                    ]
                })
                .collect()
        };
        for mid in rows {
            let fields: Vec<String> = head
                .iter()
                .chain(mid.iter())
                .chain(tail.iter())
                .cloned()
                .collect();
            csv_row(out, &fields)?;
        }
    }
    Ok(())
}

/// The json document's header fields (everything but the values).
pub fn json_header(spec: &SweepSpec) -> serde_json::Map<String, serde_json::Value> {
    use serde_json::Value;
    let mut m = serde_json::Map::new();
    m.insert("table".into(), Value::String(spec.table.name().into()));
    m.insert("param".into(), Value::String(spec.param.as_str().into()));
    m.insert("lo".into(), json_num(spec.lo));
    m.insert("hi".into(), json_num(spec.hi));
    m.insert("steps".into(), spec.steps.into());
    let fixed = |p: SweepParam, x: f64| {
        if spec.param == p {
            Value::Null
        } else {
            json_num(x)
        }
    };
    m.insert("alpha".into(), fixed(SweepParam::Alpha, spec.alpha));
    m.insert("r".into(), fixed(SweepParam::R, spec.r));
    m.insert(
        "d".into(),
        match (spec.param, spec.table.d()) {
            (SweepParam::D, _) | (_, None) => Value::Null,
            (_, Some(d)) => json_num(d),
        },
    );
    m.insert("transient".into(), spec.transient.into());
    m.insert("keep".into(), spec.keep.into());
    m.insert(
        "solver".into(),
        Value::String(
            if spec.solver == crate::engine::Solver::Exact {
                "exact"
            } else {
                "grid"
            }
            .into(),
        ),
    );
    m.insert(
        "start".into(),
        Value::String(if spec.warm_start { "warm" } else { "cold" }.into()),
    );
    m.insert(
        "initial".into(),
        if spec.initial.near_fixed_point {
            Value::String("near-fixed-point".into())
        } else {
            serde_json::json!({"t0": json_num(spec.initial.t0), "v0": spec.initial.v0.map(json_num), "z0": json_num(spec.initial.z0)})
        },
    );
    m.insert(
        "early_stop".into(),
        match spec.periodicity {
            Some(p) => {
                serde_json::json!({"max_period": p.max_period, "tolerance": json_num(p.tolerance)})
            }
            None => Value::Null,
        },
    );
    m.insert(
        "shard".into(),
        if spec.shard == Shard::WHOLE {
            Value::Null
        } else {
            Value::String(format!("{}/{}", spec.shard.index + 1, spec.shard.count))
        },
    );
    m
}

/// One value as a json object.
pub fn json_value(b: &SweepBatch) -> serde_json::Value {
    let (period, k, stopped) = match b.outcome {
        Outcome::Periodic {
            events,
            periods,
            stopped_at,
        } => (events.into(), periods.into(), stopped_at.into()),
        _ => (
            serde_json::Value::Null,
            serde_json::Value::Null,
            serde_json::Value::Null,
        ),
    };
    let points: Vec<serde_json::Value> = b
        .points
        .iter()
        .map(|p| serde_json::json!({"phase": json_num(p.phase), "v": json_num(p.v), "kind": p.kind.as_str()}))
        .collect();
    serde_json::json!({
        "index": b.index,
        "value": json_num(b.value),
        "status": b.outcome.as_str(),
        "period": period,
        "table_periods": k,
        "stopped_at": stopped,
        "sticking": b.sticking,
        "events": b.events,
        "points": points,
    })
}

/// Write a json document from its header and its values (in index order).
pub fn write_json_doc<W: Write>(
    out: &mut W,
    mut header: serde_json::Map<String, serde_json::Value>,
    values: Vec<serde_json::Value>,
) -> io::Result<()> {
    header.insert("values".into(), serde_json::Value::Array(values));
    serde_json::to_writer(&mut *out, &serde_json::Value::Object(header))?;
    writeln!(out)
}

fn write_json<W: Write>(out: &mut W, spec: &SweepSpec, results: &[SweepBatch]) -> io::Result<()> {
    write_json_doc(
        out,
        json_header(spec),
        results.iter().map(json_value).collect(),
    )
}

fn braille_size(args: &SweepArgs) -> (u16, u16) {
    let term = crossterm::terminal::size().ok();
    let w = args
        .width
        .or(term.map(|t| t.0))
        .or_else(|| std::env::var("COLUMNS").ok().and_then(|c| c.parse().ok()))
        .unwrap_or(100);
    let h = args
        .height
        .or(term.map(|t| t.1.saturating_sub(2)))
        .unwrap_or(30);
    (w.max(20), h.max(6))
}

/// The diagram as braille text `width` characters wide and `height` lines high,
/// phase t̂ ∈ [0, 1) upwards against the swept parameter, with axis labels and a line
/// marking columns that contain sticking (s) or resting (r) values.
pub fn braille_diagram(
    spec: &SweepSpec,
    results: &[SweepBatch],
    width: u16,
    height: u16,
) -> Vec<String> {
    const GUTTER: usize = 6;
    let cols = (width as usize).saturating_sub(GUTTER).max(4);
    let rows = (height as usize).saturating_sub(4).max(2);
    let mut cells = vec![0u8; cols * rows];
    let mut marks = vec![' '; cols];
    let (dw, dh) = (2 * cols, 4 * rows);
    let span = spec.hi - spec.lo;
    for b in results {
        let x = if span > 0.0 {
            (((b.value - spec.lo) / span) * (dw - 1) as f64).round() as usize
        } else {
            dw / 2
        }
        .min(dw - 1);
        for p in &b.points {
            let y = (((1.0 - p.phase) * dh as f64) as usize).min(dh - 1);
            cells[(y / 4) * cols + x / 2] |= braille_bit(x % 2, y % 4);
        }
        let m = &mut marks[x / 2];
        if matches!(b.outcome, Outcome::Resting { .. }) {
            *m = 'r';
        } else if b.sticking && *m != 'r' {
            *m = 's';
        }
    }
    let mut lines = vec![format!(
        "{}  {} = {}..{}  {}  T = {}  keep {}  {} start",
        spec.table.name(),
        spec.param.as_str(),
        spec.lo,
        spec.hi,
        fixed_params(spec),
        spec.transient,
        spec.keep,
        if spec.warm_start { "warm" } else { "cold" },
    )];
    if spec.initial.near_fixed_point {
        lines[0].push_str(", near (1,1)");
    }
    for row in 0..rows {
        let label = if row == 0 {
            "1.0 ┤".to_string()
        } else if row == rows / 2 {
            "0.5 ┤".to_string()
        } else if row + 1 == rows {
            "0.0 ┤".to_string()
        } else {
            "    │".to_string()
        };
        let glyphs: String = cells[row * cols..(row + 1) * cols]
            .iter()
            .map(|&b| char::from_u32(0x2800 + b as u32).unwrap_or(' '))
            .collect();
        lines.push(format!("{label:>GUTTER$}{glyphs}", label = label));
    }
    lines.push(format!("{:>GUTTER$}{}", "└", "─".repeat(cols)));
    let lo = format!("{}", spec.lo);
    let hi = format!("{}", spec.hi);
    let name = spec.param.as_str();
    let pad = cols.saturating_sub(lo.len() + hi.len() + name.len());
    let left = pad / 2;
    lines.push(format!(
        "{:GUTTER$}{lo}{}{name}{}{hi}",
        "",
        " ".repeat(left),
        " ".repeat(pad - left)
    ));
    if marks.iter().any(|&m| m != ' ') {
        lines.push(format!(
            "{:>GUTTER$}{}",
            "s/r ",
            marks.iter().collect::<String>()
        ));
    }
    lines
}

fn fixed_params(spec: &SweepSpec) -> String {
    match spec.param {
        SweepParam::Alpha => format!("r = {}", spec.r),
        SweepParam::R => format!("alpha = {}", spec.alpha),
        SweepParam::D => format!("alpha = {}  r = {}", spec.alpha, spec.r),
    }
}

/// Bit of the braille dot in column `dx` (0, 1) and row `dy` (0..4) of a cell.
pub fn braille_bit(dx: usize, dy: usize) -> u8 {
    const BITS: [[u8; 4]; 2] = [[0x01, 0x02, 0x04, 0x40], [0x08, 0x10, 0x20, 0x80]];
    BITS[dx & 1][dy & 3]
}

fn parse_steps(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if (1..=sweep::MAX_STEPS).contains(&n) => Ok(n),
        _ => Err(format!(
            "'{s}' is out of range: valid 1 ..= 10000000 values"
        )),
    }
}

fn parse_transient(s: &str) -> Result<u64, String> {
    let x = s.trim().parse::<f64>().ok();
    match x {
        Some(x) if x.fract() == 0.0 && x >= 1.0 && x <= sweep::MAX_TRANSIENT as f64 => Ok(x as u64),
        _ => Err(format!(
            "'{s}' is out of range: valid a whole number of periods in 1 ..= 1e12 (e.g. 5e6)"
        )),
    }
}

fn parse_keep(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if (1..=sweep::MAX_KEEP).contains(&n) => Ok(n),
        _ => Err(format!("'{s}' is out of range: valid 1 ..= 1000000 events")),
    }
}

fn parse_max_period(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if (1..=4096).contains(&n) => Ok(n),
        _ => Err(format!("'{s}' is out of range: valid 1 ..= 4096 events")),
    }
}

fn parse_tolerance(s: &str) -> Result<f64, String> {
    let x = parse_f64(s)?;
    if x > 0.0 && x <= 1e-3 {
        Ok(x)
    } else {
        Err(format!("{x} is out of range: valid (0, 1e-3]"))
    }
}

fn parse_cells(s: &str) -> Result<u16, String> {
    match s.trim().parse::<u16>() {
        Ok(n) if (10..=2000).contains(&n) => Ok(n),
        _ => Err(format!(
            "'{s}' is out of range: valid 10 ..= 2000 characters"
        )),
    }
}

fn parse_threads(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if (1..=4096).contains(&n) => Ok(n),
        _ => Err(format!("'{s}' is out of range: valid 1 ..= 4096 threads")),
    }
}

/// `I/N` with 1 ≤ I ≤ N.
pub fn parse_shard(s: &str) -> Result<Shard, String> {
    let bad = || format!("'{s}' is not a shard: valid I/N with 1 ≤ I ≤ N, e.g. 2/8");
    let (i, n) = s.trim().split_once('/').ok_or_else(bad)?;
    let i: usize = i.trim().parse().map_err(|_| bad())?;
    let n: usize = n.trim().parse().map_err(|_| bad())?;
    if n == 0 || i == 0 || i > n {
        return Err(bad());
    }
    Ok(Shard {
        index: i - 1,
        count: n,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn braille_bits_follow_the_unicode_layout() {
        // U+28FF has all eight dots; the left column is dots 1, 2, 3, 7.
        let all: u8 = (0..2)
            .flat_map(|x| (0..4).map(move |y| braille_bit(x, y)))
            .fold(0, |a, b| a | b);
        assert_eq!(all, 0xFF);
        assert_eq!(char::from_u32(0x2800 + braille_bit(0, 3) as u32), Some('⡀'));
        assert_eq!(char::from_u32(0x2800 + braille_bit(1, 0) as u32), Some('⠈'));
    }

    #[test]
    fn shard_parsing_is_one_based() {
        assert_eq!(parse_shard("1/4"), Ok(Shard { index: 0, count: 4 }));
        assert_eq!(parse_shard("4/4"), Ok(Shard { index: 3, count: 4 }));
        assert!(parse_shard("0/4").is_err());
        assert!(parse_shard("5/4").is_err());
        assert!(parse_shard("x").is_err());
    }
}
