//! `plane`'s flags into one validated [`PlaneSpec`]: the axes `PARAM:LO..HI`, the table
//! (`fd` names the F_D family for a d axis), the fixed parameters and the start.

use super::flags::{PlaneArgs, PlaneSpecArgs, PlaneStartArg};
use super::rules;
use super::sweep::shard;
use super::table_spec::TableSpec;
use super::InputError;
use crate::output::text::quoted;
use bouncemap_engine::jobs::grid::Axis;
use bouncemap_engine::jobs::grid::Shard;
use bouncemap_engine::jobs::grid::SweepParam;
use bouncemap_engine::orbits::curves::Seeds;
use bouncemap_engine::plane::{PlaneSpec, PlaneStart};
use bouncemap_engine::Table;

/// `PARAM:LO..HI` with PARAM alpha, r or a parameter of `table`'s family, and n
/// pixels; each end is checked against the parameter's range.
pub fn parse_axis(flag: &str, s: &str, n: usize, table: &Table) -> Result<Axis, InputError> {
    let refuse = |msg: String| InputError(format!("--{flag} {}: {msg}", quoted(s)));
    let names = SweepParam::names(table);
    let (name, window) = s.trim().split_once(':').ok_or_else(|| {
        refuse(format!(
            "not an axis: valid PARAM:LO..HI with PARAM one of {names}, e.g. alpha:0.45..0.6"
        ))
    })?;
    let param = SweepParam::parse(name, table).map_err(|e| {
        if name.trim().eq_ignore_ascii_case("d") {
            refuse(format!(
                "the table {} has no parameter D: valid --table fd (the F_D family), or a table file declaring D",
                table.name()
            ))
        } else {
            refuse(format!("the table {}: {e}", table.name()))
        }
    })?;
    let (a, b) = window
        .split_once("..")
        .ok_or_else(|| refuse("not a window: valid PARAM:LO..HI".into()))?;
    let value = |t: &str| rules::param_value(param, table, t).map_err(&refuse);
    let (lo, hi) = (value(a)?, value(b)?);
    if lo > hi {
        return Err(refuse(
            "the window is empty: valid LO..HI with LO ≤ HI".into(),
        ));
    }
    Ok(Axis { param, lo, hi, n })
}

/// `--table` of a plane or curves, loaded: `fd` names the F_D family (at the default
/// D, which its axis replaces), else any table name.
fn table_of(text: &str) -> Result<(TableSpec, Table), InputError> {
    let spec = match text.trim() {
        "fd" => TableSpec::fd(rules::D.default),
        t => TableSpec::parse(t).map_err(|e| InputError(format!("--table: {e}")))?,
    };
    let table = spec.load()?;
    Ok((spec, table))
}

/// The parameter name of an axis text `NAME:LO..HI` (before the table is known).
fn axis_name(s: &str) -> &str {
    s.trim().split_once(':').map_or("", |(n, _)| n.trim())
}

/// `--table` of a plane ([`table_of`]). A table whose name gives a value to a parameter
/// that is an axis would have it replaced: refused instead of dropped.
fn plane_table(text: &str, axes: [&str; 2]) -> Result<(TableSpec, Table), InputError> {
    let (spec, table) = table_of(text)?;
    for name in axes {
        if let Ok(SweepParam::Table(n)) = SweepParam::parse(name, &table) {
            if text.trim() != "fd" && spec.sets(n.as_str()) {
                let valid = if spec.d().is_some() {
                    "--table fd".to_string()
                } else {
                    "the table without a value for it".to_string()
                };
                return Err(InputError(format!(
                    "--table {}: {} is an axis of the plane, so the table's own {} would be ignored: valid {valid}",
                    crate::output::text::escape(text.trim()),
                    n.as_str(),
                    n.as_str()
                )));
            }
        }
    }
    Ok((spec, table))
}

