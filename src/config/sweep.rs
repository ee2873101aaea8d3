//! `sweep`'s flags, and the preset they may name, into one validated
//! [`SweepSpec`]. Flags given with a preset override its settings; the swept parameter is
//! the one given as a window `LO..HI` (or named by `--param`).

use super::presets::{preset, Start};
use super::rules::{self, Rule};
use super::table_spec::TableSpec;
use super::InputError;
use crate::config::flags::{ShardArg, SweepArgs, SweepSpecArgs};
use crate::output::text::quoted;
use bouncemap_engine::jobs::grid::{Shard, SweepParam};
use bouncemap_engine::run::detect::Periodicity;
use bouncemap_engine::sweep::{InitialSpec, SweepSpec, Warm};
use bouncemap_engine::Table;

/// A number or a window LO..HI.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Setting {
    Fixed(f64),
    Window(f64, f64),
}

/// The flags that set one parameter each: --alpha, --r, and --d for F_D's D.
const FLAGS: [(&str, Rule); 3] = [("alpha", rules::ALPHA), ("r", rules::R), ("d", rules::D)];

fn parse_setting(flag: &str, rule: Rule, s: &str) -> Result<Setting, InputError> {
    let one = |t: &str| {
        rule.parse(t)
            .map_err(|e| InputError(format!("--{flag} {}: {e}", quoted(s))))
    };
    if let Some((a, b)) = s.split_once("..") {
        let (lo, hi) = (one(a)?, one(b)?);
        if lo > hi {
            return Err(InputError(format!(
                "--{flag} {}: the window is empty: valid LO..HI with LO ≤ HI",
                quoted(s)
            )));
        }
        Ok(Setting::Window(lo, hi))
    } else {
        let x = rule
            .parse(s)
            .map_err(|e| InputError(format!("--{flag} {}: {e} (or a window LO..HI)", quoted(s))))?;
        Ok(Setting::Fixed(x))
    }
}

/// The parameter a flag sets, over `table`.
fn flag_param(flag: &str) -> SweepParam {
    match flag {
        "alpha" => SweepParam::Alpha,
        "r" => SweepParam::R,
        _ => SweepParam::D,
    }
}

/// `--param NAME` or `--param NAME:LO..HI`: the name, and the window if given (each end
/// checked against the parameter's range over `table`, which `source` names in the
/// refusal of a name it does not have).
fn parse_param_flag(
    s: &str,
    table: &Table,
    source: &str,
) -> Result<(SweepParam, Option<(f64, f64)>), InputError> {
    let refuse = |m: String| InputError(format!("--param {}: {m}", quoted(s)));
    let (name, window) = match s.split_once(':') {
        Some((n, w)) => (n, Some(w)),
        None => (s, None),
    };
    let param = SweepParam::parse(name, table).map_err(|_| {
        refuse(format!(
            "{source} has no such parameter: valid {}",
            SweepParam::names(table)
        ))
    })?;
    let Some(w) = window else {
        return Ok((param, None));
    };
    let (a, b) = w
        .split_once("..")
        .ok_or_else(|| refuse("not a window: valid NAME:LO..HI".into()))?;
    let num = |t: &str| rules::param_value(param, table, t).map_err(&refuse);
    let (lo, hi) = (num(a)?, num(b)?);
    if lo > hi {
        return Err(refuse(
            "the window is empty: valid LO..HI with LO ≤ HI".into(),
        ));
    }
    Ok((param, Some((lo, hi))))
}

/// The sweep `sweep`'s flags (and their preset) describe.
pub fn sweep_spec(args: &SweepArgs) -> Result<SweepSpec, InputError> {
    let mut spec = sweep_spec_from(
        &args.spec,
        shard(args.part.shard, |name| std::env::var(name).ok())?,
    )?;
    spec.digits = super::digits::digits_ask(&args.precision)?;
    if let Some(ask) = spec.digits {
        super::digits::digits_take(&spec.table)?;
        // The parameters and the window as typed, every digit.
        let a = &args.spec;
        let mut settings = vec![
            ("alpha", a.alpha.as_deref()),
            ("r", a.r.as_deref()),
            ("D", a.d.as_deref()),
        ];
        if let Some((name, window)) = a.param.as_deref().and_then(|p| p.split_once(':')) {
            settings.push((name.trim(), Some(window)));
        }
        let system = (&spec.table, spec.alpha, spec.r);
        spec.written = super::digits::job_written(&args.precision.written, &settings, system, ask)?;
    }
    Ok(spec)
}

