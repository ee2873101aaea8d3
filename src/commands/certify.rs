//! `bouncemap certify`: a proof by interval arithmetic of one (n, k) cycle (the engine's
//! [`bouncemap_engine::orbits::certify`]): an exact cycle in a small box and no other
//! there, each landing its flight's first contact, and its stability where the
//! enclosure of its multipliers decides it; or why not.
//!
//! The guess is `--t0 --v0`; without them, the stable (1, k) solution for n = 1, and
//! for n > 1 the state where the orbit from next to the (1, 1) solution is after
//! [`SETTLE_EVENTS`] events (on an attracting (n, k) cycle, a launch of it).
//!
//! text: the statement, the box, the multipliers and the stability; csv: a row per
//! impact of the box; json: all of it. A cycle not proved is an answer, not an error:
//! the verdict says `not_proved` and why, and the exit status is 0.

use crate::config::flags::CertifyArgs;
use crate::config::{self, InputError};
use crate::output::records::{
    csv_writer, failure_text, near_name, stability_name, CertifyDoc, CertifyRow,
};
use crate::output::sink::Sink;
use crate::output::text::interval as iv;
use crate::output::Format;
use bouncemap_engine::orbits::certify::{
    certify, Certificate, Multipliers, Near, StabilityVerdict,
};
use bouncemap_engine::orbits::{fixed_points, Classification};
use bouncemap_engine::run::start::near_fixed_point;
use bouncemap_engine::{EventKind, ImpactMap, Solver, State, System};
use std::io::Write;

/// Events the orbit from next to the (1, 1) solution runs before its state is the
/// guess of a cycle of more than one impact.
pub const SETTLE_EVENTS: usize = 20_000;

pub fn run(args: &CertifyArgs) -> anyhow::Result<()> {
    let sys = config::system(&args.system)?;
    let (t0, v0) = match args.t0.zip(args.v0) {
        Some(g) => g,
        None => default_guess(&sys, args.n, args.k)?,
    };
    let cert = certify(&sys, args.n, args.k, t0, v0);
    let mut out = Sink::open(args.output.out.as_deref()).map_err(InputError)?;
    let name = sys.table().name();
    let written = (|| -> anyhow::Result<()> {
        match args.format {
            Format::Json => {
                let doc = CertifyDoc::of(name, sys.alpha(), sys.r(), [t0, v0], &cert);
                serde_json::to_writer(&mut out, &doc)?;
                writeln!(out)?;
            }
            Format::Csv => {
                let mut w = csv_writer(&mut out, &CertifyRow::HEADER)?;
                for row in CertifyRow::rows(name, sys.alpha(), sys.r(), &cert) {
                    w.serialize(row)?;
                }
                w.flush()?;
            }
            Format::Text => write_text(&mut out, &sys, (t0, v0), &cert)?,
        }
        Ok(())
    })();
    out.end(written)
}

/// The guess when none is given (see the module's header).
fn default_guess(sys: &System, n: usize, k: u32) -> Result<(f64, f64), InputError> {
    let none = || {
        InputError(format!(
            "no guess for a ({n}, {k}) cycle at alpha {}: valid a launch near one by --t0 PHASE --v0 V (from `bouncemap continue` or `bouncemap orbit`)",
            sys.alpha()
        ))
    };
    if n == 1 {
        let fps = fixed_points(sys, k).map_err(InputError::from)?;
        let rank = |c: Classification| match c {
            Classification::Stable => 0,
            Classification::UnstablePeriodDoubling => 1,
            Classification::UnstableSaddle => 2,
            Classification::NotAdmissible => 3,
        };
        return fps
            .iter()
            .filter(|p| p.classification != Classification::NotAdmissible)
            .min_by_key(|p| rank(p.classification))
            .map(|p| (p.phase, p.v))
            .ok_or_else(none);
    }
    let start = near_fixed_point(sys)
        .or_else(|| State::start(sys, 0.0, None, 0.0).ok())
        .ok_or_else(none)?;
    let mut map = ImpactMap::new(sys.clone(), Solver::Exact, start);
    let mut last = None;
    for _ in 0..SETTLE_EVENTS {
        match map.step() {
            Ok(e) => last = Some(e.kind),
            Err(_) => return Err(none()),
        }
    }
    match last {
        Some(EventKind::Impact) => Ok((map.state().phase(), map.state().v())),
        _ => Err(none()),
    }
}

