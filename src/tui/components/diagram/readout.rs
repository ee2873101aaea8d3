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

/// What a value's orbit does, in words.
pub fn status(r: &ValueResult) -> String {
    let class = classes::of_value(r);
    match (r.outcome, class) {
        (Outcome::Running { .. }, _) => "running".into(),
        (Outcome::NoLanding { .. }, _) => "no landing".into(),
        (Outcome::Resting { .. }, _) => "resting".into(),
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
        (Outcome::Unsettled, _) => "unsettled".into(),
    }
}

/// The readout text.
pub fn text(d: &Diagram, app: &Shared) -> String {
    let sym = Params::symbol(app.params.param);
    let nearest = d.slots.iter().flatten().min_by(|a, b| {
        (a.value - d.cursor)
            .abs()
            .total_cmp(&(b.value - d.cursor).abs())
    });
    let what = nearest.map_or(String::new(), |r| {
        let l = match r.lyapunov {
            Some(x) if x == f64::NEG_INFINITY => " λ=-inf".to_string(),
            Some(x) => format!(" λ={}", fmt_num((x * 1e4).round() / 1e4)),
            None => String::new(),
        };
        format!(" {}{l}", status(r))
    });
    let axis = match d.axis {
        Axis::Phase => "t̂",
        Axis::Velocity => "v",
    };
    let mark = d.mark.map_or(String::new(), |(m, _)| {
        format!(" · mark {sym}={}", fmt_num(m))
    });
    format!(
        " {sym}={}{what} · {axis}={}{mark} ",
        fmt_num(d.cursor),
        fmt_num(d.ycursor)
    )
}
