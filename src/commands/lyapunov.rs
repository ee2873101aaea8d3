//! `bouncemap lyapunov`: both Lyapunov exponents of one orbit, per impact and per table
//! period, with their convergence estimate, their sum beside 2 ln r, and what the orbit
//! settled on (see [`bouncemap_engine::attractors`]).
//!
//! The orbit runs to the end of the transient, stopping early once it has settled on a
//! cycle (the sweep's detector); a cycle's exponents come from the eigenvalues of its
//! Jacobian, any other orbit's from QR over `--impacts` more impacts.
//! `--no-early-stop` always measures by QR (a second method for a cycle's exponents).

use crate::config::flags::LyapunovArgs;
use crate::config::{self, InputError};
use crate::output::records::{csv_writer, InitialRecord, LyapunovDoc, LyapunovRow};
use crate::output::sink::Sink;
use crate::output::text::significant;
use crate::output::Format;
use bouncemap_engine::attractors::lyapunov::{Method, Spectrum};
use bouncemap_engine::attractors::{self, Found, Settle};
use bouncemap_engine::run::detect::Periodicity;
use bouncemap_engine::run::start::near_fixed_point;
use std::io::{self, Write};

pub fn run(args: &LyapunovArgs) -> anyhow::Result<()> {
    let sys = config::system(&args.system)?;
    let (start, initial) = if args.near_fixed_point {
        let s = near_fixed_point(&sys).ok_or_else(|| {
            InputError(format!(
                "--near-fixed-point: table {} at alpha = {} has no (1,1) solution to start next to (valid from the birth alpha that `bouncemap fixed` prints)",
                sys.table().name(),
                sys.alpha()
            ))
        })?;
        (s, InitialRecord::Named("near-fixed-point".into()))
    } else {
        let s = config::start(&sys, &args.initial)?;
        (
            s,
            InitialRecord::State {
                t0: args.initial.t0,
                v0: args.initial.v0,
                z0: args.initial.z0,
            },
        )
    };
    let settle = Settle {
        transient: args.transient,
        periodicity: (!args.no_early_stop).then(Periodicity::default),
        sample: args.impacts,
        solver: bouncemap_engine::Solver::Exact,
    };
    let (found, ..) = attractors::settle(&sys, start, &settle, 1, &mut |_| false)
        .expect("an uncancellable run finishes");
    let row = LyapunovRow::new(&found, sys.r());
    let mut out = Sink::stdout();
    let written = (|| -> anyhow::Result<()> {
        match args.format {
            Format::Json => {
                let doc = LyapunovDoc {
                    table: sys.table().name(),
                    alpha: sys.alpha(),
                    r: sys.r(),
                    start: initial,
                    transient: args.transient,
                    result: row,
                };
                serde_json::to_writer(&mut out, &doc)?;
                writeln!(out)?;
            }
            Format::Csv => {
                let mut w = csv_writer(&mut out, &LyapunovRow::HEADER)?;
                w.serialize(&row)?;
                w.flush()?;
            }
            Format::Text => text(&mut out, &sys, &found, args)?,
        }
        Ok(())
    })();
    out.end(written)
}

fn text(
    out: &mut impl Write,
    sys: &bouncemap_engine::System,
    found: &Found,
    args: &LyapunovArgs,
) -> io::Result<()> {
    writeln!(
        out,
        "table {}  alpha {}  r {}  transient {} periods",
        sys.table().name(),
        sys.alpha(),
        sys.r(),
        args.transient
    )?;
    let unresolved = found.precision.is_some_and(|p| !p.resolved);
    let period = match (found.events, found.periods) {
        // No cycle length is claimed where rounding decides it.
        _ if unresolved => String::new(),
        (Some(n), Some(k)) => format!(
            " ({n}, {k}): {n} event{} every {k} table period{}",
            if n == 1 { "" } else { "s" },
            if k == 1 { "" } else { "s" }
        ),
        _ => String::new(),
    };
    let kind = match found.kind {
        attractors::Kind::Converging => {
            "converging: periodic, period > 4096 events or transient too short (negative exponent, no cycle found)"
        }
        k => k.as_str(),
    };
    writeln!(out, "orbit: {kind}{period}")?;
    if let Some(p) = found.precision {
        writeln!(out, "cycle: {}", p.describe())?;
    }
    let two_ln_r = 2.0 * sys.r().ln();
    match found.spectrum {
        Some(Spectrum::Finite(e)) => {
            match e.method {
                Method::Cycle => writeln!(
                    out,
                    "exponents from the eigenvalues of the cycle's Jacobian (exact to the cycle's tolerance)"
                )?,
                Method::Qr => writeln!(
                    out,
                    "exponents by QR over {} impacts ({} table periods); ± one standard error over {} blocks",
                    e.impacts,
                    significant(e.periods, 6),
                    attractors::lyapunov::BLOCKS
                )?,
            }
            writeln!(out, "{:>10} {:>20} {:>20} {:>12}", "", "per impact", "per period", "±")?;
            for i in 0..2 {
                writeln!(
                    out,
                    "{:>10} {:>20} {:>20} {:>12}",
                    format!("lambda{}", i + 1),
                    significant(e.per_impact[i], 12),
                    significant(e.per_period[i], 12),
                    if e.method == Method::Qr {
                        significant(e.stderr[i], 2)
                    } else {
                        "0".into()
                    }
                )?;
            }
            writeln!(
                out,
                "{:>10} {:>20}   2 ln r = {}",
                "sum",
                significant(e.per_impact[0] + e.per_impact[1], 12),
                significant(two_ln_r, 12)
            )?;
        }
        Some(Spectrum::Sticking) => writeln!(
            out,
            "both exponents -inf: the ball sticks to the table, which forgets where it landed (superstable)"
        )?,
        Some(Spectrum::Grazing) => writeln!(
            out,
            "no exponents: a landing grazed the table (zero relative velocity), where the Jacobian is unbounded"
        )?,
        None => writeln!(out, "no exponents: the ball did not land")?,
    }
    Ok(())
}