/// The plane `plane`'s flags describe.
pub fn plane_spec(args: &PlaneArgs) -> Result<PlaneSpec, InputError> {
    let mut spec = plane_spec_from(
        &args.spec,
        args.size,
        shard(args.part.shard, |name| std::env::var(name).ok())?,
    )?;
    spec.digits = super::digits::digits_ask(&args.precision)?;
    if let Some(ask) = spec.digits {
        super::digits::digits_take(&spec.table)?;
        // The parameters and the axes' windows as typed, every digit.
        let settings: Vec<(&str, Option<&str>)> = [&args.spec.x, &args.spec.y]
            .into_iter()
            .filter_map(|axis| axis.split_once(':'))
            .map(|(name, window)| (name.trim(), Some(window)))
            .collect();
        let system = (&spec.table, spec.alpha, spec.r);
        spec.written = super::digits::job_written(&args.precision.written, &settings, system, ask)?;
    }
    Ok(spec)
}

/// The plane `plane`'s spec flags describe with `nx × ny` pixels, computing part `part`.
pub fn plane_spec_from(
    args: &PlaneSpecArgs,
    (nx, ny): (usize, usize),
    part: Shard,
) -> Result<PlaneSpec, InputError> {
    let (_, table) = plane_table(&args.table, [axis_name(&args.x), axis_name(&args.y)])?;
    let x = parse_axis("x", &args.x, nx, &table)?;
    let y = parse_axis("y", &args.y, ny, &table)?;
    let mut spec = PlaneSpec::new(
        table,
        x,
        y,
        args.alpha.unwrap_or(rules::ALPHA.default),
        args.r.unwrap_or(rules::R.default),
    );
    for (p, given, flag) in [
        (SweepParam::Alpha, args.alpha.is_some(), "alpha"),
        (SweepParam::R, args.r.is_some(), "r"),
    ] {
        if given && (x.param == p || y.param == p) {
            return Err(InputError(format!(
                "--{flag}: {flag} is an axis of the plane: valid either --{flag} or an axis {flag}:LO..HI"
            )));
        }
    }
    spec.transient = args.transient;
    spec.start = match args.start {
        PlaneStartArg::NearFixedPoint => PlaneStart::NearFixedPoint,
        PlaneStartArg::Cold => PlaneStart::Cold,
    };
    spec.lyapunov = !args.no_lyapunov;
    spec.shard = part;
    spec.validate()?;
    Ok(spec)
}

/// `curves`' flags into the engine's plane of two parameters and the seeds the curves
/// are started from, at the second parameter's starting value: the x axis must be α,
/// the y axis r or a family parameter (with the F_D family, `--table fd` starts from
/// the window's middle, `fd:D` from D, which must lie in the window; an r axis starts
/// from `--r`).
pub fn curves_plane(
    args: &super::flags::CurvesSpecArgs,
) -> Result<(bouncemap_engine::orbits::curves::Plane, Seeds), InputError> {
    let fd_family = args.table.trim() == "fd";
    let (table_spec, table) = table_of(&args.table)?;
    let x = parse_axis("x", &args.x, 2, &table)?;
    let y = parse_axis("y", &args.y, 2, &table)?;
    if x.param != SweepParam::Alpha {
        return Err(InputError(format!(
            "--x {}: the curves' x axis is alpha: valid alpha:LO..HI",
            quoted(&args.x)
        )));
    }
    if y.param == SweepParam::Alpha {
        return Err(InputError(format!(
            "--y {}: the second parameter is one of {}: valid NAME:LO..HI",
            quoted(&args.y),
            SweepParam::names(&table).trim_start_matches("alpha, ")
        )));
    }
    for (flag, axis, text) in [("x", x, &args.x), ("y", y, &args.y)] {
        if axis.lo >= axis.hi {
            return Err(InputError(format!(
                "--{flag} {}: the window is a single value: valid LO..HI with LO < HI",
                quoted(text)
            )));
        }
    }
    let at = match y.param {
        SweepParam::Table(n) => {
            let name = n.as_str();
            let v = table
                .param(name)
                .expect("the axis is the table's parameter");
            if fd_family || !table_spec.sets(name) {
                // No value given: the curves start from the window's middle.
                0.5 * (y.lo + y.hi)
            } else if v < y.lo || v > y.hi {
                let valid = if table_spec.d().is_some() {
                    "fd:D with D in the window, or fd"
                } else {
                    "a value in the window, or none"
                };
                return Err(InputError(format!(
                    "--table {}: {name} = {v} is outside the {name} window {}..{}: valid {valid}",
                    args.table.trim(),
                    y.lo,
                    y.hi
                )));
            } else {
                v
            }
        }
        _ => match args.r {
            Some(r) if r < y.lo || r > y.hi => {
                return Err(InputError(format!(
                    "--r {r}: outside the r window {}..{}: valid an r in the window, where the curves start (or none: the window's middle)",
                    y.lo, y.hi
                )));
            }
            Some(r) => r,
            None => 0.5 * (y.lo + y.hi),
        },
    };
    let plane = bouncemap_engine::orbits::curves::Plane {
        table,
        r: match y.param {
            SweepParam::R => at,
            _ => args.r.unwrap_or(rules::R.default),
        },
        alpha: (x.lo, x.hi),
        second: y.param,
        window: (y.lo, y.hi),
    };
    plane.check()?;
    Ok((plane, seeds(args, at)))
}

