//! What a value's orbit is, as the pictures colour it: period 1, 2, 4, 8, another
//! cycle, sticking, chaotic, or unresolved. The one place for the classes, their order,
//! their names and legend labels and how a sweep result or a pixel is classified (the
//! figures, the text pictures and the terminal application's period colours use these).
//!
//! A value is *sticking* when its orbit sticks to the table in what it settled on (the
//! engine's one meaning: a stick–release cycle, a ball at rest, a stick among the kept
//! points or in the sample its exponent was measured on; exponent −∞), and *sticking
//! beyond double precision* when that is a cycle whose length rounding decides
//! ([`Precision`]); *chaotic* when it did not settle and its largest exponent is
//! positive (above [`CHAOS_FLOOR`]); *another period* when it settled on a cycle other
//! than 1, 2, 4, 8, or did not settle with a negative exponent (periodic, but longer
//! than the detectors or converging too slowly); *unresolved* when it did not settle
//! with an exponent zero within its error, or its exponent is not known.
//!
//! The palette is Okabe and Ito's, which stays apart for colour-blind readers, one
//! colour per class in the figures, the text pictures and the terminal application
//! alike ([`Class::rgb`], and [`Class::ansi256`] its nearest of 256).

use crate::model::Color;
use bouncemap_engine::attractors::{Kind, CHAOS_FLOOR};
use bouncemap_engine::plane::Pixel;
use bouncemap_engine::run::precision::Precision;
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
    /// A sticking cycle whose length is beyond double precision.
    StickingUnresolved,
    Chaotic,
    Unresolved,
}

impl Class {
    /// Every class, in legend order.
    pub const ALL: [Class; 9] = [
        Class::Period1,
        Class::Period2,
        Class::Period4,
        Class::Period8,
        Class::Periodic,
        Class::Sticking,
        Class::StickingUnresolved,
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
            Class::StickingUnresolved => "stick?",
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
            Class::Periodic => "another period (or longer than 4096 events: exponent < 0)",
            Class::Sticking => "sticks to the table (exponent -inf)",
            Class::StickingUnresolved => "sticks; cycle length beyond double precision",
            Class::Chaotic => "chaotic (largest exponent > 0)",
            Class::Unresolved => "not settled, exponent zero within its error",
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
            Class::StickingUnresolved => "sticking-unresolved",
            Class::Chaotic => "chaotic",
            Class::Unresolved => "unresolved",
        }
    }

    /// Its colour, the same in the figures (white paper), the text pictures and the
    /// terminal (a dark background): Okabe and Ito's palette, which stays apart for
    /// colour-blind readers, with the hues that vanish on one of the two backgrounds
    /// (black, yellow) replaced by a dark grey and a dark yellow legible on both.
    pub fn rgb(self) -> (u8, u8, u8) {
        match self {
            Class::Period1 => (86, 180, 233),             // sky blue
            Class::Period2 => (230, 159, 0),              // orange
            Class::Period4 => (0, 158, 115),              // bluish green
            Class::Period8 => (213, 94, 0),               // vermillion
            Class::Periodic => (204, 121, 167),           // reddish purple
            Class::Sticking => (30, 130, 210),            // blue
            Class::StickingUnresolved => (140, 180, 220), // pale blue
            Class::Chaotic => (105, 105, 105),            // grey
            Class::Unresolved => (190, 170, 0),           // dark yellow
        }
    }

    /// Its colour among the 256 of a terminal: the nearest of the xterm colour cube and
    /// grey ramp to [`Self::rgb`] (the terminal application's 256-colour mode and the
    /// coloured text pictures).
    pub fn ansi256(self) -> u8 {
        nearest_xterm(self.rgb())
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

/// The index in the xterm 256-colour palette nearest to `rgb` (its 6 × 6 × 6 cube and
/// 24 greys; the 16 system colours vary between terminals and are left out).
pub fn nearest_xterm((r, g, b): (u8, u8, u8)) -> u8 {
    const LEVELS: [i32; 6] = [0, 95, 135, 175, 215, 255];
    let near = |x: u8| {
        (0..6)
            .min_by_key(|&i| (LEVELS[i] - i32::from(x)).abs())
            .unwrap_or(0)
    };
    let (i, j, k) = (near(r), near(g), near(b));
    let cube = (LEVELS[i], LEVELS[j], LEVELS[k]);
    let grey_level = ((i32::from(r) + i32::from(g) + i32::from(b)) / 3 - 8).clamp(0, 230) / 10;
    let grey = 8 + 10 * grey_level;
    let dist = |(x, y, z): (i32, i32, i32)| {
        (x - i32::from(r)).pow(2) + (y - i32::from(g)).pow(2) + (z - i32::from(b)).pow(2)
    };
    if dist((grey, grey, grey)) < dist(cube) {
        (232 + grey_level) as u8
    } else {
        (16 + 36 * i + 6 * j + k) as u8
    }
}

/// The class of a value (of its first start's orbit); None while it is provisional or
/// when the ball did not land.
pub fn of_value(r: &ValueResult) -> Option<Class> {
    with_precision(of_outcome(&r.outcome, r.sticking, r.lyapunov), r.precision)
}

/// A sticking class made "stick?" where double precision cannot decide the cycle.
fn with_precision(class: Option<Class>, precision: Option<Precision>) -> Option<Class> {
    match class {
        Some(Class::Sticking) if unresolved(precision) => Some(Class::StickingUnresolved),
        _ => class,
    }
}

/// Whether a result's cycle is out of reach of double precision.
pub fn unresolved(precision: Option<Precision>) -> bool {
    precision.is_some_and(|p| !p.resolved)
}

/// The class of one pixel of a plane; None when the ball did not land.
pub fn of_pixel(p: &Pixel) -> Option<Class> {
    with_precision(of_outcome(&p.outcome, p.sticking, p.lyapunov), p.precision)
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
            Some(l) if l < -CHAOS_FLOOR => Class::Periodic,
            _ => Class::Unresolved,
        }),
    }
}

