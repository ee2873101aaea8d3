//! `sweep`'s flags, and the preset they may name, into one validated
//! [`SweepSpec`]. Flags given with a preset override its settings; the swept parameter is
//! the one given as a window `LO..HI` (or named by `--param`).

use super::presets::{preset, Param, Start};
use super::rules::{self, Rule};
use super::table_spec::TableSpec;
use super::InputError;
use crate::config::flags::{SweepArgs, SweepSpecArgs};
use bouncemap_engine::sweep::{InitialSpec, Periodicity, Shard, SweepSpec, Warm};
use bouncemap_engine::Table;

/// A number or a window LO..HI.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Setting {
    Fixed(f64),
    Window(f64, f64),
}

fn flag_rule(p: Param) -> (&'static str, Rule) {
    match p {
        Param::Alpha => ("alpha", rules::ALPHA),
        Param::R => ("r", rules::R),
        Param::D => ("d", rules::D),
    }
}

fn parse_setting(p: Param, s: &str) -> Result<Setting, InputError> {
    let (flag, rule) = flag_rule(p);
    let one = |t: &str| {
        rule.parse(t)
            .map_err(|e| InputError(format!("--{flag} {s}: {e}")))
    };
    if let Some((a, b)) = s.split_once("..") {
        let (lo, hi) = (one(a)?, one(b)?);
        if lo > hi {
            return Err(InputError(format!(
                "--{flag} {s}: the window is empty: valid LO..HI with LO ≤ HI"
            )));
        }
        Ok(Setting::Window(lo, hi))
    } else {
        let x = rule
            .parse(s)
            .map_err(|e| InputError(format!("--{flag} {s}: {e} (or a window LO..HI)")))?;
        Ok(Setting::Fixed(x))
    }
}

/// The sweep `sweep`'s flags (and their preset) describe.
pub fn sweep_spec(args: &SweepArgs) -> Result<SweepSpec, InputError> {
    sweep_spec_from(&args.spec, args.shard.unwrap_or(Shard::WHOLE))
}

