//! What a value's orbit is, as the pictures colour it: period 1, 2, 4, 8, another
//! cycle, sticking, chaotic, or unresolved. The one place for the classes, their order,
//! their names and legend labels and how a sweep result or a pixel is classified (the
//! figures, the text pictures and the terminal application's period colours use these).
//!
//! A value is *sticking* when its points include a stick or a release, or its exponent
//! is −∞ (a stick–release cycle, a ball at rest); *chaotic* when it did not settle and
//! its largest exponent is positive (above [`CHAOS_FLOOR`]); *unresolved* when it did
//! not settle without a positive exponent (a long or slowly converging cycle, a torus)
//! or its exponent is not known.

use bouncemap_engine::attractors::{Kind, CHAOS_FLOOR};
use bouncemap_engine::plane::Pixel;
use bouncemap_engine::run::Outcome;
use bouncemap_engine::sweep::{ValueAttractor, ValueResult};

/// The class name of a pixel where the ball never lands (or rests): no class.
pub const NO_LANDING: &str = "no-landing";

/// The class of a value's orbit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Class {
    Period1,
    Period2,
    Period4,
    Period8,
    /// A cycle of another number of events.
    Periodic,
    Sticking,
    Chaotic,
    Unresolved,
}

impl Class {
    /// Every class, in legend order.
    pub const ALL: [Class; 8] = [
        Class::Period1,
        Class::Period2,
        Class::Period4,
        Class::Period8,
        Class::Periodic,
        Class::Sticking,
        Class::Chaotic,
        Class::Unresolved,
    ];

    /// Position in [`Self::ALL`].
    pub fn index(self) -> usize {
        Class::ALL.iter().position(|c| *c == self).unwrap_or(0)
    }

    /// Short legend label.
    pub fn label(self) -> &'static str {
        match self {
            Class::Period1 => "1",
            Class::Period2 => "2",
            Class::Period4 => "4",
            Class::Period8 => "8",
            Class::Periodic => "n",
            Class::Sticking => "stick",
            Class::Chaotic => "chaos",
            Class::Unresolved => "?",
        }
    }

    /// What the label means (help, README).
    pub fn describe(self) -> &'static str {
        match self {
            Class::Period1 => "period 1 (one impact per cycle)",
            Class::Period2 => "period 2",
            Class::Period4 => "period 4",
            Class::Period8 => "period 8",
            Class::Periodic => "another period",
            Class::Sticking => "sticks to the table (exponent -inf)",
            Class::Chaotic => "chaotic (largest exponent > 0)",
            Class::Unresolved => "not settled, no positive exponent",
        }
    }

    /// Name in files (`plane`'s class column).
    pub fn name(self) -> &'static str {
        match self {
            Class::Period1 => "period-1",
            Class::Period2 => "period-2",
            Class::Period4 => "period-4",
            Class::Period8 => "period-8",
            Class::Periodic => "periodic",
            Class::Sticking => "sticking",
            Class::Chaotic => "chaotic",
            Class::Unresolved => "unresolved",
        }
    }

    /// Its colour among the 256 of a terminal: the terminal application's period colour
    /// in 256-colour mode (a test keeps the two equal), for coloured text pictures.
    pub fn ansi256(self) -> u8 {
        match self {
            Class::Period1 => 51,
            Class::Period2 => 84,
            Class::Period4 => 226,
            Class::Period8 => 209,
            Class::Periodic => 111,
            Class::Sticking => 246,
            Class::Chaotic => 207,
            Class::Unresolved => 255,
        }
    }

    /// The class named `name` (as [`Self::name`] writes it).
    pub fn from_name(name: &str) -> Option<Class> {
        Class::ALL.into_iter().find(|c| c.name() == name)
    }

    fn of_cycle(events: usize) -> Class {
        match events {
            1 => Class::Period1,
            2 => Class::Period2,
            4 => Class::Period4,
            8 => Class::Period8,
            _ => Class::Periodic,
        }
    }
}

/// The class of a value (of its first start's orbit); None while it is provisional or
/// when the ball did not land.
pub fn of_value(r: &ValueResult) -> Option<Class> {
    of_outcome(&r.outcome, r.sticking, r.lyapunov)
}

/// The class of one pixel of a plane; None when the ball did not land.
pub fn of_pixel(p: &Pixel) -> Option<Class> {
    of_outcome(&p.outcome, p.sticking, p.lyapunov)
}

/// The class of an orbit that ended its transient with `outcome`, whose last events
/// include a stick or release (`sticking`), with largest exponent `lyapunov`.
pub fn of_outcome(outcome: &Outcome, sticking: bool, lyapunov: Option<f64>) -> Option<Class> {
    let sticks = sticking || lyapunov == Some(f64::NEG_INFINITY);
    match *outcome {
        Outcome::Running { .. } | Outcome::NoLanding { .. } => None,
        Outcome::Resting { .. } => Some(Class::Sticking),
        _ if sticks => Some(Class::Sticking),
        Outcome::Periodic { events, .. } => Some(Class::of_cycle(events)),
        Outcome::Unsettled => Some(match lyapunov {
            Some(l) if l > CHAOS_FLOOR => Class::Chaotic,
            _ => Class::Unresolved,
        }),
    }
}

/// The class of one attractor of a value with several starts.
pub fn of_attractor(a: &ValueAttractor) -> Option<Class> {
    match a.kind {
        Kind::Periodic => Some(Class::of_cycle(a.events.unwrap_or(0))),
        Kind::Sticking | Kind::Resting => Some(Class::Sticking),
        Kind::Chaotic => Some(Class::Chaotic),
        Kind::Unsettled => Some(Class::Unresolved),
        Kind::Escaping => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn value(outcome: Outcome, sticking: bool, lyapunov: Option<f64>) -> ValueResult {
        ValueResult {
            index: 0,
            value: 0.5,
            complete: true,
            points: Vec::new(),
            outcome,
            sticking,
            events: 0,
            lyapunov,
            attractors: Vec::new(),
        }
    }

    #[test]
    fn values_are_classified_by_cycle_sticking_and_exponent() {
        let p = |events| Outcome::Periodic {
            events,
            periods: events as i64,
            stopped_at: 0,
        };
        assert_eq!(
            of_value(&value(p(1), false, Some(-0.2))),
            Some(Class::Period1)
        );
        assert_eq!(of_value(&value(p(8), false, None)), Some(Class::Period8));
        assert_eq!(of_value(&value(p(3), false, None)), Some(Class::Periodic));
        // A stick–release cycle whose kept points happen to be impacts only.
        let inf = Some(f64::NEG_INFINITY);
        assert_eq!(of_value(&value(p(300), false, inf)), Some(Class::Sticking));
        assert_eq!(
            of_value(&value(Outcome::Unsettled, false, Some(0.1))),
            Some(Class::Chaotic)
        );
        assert_eq!(
            of_value(&value(Outcome::Unsettled, false, Some(-0.01))),
            Some(Class::Unresolved)
        );
        assert_eq!(
            of_value(&value(Outcome::Unsettled, true, None)),
            Some(Class::Sticking)
        );
        assert_eq!(
            of_value(&value(Outcome::Running { reached: 5 }, false, None)),
            None
        );
        for (i, c) in Class::ALL.iter().enumerate() {
            assert_eq!(c.index(), i);
        }
    }
}
