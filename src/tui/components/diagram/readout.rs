//! The cursor readout in the diagram's top border: the swept parameter at the cursor,
//! what the value nearest to it does (its class of orbit with (n, k), its largest
//! exponent), the height under the cursor, and the first corner of a window being
//! marked.

use super::{Axis, Diagram};
use crate::output::classes::{self, Class};
use crate::tui::components::Shared;
use crate::tui::params::{fmt_num, Params};
use bouncemap_engine::run::Outcome;
use bouncemap_engine::sweep::ValueResult;

/// What a value's orbit does, in words (no cycle length where double precision cannot
/// decide it).
pub fn status(r: &ValueResult) -> String {
    let class = classes::of_value(r);
    match (r.outcome, class) {
        (Outcome::Running { .. }, _) => "running".into(),
        (Outcome::NoLanding { .. }, _) => "no landing".into(),
        (Outcome::Resting { .. }, _) => "resting".into(),
        (_, Some(Class::StickingUnresolved)) => "sticking, length beyond f64".into(),
        (
            Outcome::Periodic {
                events, periods, ..
            },
            Some(Class::Sticking),
        ) => {
            format!("sticking ({events},{periods})")
        }
        (
            Outcome::Periodic {
                events, periods, ..
            },
            _,
        ) => format!("periodic ({events},{periods})"),
        (Outcome::Unsettled, Some(Class::Sticking)) => "sticking".into(),
        (Outcome::Unsettled, Some(Class::Chaotic)) => "chaotic".into(),
        (Outcome::Unsettled, Some(Class::Periodic)) => "converging (λ<0, no cycle ≤ 4096)".into(),
        (Outcome::Unsettled, _) => "unsettled".into(),
    }
}

/// The value nearest the cursor, if any has arrived.
pub fn nearest(d: &Diagram) -> Option<&ValueResult> {
    d.slots.iter().flatten().min_by(|a, b| {
        (a.value - d.cursor)
            .abs()
            .total_cmp(&(b.value - d.cursor).abs())
    })
}

/// What the value nearest the cursor settled on, with the evidence for it: its status
/// and, for a cycle, whether double precision decides it.
pub fn evidence(d: &Diagram, app: &Shared) -> Option<String> {
    let r = nearest(d)?;
    let sym = Params::symbol(app.params.param);
    let verdict = match r.precision {
        Some(p) if !p.resolved => format!(
            " (growth 10^{:.0} over {} impacts)",
            p.growth_decades, p.impacts
        ),
        Some(p) if p.impacts > 0 => format!(", resolved (growth 10^{:.1})", p.growth_decades),
        Some(_) => ", resolved (converges)".into(),
        None => String::new(),
    };
    Some(format!(
        "{sym} {}: {}{verdict}",
        fmt_num(r.value),
        status(r)
    ))
}

/// The readout's parts, most important first: the value under the cursor (the
/// nearest value's own parameter, the one its status is of, as the stability panel
/// says it) with what it does, its exponent, the height under the cursor and the mark.
/// A narrow panel drops parts from the end, never the orbit's class.
pub fn parts(d: &Diagram, app: &Shared) -> Vec<String> {
    let sym = Params::symbol(app.params.param);
    let mut out = Vec::new();
    match nearest(d) {
        Some(r) => {
            out.push(format!("{sym}={} {}", fmt_num(r.value), status(r)));
            if let Some(x) = r.lyapunov {
                out.push(if x == f64::NEG_INFINITY {
                    "λ=-inf".to_string()
                } else {
                    format!("λ={}", fmt_num((x * 1e4).round() / 1e4))
                });
            }
        }
        None => out.push(format!("{sym}={}", fmt_num(d.cursor))),
    }
    let axis = match d.axis {
        Axis::Phase => "t̂",
        Axis::Velocity => "v",
    };
    out.push(format!("· {axis}={}", fmt_num(d.ycursor)));
    if let Some((m, _)) = d.mark {
        out.push(format!("· mark {sym}={}", fmt_num(m)));
    }
    out
}

/// The readout in at most `width` columns: as many of [`parts`] as fit, in order (the
/// first is cut with an ellipsis only if it alone does not fit).
pub fn text(d: &Diagram, app: &Shared, width: usize) -> String {
    let w = |s: &str| ratatui::text::Line::from(s).width();
    let mut out = String::from(" ");
    for (i, p) in parts(d, app).into_iter().enumerate() {
        let sep = if i == 0 { "" } else { " " };
        if w(&out) + w(sep) + w(&p) + 1 > width {
            if i == 0 {
                return super::fit(&format!(" {p} "), width);
            }
            break;
        }
        out.push_str(sep);
        out.push_str(&p);
    }
    out.push(' ');
    out
}
