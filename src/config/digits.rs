//! `--digits`, `--max-digits` and `--binary-params` settled once for every command that
//! computes at any precision (`orbit`, `lyapunov`, `sweep`, `basins`), and what they are
//! refused with.

use super::InputError;

/// `--digits`, `--max-digits` and `--binary-params`, settled (None without
/// `--digits`, where the other two are refused).
pub fn digits_ask(
    p: &super::flags::PrecisionArgs,
) -> Result<Option<bouncemap_engine::DigitsAsk>, InputError> {
    let Some(digits) = p.digits else {
        if p.binary_params || p.max_digits != super::rules::MAX_DIGITS.default as u32 {
            return Err(InputError(
                "--binary-params and --max-digits go with --digits N: valid with --digits".into(),
            ));
        }
        return Ok(None);
    };
    if p.max_digits < digits {
        return Err(InputError(format!(
            "--max-digits {} is below --digits {digits}: valid --max-digits M with M ≥ N",
            p.max_digits
        )));
    }
    Ok(Some(bouncemap_engine::DigitsAsk {
        digits,
        max_digits: p.max_digits,
        binary: p.binary_params,
    }))
}

/// Whether `--digits` takes `table`: refused naming what it takes.
pub fn digits_take(table: &bouncemap_engine::Table) -> Result<(), InputError> {
    if !bouncemap_engine::precise_takes(table) {
        return Err(digits_refusal(table));
    }
    Ok(())
}

/// Why `--digits` does not take `table`, naming what it takes.
pub fn digits_refusal(table: &bouncemap_engine::Table) -> InputError {
    InputError(format!(
        "--digits: table {} is not computed at any precision: valid the sine or a piecewise polynomial table of degree ≤ {} (fd:D, quad, cubic, a table file)",
        table.name(),
        bouncemap_engine::PRECISE_MAX_DEGREE
    ))
}

/// The texts a job at any precision reads its parameters from: `kept` (α, r and the
/// table's, as typed on the command line) with each of `settings` (a parameter's name
/// and its text: a window `LO..HI`, or a value) as typed. Then refused, naming it, if
/// any is outside its range as written though its double is inside (the job's system,
/// `table` at α and r, checked by
/// [`bouncemap_engine::PreciseSetup::check_written`]).
pub fn job_written(
    kept: &bouncemap_engine::Written,
    settings: &[(&str, Option<&str>)],
    (table, alpha, r): (&bouncemap_engine::Table, f64, f64),
    ask: bouncemap_engine::DigitsAsk,
) -> Result<bouncemap_engine::Written, InputError> {
    let mut w = kept.clone();
    for (name, text) in settings {
        let Some(t) = text.map(str::trim) else {
            continue;
        };
        match t.split_once("..") {
            Some((a, b)) => {
                // A window, not a value (the flag's text as kept).
                if name.eq_ignore_ascii_case("alpha") {
                    w.alpha = None;
                } else if name.eq_ignore_ascii_case("r") {
                    w.r = None;
                }
                w.windows
                    .push((name.to_string(), a.trim().into(), b.trim().into()));
            }
            None if name.eq_ignore_ascii_case("alpha") => w.alpha = Some(t.into()),
            None if name.eq_ignore_ascii_case("r") => w.r = Some(t.into()),
            None => w.table.push((name.to_string(), t.into())),
        }
    }
    let setup = bouncemap_engine::PreciseSetup::new(table, alpha, r, 0.0, None, ask.binary);
    if let Some(setup) = setup {
        setup.as_written(&w).check_written().map_err(InputError)?;
    }
    Ok(w)
}