/// The class of one attractor of a value with several starts.
pub fn of_attractor(a: &ValueAttractor) -> Option<Class> {
    match a.kind {
        Kind::Periodic => Some(Class::of_cycle(a.events.unwrap_or(0))),
        Kind::Sticking if unresolved(a.precision) => Some(Class::StickingUnresolved),
        Kind::Sticking | Kind::Resting => Some(Class::Sticking),
        Kind::Chaotic => Some(Class::Chaotic),
        Kind::Converging => Some(Class::Periodic),
        Kind::Unsettled => Some(Class::Unresolved),
        Kind::Escaping => None,
    }
}

/// Colours of attractors 1, 2, … (repeated beyond the list), chosen to stay apart in
/// print and for the common colour-vision deficiencies.
pub const PALETTE: [Color; 8] = [
    Color(31, 89, 180),
    Color(230, 120, 20),
    Color(44, 150, 44),
    Color(204, 37, 41),
    Color(140, 86, 180),
    Color(140, 90, 60),
    Color(220, 110, 180),
    Color(120, 160, 200),
];

/// Starts that come to rest or escape: not an attractor of their own.
pub const REST: Color = Color(200, 200, 200);

/// The colour of attractor number `n` (1-based).
pub fn attractor_colour(n: usize) -> Color {
    PALETTE[(n.max(1) - 1) % PALETTE.len()]
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
            precision: None,
            cycle: None,
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
            Some(Class::Periodic)
        );
        assert_eq!(
            of_value(&value(Outcome::Unsettled, false, Some(-1e-4))),
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

#[cfg(test)]
mod palette {
    use super::*;

    #[test]
    fn the_nearest_xterm_colours_are_the_cube_and_grey_entries() {
        // Exact cube and grey entries map to themselves.
        assert_eq!(nearest_xterm((0, 0, 0)), 16);
        assert_eq!(nearest_xterm((255, 255, 255)), 231);
        assert_eq!(nearest_xterm((0, 135, 215)), 32);
        assert_eq!(nearest_xterm((128, 128, 128)), 244);
    }

    #[test]
    fn every_class_has_its_own_colour_on_both_backgrounds() {
        for (i, a) in Class::ALL.iter().enumerate() {
            for b in &Class::ALL[i + 1..] {
                assert_ne!(a.rgb(), b.rgb(), "{a:?} {b:?}");
                assert_ne!(a.ansi256(), b.ansi256(), "{a:?} {b:?}");
            }
            // Not the axes' grey of the terminal (245) nor its neighbours.
            assert!(!(243..=247).contains(&a.ansi256()), "{a:?}");
        }
    }
}