fn write_text(
    out: &mut impl Write,
    sys: &System,
    (t0, v0): (f64, f64),
    c: &Certificate,
) -> std::io::Result<()> {
    let (n, k) = (c.n, c.k);
    writeln!(
        out,
        "certify the ({n}, {k}) cycle of {} at alpha {}, r {} from the guess t̂0 = {t0}, v0 = {v0}",
        sys.table().name(),
        sys.alpha(),
        sys.r()
    )?;
    writeln!(
        out,
        "  for every alpha in {} and r in {} (the decimals as written and their doubles; the table's coefficients likewise)",
        iv(c.alpha),
        iv(c.r)
    )?;
    match (&c.failure, &c.enclosure) {
        (None, Some(e)) => writeln!(
            out,
            "  verdict: proved: exactly one ({n}, {k}) cycle of the impact map lies in the box below (Krawczyk test on a box of relative half-width {:.1e}), and each of its landings is its flight's first contact with the table",
            e.inflation
        )?,
        (Some(f), _) => writeln!(out, "  verdict: not proved: {}", failure_text(c, f))?,
        (None, None) => writeln!(out, "  verdict: not proved")?,
    }
    if let Some(e) = &c.enclosure {
        writeln!(
            out,
            "  {:>6}  {:<34}  {:<34}  |u| at the next landing",
            "impact", "phase t̂", "launch velocity v"
        )?;
        for i in 0..n {
            writeln!(
                out,
                "  {:>6}  {:<34}  {:<34}  {}",
                i,
                iv(e.phases[i]),
                iv(e.velocities[i]),
                c.flights
                    .get(i)
                    .map(|f| iv(f.impact_speed))
                    .unwrap_or_default()
            )?;
        }
        writeln!(out, "  box width {:.2e}", e.width)?;
    }
    if let Some(s) = &c.stability {
        match s.multipliers {
            Multipliers::Real([a, b]) => {
                writeln!(out, "  multipliers: real, {} and {}", iv(a), iv(b))?
            }
            Multipliers::Complex { re, im } => writeln!(
                out,
                "  multipliers: a complex pair re ± i·im, re = {}, im = {}",
                iv(re),
                iv(im)
            )?,
            Multipliers::Unresolved { re, spread } => writeln!(
                out,
                "  multipliers: within {:.3e} of {} (real or complex not decided)",
                spread,
                iv(re)
            )?,
        }
        let tests = format!(
            "1 + tr M + det M = {}, 1 − tr M + det M = {}",
            iv(s.pd_test()),
            iv(s.fold_test())
        );
        match s.verdict {
            StabilityVerdict::Stable => writeln!(
                out,
                "  stability: proved stable (both multipliers inside the unit circle: {tests}, both positive)"
            )?,
            StabilityVerdict::Unstable => writeln!(
                out,
                "  stability: proved unstable (a multiplier outside the unit circle: {tests}, one negative)"
            )?,
            StabilityVerdict::Undecided { near } => {
                let (test, at) = match near {
                    Near::PeriodDoubling => (s.pd_test(), "−1: a period doubling is this close"),
                    Near::Fold => (s.fold_test(), "+1: a fold is this close"),
                };
                writeln!(
                    out,
                    "  stability: {}, not proved: {tests}; the {} test's enclosure contains 0 (a multiplier within about {:.1e} of {at})",
                    stability_name(&s.verdict),
                    near_name(near).replace('_', " "),
                    test.width()
                )?
            }
        }
    }
    Ok(())
}
