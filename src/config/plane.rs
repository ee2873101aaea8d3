//! `plane`'s flags into one validated [`PlaneSpec`]: the axes `PARAM:LO..HI`, the table
//! (`fd` names the F_D family for a d axis), the fixed parameters and the start.

use super::flags::{PlaneArgs, PlaneSpecArgs, PlaneStartArg};
use super::rules::{self, Rule};
use super::sweep::shard;
use super::table_spec::TableSpec;
use super::InputError;
use crate::output::text::quoted;
use bouncemap_engine::grid::Axis;
use bouncemap_engine::grid::Shard;
use bouncemap_engine::grid::SweepParam;
use bouncemap_engine::plane::{PlaneSpec, PlaneStart};

/// The rule of an axis parameter.
fn rule_of(p: SweepParam) -> Rule {
    match p {
        SweepParam::Alpha => rules::ALPHA,
        SweepParam::R => rules::R,
        SweepParam::D => rules::D,
    }
}

/// `PARAM:LO..HI` with PARAM alpha, r or d and n pixels.
pub fn parse_axis(flag: &str, s: &str, n: usize) -> Result<Axis, InputError> {
    let refuse = |msg: String| InputError(format!("--{flag} {}: {msg}", quoted(s)));
    let (name, window) = s.trim().split_once(':').ok_or_else(|| {
        refuse(
            "not an axis: valid PARAM:LO..HI with PARAM alpha, r or d, e.g. alpha:0.45..0.6".into(),
        )
    })?;
    let param = SweepParam::ALL
        .into_iter()
        .find(|p| p.as_str() == name.trim())
        .ok_or_else(|| {
            refuse(format!(
                "unknown parameter '{}': valid alpha, r or d",
                name.trim()
            ))
        })?;
    let (a, b) = window
        .split_once("..")
        .ok_or_else(|| refuse("not a window: valid PARAM:LO..HI".into()))?;
    let rule = rule_of(param);
    let lo = rule.parse(a).map_err(&refuse)?;
    let hi = rule.parse(b).map_err(&refuse)?;
    if lo > hi {
        return Err(refuse(
            "the window is empty: valid LO..HI with LO ≤ HI".into(),
        ));
    }
    Ok(Axis { param, lo, hi, n })
}

/// The plane `plane`'s flags describe.
pub fn plane_spec(args: &PlaneArgs) -> Result<PlaneSpec, InputError> {
    plane_spec_from(
        &args.spec,
        args.size,
        shard(args.part.shard, |name| std::env::var(name).ok())?,
    )
}

/// The plane `plane`'s spec flags describe with `nx × ny` pixels, computing part `part`.
pub fn plane_spec_from(
    args: &PlaneSpecArgs,
    (nx, ny): (usize, usize),
    part: Shard,
) -> Result<PlaneSpec, InputError> {
    let x = parse_axis("x", &args.x, nx)?;
    let y = parse_axis("y", &args.y, ny)?;
    let has_d = x.param == SweepParam::D || y.param == SweepParam::D;
    let table = match args.table.trim() {
        "fd" => TableSpec::fd(rules::D.default),
        t => TableSpec::parse(t).map_err(|e| InputError(format!("--table: {e}")))?,
    };
    if has_d && table.d().is_none() {
        return Err(InputError(format!(
            "--table {}: a d axis needs the F_D family: valid --table fd",
            crate::output::text::escape(args.table.trim())
        )));
    }
    // A D given with the table would be replaced by the axis's: say so instead of
    // dropping it.
    if has_d && args.table.trim() != "fd" {
        return Err(InputError(format!(
            "--table {}: D is an axis of the plane, so the table's own D would be ignored: valid --table fd",
            crate::output::text::escape(args.table.trim())
        )));
    }
    let table = table.load()?;
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

/// `curves`' flags into the engine's plane of two parameters and the second
/// parameter's value the curves are started from: the x axis must be α, the y axis r
/// or d (d with the F_D family: `--table fd` starts from the window's middle, `fd:D`
/// from D, which must lie in the window; an r axis starts from `--r`).
pub fn curves_plane(
    args: &super::flags::CurvesSpecArgs,
) -> Result<(bouncemap_engine::orbits::curves::Plane, f64), InputError> {
    let x = parse_axis("x", &args.x, 2)?;
    let y = parse_axis("y", &args.y, 2)?;
    if x.param != SweepParam::Alpha {
        return Err(InputError(format!(
            "--x {}: the curves' x axis is alpha: valid alpha:LO..HI",
            quoted(&args.x)
        )));
    }
    if y.param == SweepParam::Alpha {
        return Err(InputError(format!(
            "--y {}: the second parameter is r or d: valid r:LO..HI or d:LO..HI",
            quoted(&args.y)
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
    let table = match args.table.trim() {
        "fd" => TableSpec::fd(rules::D.default),
        t => TableSpec::parse(t).map_err(|e| InputError(format!("--table: {e}")))?,
    };
    let at = match y.param {
        SweepParam::D => {
            let Some(d) = table.d() else {
                return Err(InputError(format!(
                    "--table {}: a d axis needs the F_D family: valid --table fd or fd:D",
                    crate::output::text::escape(args.table.trim())
                )));
            };
            if args.table.trim() == "fd" {
                0.5 * (y.lo + y.hi)
            } else if d < y.lo || d > y.hi {
                return Err(InputError(format!(
                    "--table {}: D = {d} is outside the d window {}..{}: valid fd:D with D in the window, or fd",
                    args.table.trim(),
                    y.lo,
                    y.hi
                )));
            } else {
                d
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
        table: table.load()?,
        r: match y.param {
            SweepParam::R => at,
            _ => args.r.unwrap_or(rules::R.default),
        },
        alpha: (x.lo, x.hi),
        second: y.param,
        window: (y.lo, y.hi),
    };
    plane.check()?;
    Ok((plane, at))
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
        SweepParam::D => spec.table.d().unwrap_or(rules::D.default),
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