/// The sweep the flags shared by `sweep` and `figure diagram` (and their preset)
/// describe, computing part `shard`.
pub fn sweep_spec_from(args: &SweepSpecArgs, shard: Shard) -> Result<SweepSpec, InputError> {
    let p = match &args.preset {
        Some(name) => Some(preset(name).map_err(|e| InputError(format!("--preset: {e}")))?),
        None => None,
    };
    let pr = p.as_ref();
    let mut given = [
        (Param::Alpha, args.alpha.clone()),
        (Param::R, args.r.clone()),
        (Param::D, args.d.clone()),
    ];
    // The preset's window applies to its own parameter, unless --param sweeps another.
    if let Some(p) = pr {
        if args.param.is_none_or(|q| q == p.param) {
            for (q, v) in given.iter_mut() {
                if *q == p.param && v.is_none() {
                    *v = Some(format!("{}..{}", p.window[0], p.window[1]));
                }
            }
        }
        for (q, v) in given.iter_mut() {
            let fixed = match q {
                Param::Alpha => p.alpha,
                Param::R => p.r,
                Param::D => None,
            };
            if v.is_none() && *q != p.param {
                *v = fixed.map(|x| x.to_string());
            }
        }
    }
    let mut parsed = Vec::new();
    for (q, v) in &given {
        parsed.push((*q, v.as_deref().map(|s| parse_setting(*q, s)).transpose()?));
    }
    let windows: Vec<Param> = parsed
        .iter()
        .filter(|(_, s)| matches!(s, Some(Setting::Window(..))))
        .map(|(q, _)| *q)
        .collect();
    let param = match (args.param, windows.as_slice()) {
        (Some(q), _) => q,
        (None, [one]) => *one,
        (None, []) => return Err(InputError(
            "sweep: no window given: give the swept parameter as LO..HI, e.g. --alpha 0.45..0.6"
                .into(),
        )),
        (None, _) => {
            let names: Vec<String> = windows
                .iter()
                .map(|q| format!("--{}", flag_rule(*q).0))
                .collect();
            return Err(InputError(format!(
                "sweep: windows given for {}: valid a window for exactly one of --alpha, --r, --d",
                names.join(" and ")
            )));
        }
    };
    let mut window = None;
    let mut fixed = |q: Param| -> Result<Option<f64>, InputError> {
        let flag = flag_rule(q).0;
        let s = parsed.iter().find(|(g, _)| *g == q).and_then(|(_, s)| *s);
        match s {
            Some(Setting::Window(lo, hi)) if q == param => {
                window = Some((lo, hi));
                Ok(None)
            }
            Some(Setting::Window(lo, hi)) => Err(InputError(format!(
                "--{flag} {lo}..{hi}: only the swept parameter (--{}) takes a window: valid a number",
                flag_rule(param).0
            ))),
            None if q == param => Err(InputError(format!(
                "--{flag}: the swept parameter needs a window: valid LO..HI, e.g. --{flag} 0.4..0.6"
            ))),
            Some(Setting::Fixed(x)) if q == param => Err(InputError(format!(
                "--{flag} {x}: the swept parameter needs a window: valid LO..HI"
            ))),
            Some(Setting::Fixed(x)) => Ok(Some(x)),
            None => Ok(None),
        }
    };
    let alpha = fixed(Param::Alpha)?.unwrap_or(rules::ALPHA.default);
    let r = fixed(Param::R)?.unwrap_or(rules::R.default);
    let d = fixed(Param::D)?;
    let (lo, hi) = window.expect("the swept parameter's window was checked");
    let table_arg: Option<TableSpec> = args.table.clone().or(pr.map(|p| p.table.clone()));
    let table =
        match (param, &table_arg, d) {
            (Param::D, Some(t), _) => {
                if t.d().is_none() {
                    let source = match (&args.table, &args.preset) {
                        (None, Some(name)) => format!("--preset {name}: its table {t}"),
                        _ => format!("--table {t}"),
                    };
                    return Err(InputError(format!(
                        "{source} cannot sweep D: valid an fd:D table (fd:D, quad or cubic)"
                    )));
                }
                t.load()?
            }
            (Param::D, None, _) => Table::fd(lo)?,
            (_, Some(_), Some(_)) if args.table.is_some() => return Err(InputError(
                "--d: give either --table or --d, not both: valid --d D alone means --table fd:D"
                    .into(),
            )),
            (_, _, Some(dv)) => Table::fd(dv)?,
            (_, Some(t), None) => t.load()?,
            (_, None, None) => TableSpec::parse(rules::DEFAULT_TABLE)
                .map_err(InputError)?
                .load()?,
        };
    let mut spec = SweepSpec::new(
        table,
        alpha,
        r,
        param.into(),
        lo,
        hi,
        args.steps
            .or(pr.map(|p| p.steps))
            .unwrap_or(rules::STEPS.default as usize),
    );
    spec.initial = InitialSpec {
        t0: args.initial.t0,
        v0: args.initial.v0,
        z0: args.initial.z0,
        near_fixed_point: args.near_fixed_point
            || pr.is_some_and(|p| p.start == Start::NearFixedPoint),
    };
    spec.transient = args
        .transient
        .or(pr.map(|p| p.transient))
        .unwrap_or(rules::TRANSIENT.default as u64);
    spec.keep = args
        .keep
        .or(pr.map(|p| p.keep))
        .unwrap_or(rules::KEEP.default as usize);
    spec.solver = args.solver.unwrap_or_default().into();
    spec.warm = if args.warm { Warm::Forward } else { Warm::Off };
    spec.periodicity = (!args.no_early_stop).then_some(Periodicity {
        max_period: args.max_period,
        tolerance: args.tolerance,
    });
    spec.shard = shard;
    spec.lyapunov = args.lyapunov;
    spec.starts = args.starts.unwrap_or(rules::STARTS.default as usize);
    spec.w_max = args.w_max;
    spec.validate()
        .map_err(|e| InputError(format!("sweep: {e}")))?;
    Ok(spec)
}
