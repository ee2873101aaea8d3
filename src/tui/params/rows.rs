//! The rows of the parameters panel ([`ParamId`]: each one's rule, label, valid range
//! and what a change of it touches) and the diagram's start modes ([`StartMode`]).
//! The values themselves, and what a change checks, are [`super::Params`]'.

use crate::config::rules::{self, Rule};
use crate::config::table_spec::table_range;
use bouncemap_engine::sweep::Warm;

/// How every value of the diagram's sweep starts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StartMode {
    /// Next to the (1, 1) solution (the paper's start, `sweep --near-fixed-point`).
    NearFixedPoint,
    /// From t̂0, v0 (`sweep` without flags).
    Cold,
    /// Each value from its lower neighbour's final state (`sweep --warm`).
    Warm,
    /// Each value from its upper neighbour's final state (hysteresis with `Warm`).
    WarmBackward,
}

impl StartMode {
    pub const ALL: [StartMode; 4] = [
        StartMode::NearFixedPoint,
        StartMode::Cold,
        StartMode::Warm,
        StartMode::WarmBackward,
    ];

    /// How the row shows it.
    pub fn label(self) -> &'static str {
        match self {
            StartMode::NearFixedPoint => "near (1,1)",
            StartMode::Cold => "cold t̂0,v0",
            StartMode::Warm => "warm →",
            StartMode::WarmBackward => "warm ←",
        }
    }

    /// The name typed or written in the config file.
    pub fn key(self) -> &'static str {
        match self {
            StartMode::NearFixedPoint => "near-fixed-point",
            StartMode::Cold => "cold",
            StartMode::Warm => "warm",
            StartMode::WarmBackward => "warm-backward",
        }
    }

    /// The mode named `text`.
    pub fn parse(text: &str) -> Result<StartMode, String> {
        StartMode::ALL
            .into_iter()
            .find(|m| m.key() == text.trim())
            .ok_or_else(|| {
                format!(
                    "'{}' is not a start mode: valid {}",
                    text.trim(),
                    START_RANGE
                )
            })
    }

    /// Continuation along the sweep.
    pub fn warm(self) -> Warm {
        match self {
            StartMode::Warm => Warm::Forward,
            StartMode::WarmBackward => Warm::Backward,
            _ => Warm::Off,
        }
    }
}

const START_RANGE: &str = "near-fixed-point, cold, warm, warm-backward";

/// One row of the parameters panel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ParamId {
    Table,
    /// The i-th parameter of the table's family (F_D's D).
    Family(u8),
    Alpha,
    R,
    K,
    T0,
    V0,
    Sweep,
    Lo,
    Hi,
    Start,
    Transient,
    Keep,
    Values,
}

/// What a change touches, so that only the affected work restarts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Touch {
    /// The system (table, α, r) or k: everything restarts.
    System,
    /// Only the initial state: the phase plot and the bounce panel.
    Start,
    /// Only the sweep (swept parameter, window, start mode, transient, keep).
    Sweep,
}

impl ParamId {
    /// The rows after the table and its family's parameters.
    pub const SYSTEM: [ParamId; 12] = [
        ParamId::Alpha,
        ParamId::R,
        ParamId::K,
        ParamId::T0,
        ParamId::V0,
        ParamId::Sweep,
        ParamId::Lo,
        ParamId::Hi,
        ParamId::Start,
        ParamId::Transient,
        ParamId::Keep,
        ParamId::Values,
    ];

    /// The shared rule of a numeric row.
    pub fn rule(self) -> Option<Rule> {
        match self {
            ParamId::Alpha => Some(rules::ALPHA),
            ParamId::R => Some(rules::R),
            ParamId::K => Some(rules::K),
            ParamId::T0 => Some(rules::T0),
            ParamId::Transient => Some(rules::TRANSIENT),
            ParamId::Keep => Some(rules::KEEP),
            ParamId::Values => Some(rules::STEPS),
            ParamId::Table | ParamId::V0 | ParamId::Sweep | ParamId::Start => None,
            // A family parameter's range is the family's (see `Params::range_of`).
            ParamId::Family(_) => None,
            // The window's rule is the swept parameter's (see `Params::window_rule`).
            ParamId::Lo | ParamId::Hi => None,
        }
    }

    pub fn label(self) -> &'static str {
        match self {
            ParamId::Table => "table",
            ParamId::Sweep => "sweep",
            ParamId::Lo => " from",
            ParamId::Hi => " to",
            ParamId::Start => "start",
            ParamId::V0 => "v0",
            other => other.rule().map_or("", |r| r.label),
        }
    }

    pub fn touches(self) -> Touch {
        match self {
            ParamId::Table | ParamId::Family(_) | ParamId::Alpha | ParamId::R | ParamId::K => {
                Touch::System
            }
            ParamId::T0 | ParamId::V0 => Touch::Start,
            ParamId::Sweep
            | ParamId::Lo
            | ParamId::Hi
            | ParamId::Start
            | ParamId::Transient
            | ParamId::Keep
            | ParamId::Values => Touch::Sweep,
        }
    }

    /// The valid range, as shown in refusals.
    pub fn range(self) -> String {
        match self {
            ParamId::Table => format!("{} (a file is read when typed)", table_range()),
            ParamId::V0 => "auto, or a number ≥ f'(t̂0) with |v0 − f'(t̂0)| ≤ 1000".into(),
            ParamId::Sweep => "alpha, r, or a parameter of the table's family".into(),
            ParamId::Start => START_RANGE.into(),
            ParamId::Lo => "the swept parameter's range, below the window's end".into(),
            ParamId::Hi => "the swept parameter's range, above the window's start".into(),
            other => other
                .rule()
                .map_or(String::new(), |r| r.limit.text.to_string()),
        }
    }
}