/// The sweep the flags shared by `sweep` and `figure diagram` (and their preset)
/// describe, computing part `part`.
pub fn sweep_spec_from(args: &SweepSpecArgs, part: Shard) -> Result<SweepSpec, InputError> {
    let p = match &args.preset {
        Some(name) => Some(preset(name).map_err(|e| InputError(format!("--preset: {e}")))?),
        None => None,
    };
    let pr = p.as_ref();
    let mut given: Vec<(&str, Option<Setting>)> = Vec::new();
    for ((flag, rule), text) in FLAGS.iter().zip([&args.alpha, &args.r, &args.d]) {
        given.push((
            flag,
            text.as_deref()
                .map(|s| parse_setting(flag, *rule, s))
                .transpose()?,
        ));
    }
    let setting = |flag: &str| given.iter().find(|g| g.0 == flag).and_then(|g| g.1);
    // The table: --table, else the preset's; --d D alone means fd:D.
    let table_arg: Option<TableSpec> = args.table.clone().or(pr.map(|p| p.table.clone()));
    let table =
        match (&table_arg, setting("d")) {
            (Some(_), Some(Setting::Fixed(_))) if args.table.is_some() => return Err(InputError(
                "--d: give either --table or --d, not both: valid --d D alone means --table fd:D"
                    .into(),
            )),
            (_, Some(Setting::Fixed(d))) => Table::fd(d)?,
            (Some(t), _) => t.load()?,
            (None, Some(Setting::Window(lo, _))) => Table::fd(lo)?,
            (None, None) => TableSpec::parse(rules::DEFAULT_TABLE)
                .map_err(InputError)?
                .load()?,
        };
    // Where the table came from, as refusals name it.
    let source = match (&args.table, &args.preset, &table_arg) {
        (None, Some(name), Some(t)) => format!("--preset {name}: its table {t}"),
        (_, _, Some(t)) => format!("--table {t}"),
        _ => format!("the table {}", table.name()),
    };
    let (flagged, flag_window) = match &args.param {
        Some(s) => {
            let (q, w) = parse_param_flag(s, &table, &source)?;
            (Some(q), w)
        }
        None => (None, None),
    };
    // The preset's window applies to its own parameter, unless --param sweeps another.
    let preset_param = match pr {
        Some(p) => Some(
            SweepParam::parse(&p.param, &table)
                .map_err(|e| InputError(format!("--preset: {e}")))?,
        ),
        None => None,
    };
    let windows: Vec<&str> = given
        .iter()
        .filter(|(_, s)| matches!(s, Some(Setting::Window(..))))
        .map(|(f, _)| *f)
        .collect();
    let param = match (flagged, windows.as_slice()) {
        (Some(q), _) => q,
        (None, [one]) => flag_param(one),
        (None, []) => match preset_param {
            Some(q) => q,
            None => return Err(InputError(
                "sweep: no window given: give the swept parameter as LO..HI, e.g. --alpha 0.45..0.6, or name it with --param NAME"
                    .into(),
            )),
        },
        (None, _) => {
            let names: Vec<String> = windows.iter().map(|f| format!("--{f}")).collect();
            return Err(InputError(format!(
                "sweep: windows given for {}: valid a window for exactly one of --alpha, --r, --d",
                names.join(" and ")
            )));
        }
    };
    if param == SweepParam::D && table.param("D").is_none() {
        return Err(InputError(format!(
            "{source} cannot sweep D: valid an fd:D table (fd:D, quad or cubic), or a table file declaring D"
        )));
    }
    // The swept parameter's flag, if it has one.
    let own_flag = FLAGS.iter().map(|f| f.0).find(|f| flag_param(f) == param);
    let mut window = flag_window;
    for (flag, s) in &given {
        match s {
            Some(Setting::Window(lo, hi)) if Some(*flag) == own_flag => {
                if window.is_some() {
                    return Err(InputError(format!(
                        "--{flag} {lo}..{hi}: the window is given twice (also by --param): valid one of them"
                    )));
                }
                window = Some((*lo, *hi));
            }
            Some(Setting::Window(lo, hi)) => {
                return Err(InputError(format!(
                    "--{flag} {lo}..{hi}: only the swept parameter ({param}) takes a window: valid a number"
                )))
            }
            Some(Setting::Fixed(x)) if Some(*flag) == own_flag => {
                return Err(InputError(format!(
                    "--{flag} {x}: the swept parameter needs a window: valid LO..HI"
                )))
            }
            _ => {}
        }
    }
    if window.is_none() && preset_param == Some(param) {
        window = pr.map(|p| p.window());
    }
    // A parameter of the table's family is swept over its whole range by default.
    if window.is_none() && param.is_table() {
        window = param.range(&table);
    }
    let Some((lo, hi)) = window else {
        let flag = own_flag.unwrap_or("alpha");
        return Err(InputError(format!(
            "--{flag}: the swept parameter needs a window: valid LO..HI, e.g. --{flag} 0.4..0.6"
        )));
    };
    let fixed = |flag: &str, from_preset: Option<f64>, default: f64| -> f64 {
        match setting(flag) {
            Some(Setting::Fixed(x)) => x,
            _ => from_preset.unwrap_or(default),
        }
    };
    let alpha = fixed("alpha", pr.and_then(|p| p.alpha), rules::ALPHA.default);
    let r = fixed("r", pr.and_then(|p| p.r), rules::R.default);
    let mut spec = SweepSpec::new(
        table,
        alpha,
        r,
        param,
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
    spec.shard = part;
    spec.lyapunov = args.lyapunov;
    spec.starts = args.starts.unwrap_or(rules::STARTS.default as usize);
    spec.w_max = args.w_max;
    spec.validate()
        .map_err(|e| InputError(format!("sweep: {e}")))?;
    Ok(spec)
}

/// The part to compute: `--shard I/N` as given; `--shard auto`, or no `--shard` in a
/// task of a Slurm job array (`SLURM_ARRAY_TASK_ID` set), the task's part; else the
/// whole sweep. `env` reads an environment variable (unset and empty are alike).
///
/// The array's part: N = MAX − MIN + 1 and I = ID − MIN + 1 from
/// `SLURM_ARRAY_TASK_ID`, `SLURM_ARRAY_TASK_MIN` and `SLURM_ARRAY_TASK_MAX`, so
/// `--array=0-7` and `--array=1-8` both make the shards 1/8 … 8/8. An array that is
/// not a whole range (`SLURM_ARRAY_TASK_COUNT` ≠ N: a step, or a list with gaps) and
/// inconsistent variables are refused.
pub fn shard(
    arg: Option<ShardArg>,
    env: impl Fn(&str) -> Option<String>,
) -> Result<Shard, InputError> {
    let var = |name: &str| env(name).filter(|v| !v.trim().is_empty());
    let context = match arg {
        Some(ShardArg::Part(s)) => return Ok(s),
        Some(ShardArg::Auto) => "--shard auto",
        None if var("SLURM_ARRAY_TASK_ID").is_some() => {
            "--shard auto (the default in a Slurm job array task)"
        }
        None => return Ok(Shard::WHOLE),
    };
    let refuse = |msg: String| InputError(format!("{context}: {msg}"));
    let id_of = |name: &str| -> Result<u64, InputError> {
        let v = var(name).ok_or_else(|| {
            refuse(format!(
                "{name} is not set: valid in a task of a Slurm job array (sbatch --array), \
                 which sets SLURM_ARRAY_TASK_ID, _MIN and _MAX; elsewhere give --shard I/N"
            ))
        })?;
        v.trim().parse::<u64>().map_err(|_| {
            refuse(format!(
                "{name}='{}' is not an array index: valid a whole number ≥ 0",
                v.escape_debug()
            ))
        })
    };
    let id = id_of("SLURM_ARRAY_TASK_ID")?;
    let min = id_of("SLURM_ARRAY_TASK_MIN")?;
    let max = id_of("SLURM_ARRAY_TASK_MAX")?;
    if min > max || id < min || id > max {
        return Err(refuse(format!(
            "SLURM_ARRAY_TASK_ID={id} is not in SLURM_ARRAY_TASK_MIN..SLURM_ARRAY_TASK_MAX \
             = {min}..{max}: valid MIN ≤ ID ≤ MAX"
        )));
    }
    let count = max - min + 1;
    if let Some(c) = var("SLURM_ARRAY_TASK_COUNT") {
        if c.trim().parse::<u64>().ok() != Some(count) {
            return Err(refuse(format!(
                "the array has SLURM_ARRAY_TASK_COUNT={} tasks but spans the {count} indices \
                 {min}..{max}: valid a whole range without step or gaps, e.g. --array=1-{count}",
                c.escape_debug()
            )));
        }
    }
    let too_many = || refuse(format!("an array of {count} tasks is too large to shard"));
    Ok(Shard {
        index: usize::try_from(id - min).map_err(|_| too_many())?,
        count: usize::try_from(count).map_err(|_| too_many())?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    fn env(vars: &[(&str, &str)]) -> impl Fn(&str) -> Option<String> {
        let map: HashMap<String, String> = vars
            .iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect();
        move |k| map.get(k).cloned()
    }

    fn array(id: &str, min: &str, max: &str) -> Vec<(&'static str, String)> {
        vec![
            ("SLURM_ARRAY_TASK_ID", id.to_string()),
            ("SLURM_ARRAY_TASK_MIN", min.to_string()),
            ("SLURM_ARRAY_TASK_MAX", max.to_string()),
        ]
    }

    fn auto(vars: &[(&str, String)], arg: Option<ShardArg>) -> Result<Shard, InputError> {
        let v: Vec<(&str, &str)> = vars.iter().map(|(k, v)| (*k, v.as_str())).collect();
        shard(arg, env(&v))
    }

    fn part(i: usize, n: usize) -> Shard {
        Shard {
            index: i - 1,
            count: n,
        }
    }

    #[test]
    fn array_tasks_map_to_parts_from_either_base() {
        // Task 3 of 0-7 is the fourth of eight; task 3 of 1-8 the third.
        assert_eq!(auto(&array("3", "0", "7"), None), Ok(part(4, 8)));
        assert_eq!(auto(&array("3", "1", "8"), None), Ok(part(3, 8)));
        assert_eq!(
            auto(&array("0", "0", "7"), Some(ShardArg::Auto)),
            Ok(part(1, 8))
        );
        assert_eq!(auto(&array("7", "0", "7"), None), Ok(part(8, 8)));
        assert_eq!(auto(&array("12", "10", "13"), None), Ok(part(3, 4)));
        // A one-task array is the whole sweep.
        assert_eq!(auto(&array("5", "5", "5"), None), Ok(part(1, 1)));
        // Every task of an array gets a different part, and together they cover 1..N.
        let mut seen: Vec<usize> = (0..8)
            .map(|id| auto(&array(&id.to_string(), "0", "7"), None).unwrap())
            .inspect(|s| assert_eq!(s.count, 8))
            .map(|s| s.index)
            .collect();
        seen.sort();
        assert_eq!(seen, (0..8).collect::<Vec<_>>());
    }

    #[test]
    fn an_explicit_part_wins_and_no_array_is_the_whole_sweep() {
        let given = Some(ShardArg::Part(part(2, 5)));
        assert_eq!(auto(&array("3", "0", "7"), given), Ok(part(2, 5)));
        assert_eq!(auto(&[], None), Ok(Shard::WHOLE));
        // Outside an array job, variables of other kinds change nothing.
        assert_eq!(
            auto(&[("SLURM_JOB_ID", "17".into())], None),
            Ok(Shard::WHOLE)
        );
        assert_eq!(
            auto(&[("SLURM_ARRAY_TASK_ID", "".into())], None),
            Ok(Shard::WHOLE)
        );
        let mut with_count = array("2", "1", "4");
        with_count.push(("SLURM_ARRAY_TASK_COUNT", "4".into()));
        assert_eq!(auto(&with_count, None), Ok(part(2, 4)));
    }

    #[test]
    fn inconsistent_arrays_are_refused_in_one_line_naming_the_variable() {
        let refused = |vars: &[(&str, String)], arg: Option<ShardArg>, want: &str| {
            let e = auto(vars, arg).unwrap_err().0;
            assert!(e.contains(want), "{e:?} lacks {want:?}");
            assert!(!e.contains('\n'), "{e:?}");
        };
        refused(&[], Some(ShardArg::Auto), "SLURM_ARRAY_TASK_ID is not set");
        refused(
            &[("SLURM_ARRAY_TASK_ID", "3".into())],
            None,
            "SLURM_ARRAY_TASK_MIN is not set",
        );
        refused(
            &[
                ("SLURM_ARRAY_TASK_ID", "3".into()),
                ("SLURM_ARRAY_TASK_MIN", "0".into()),
            ],
            Some(ShardArg::Auto),
            "SLURM_ARRAY_TASK_MAX is not set",
        );
        refused(
            &array("9", "0", "7"),
            None,
            "SLURM_ARRAY_TASK_ID=9 is not in",
        );
        refused(&array("0", "1", "8"), None, "= 1..8");
        refused(&array("4", "5", "3"), None, "= 5..3");
        refused(&array("x", "0", "7"), None, "SLURM_ARRAY_TASK_ID='x'");
        refused(&array("-1", "0", "7"), None, "SLURM_ARRAY_TASK_ID='-1'");
        // --array=1-7:2 has 4 tasks over 7 indices.
        let mut stepped = array("3", "1", "7");
        stepped.push(("SLURM_ARRAY_TASK_COUNT", "4".into()));
        refused(&stepped, None, "SLURM_ARRAY_TASK_COUNT=4");
        // The default says where the shard came from.
        refused(&array("9", "0", "7"), None, "default in a Slurm job array");
    }
}