/// The seeds `args` ask for, started at `at`: the (1, k) branches, or one (n, k)
/// cycle's.
fn seeds(args: &super::flags::CurvesSpecArgs, at: f64) -> Seeds {
    match args.guess.cycle() {
        Some((n, t0, v0)) => Seeds::Point {
            n,
            k: args.k,
            t0,
            v0,
            at,
        },
        None => Seeds::FromFixed {
            k: args.k,
            max_period: args.max_period,
            at,
            count: args.seeds,
        },
    }
}

/// The two-parameter curves that cover a plane's picture (`plane --curves`, `figure
/// plane --curves`, the plane view's curves): the plane of α on one axis and r or d on
/// the other, and the seeds of `curves`' defaults for the (1, k) branches up to
/// `max_period`, started at `current` (the application's own D or r), else at the
/// plane's r (an r axis) or its table's D (a d axis), whichever lies in the window,
/// else at the window's middle.
pub fn plane_curves(
    spec: &PlaneSpec,
    k: u32,
    max_period: usize,
    current: Option<f64>,
) -> Result<
    (
        bouncemap_engine::orbits::curves::Plane,
        bouncemap_engine::orbits::curves::Seeds,
    ),
    InputError,
> {
    let (alpha, other) = match (spec.x.param, spec.y.param) {
        (SweepParam::Alpha, p) if p != SweepParam::Alpha => (spec.x, spec.y),
        (p, SweepParam::Alpha) if p != SweepParam::Alpha => (spec.y, spec.x),
        _ => {
            return Err(InputError(
                "--curves: the curves live in a plane of alpha and r or d: valid with one axis alpha:LO..HI and the other r or d".into(),
            ))
        }
    };
    let own = match other.param {
        SweepParam::Table(n) => spec.table.param(n.as_str()).unwrap_or(other.lo),
        _ => spec.r,
    };
    let at = [current, Some(own)]
        .into_iter()
        .flatten()
        .find(|v| (other.lo..=other.hi).contains(v))
        .unwrap_or(0.5 * (other.lo + other.hi));
    let plane = bouncemap_engine::orbits::curves::Plane {
        table: spec.table.clone(),
        r: spec.r,
        alpha: (alpha.lo, alpha.hi),
        second: other.param,
        window: (other.lo, other.hi),
    };
    plane.check()?;
    let seeds = bouncemap_engine::orbits::curves::Seeds::FromFixed {
        k,
        max_period,
        at,
        count: rules::CURVE_SEEDS.default as usize,
    };
    Ok((plane, seeds))
}
