//! The parameters the user edits: table, D, α, r, k, initial state, sweep window,
//! transient and keep. Each row knows its valid range, its coarse and fine steps, and
//! how to parse a typed value; a refused value leaves everything unchanged and comes
//! back as a one-line message naming the valid range.

use crate::cli::DEFAULT_HOP;
use crate::engine::{State, System, Table};

/// The table shapes the table row cycles through.
#[derive(Clone, Debug, PartialEq)]
pub enum TableKind {
    Sine,
    /// F_D with the D row's value (quad = fd:0, cubic = fd:1).
    Fd,
    /// A table read from a file at start-up.
    File(String, Table),
}

/// Every editable value.
#[derive(Clone, Debug, PartialEq)]
pub struct Params {
    pub table: TableKind,
    pub d: f64,
    pub alpha: f64,
    pub r: f64,
    pub k: u32,
    pub t0: f64,
    /// None: f'(t0) + 0.5, the same default as `bouncemap orbit`.
    pub v0: Option<f64>,
    pub lo: f64,
    pub hi: f64,
    pub transient: u32,
    pub keep: u32,
    /// The table file given at start, if any (the table row can cycle back to it).
    pub file: Option<(String, Table)>,
}

impl Default for Params {
    fn default() -> Self {
        Params {
            table: TableKind::Fd,
            d: 0.1,
            alpha: 0.45,
            r: 0.8,
            k: 1,
            t0: 0.0,
            v0: None,
            lo: 0.1,
            hi: 0.7,
            transient: 2000,
            keep: 100,
            file: None,
        }
    }
}

/// One row of the parameters panel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ParamId {
    Table,
    D,
    Alpha,
    R,
    K,
    T0,
    V0,
    Lo,
    Hi,
    Transient,
    Keep,
}

/// What a change touches, so that only the affected work restarts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Touch {
    /// The system (table, α, r) or k: everything restarts.
    System,
    /// Only the initial state: the phase plot and the bounce panel.
    Start,
    /// Only the sweep (window, transient, keep).
    Sweep,
}

impl ParamId {
    pub const ALL: [ParamId; 11] = [
        ParamId::Table,
        ParamId::D,
        ParamId::Alpha,
        ParamId::R,
        ParamId::K,
        ParamId::T0,
        ParamId::V0,
        ParamId::Lo,
        ParamId::Hi,
        ParamId::Transient,
        ParamId::Keep,
    ];

    pub fn label(self) -> &'static str {
        match self {
            ParamId::Table => "table",
            ParamId::D => "D",
            ParamId::Alpha => "α",
            ParamId::R => "r",
            ParamId::K => "k",
            ParamId::T0 => "t̂0",
            ParamId::V0 => "v0",
            ParamId::Lo => "α from",
            ParamId::Hi => "α to",
            ParamId::Transient => "transient",
            ParamId::Keep => "keep",
        }
    }

    pub fn touches(self) -> Touch {
        match self {
            ParamId::Table | ParamId::D | ParamId::Alpha | ParamId::R | ParamId::K => Touch::System,
            ParamId::T0 | ParamId::V0 => Touch::Start,
            ParamId::Lo | ParamId::Hi | ParamId::Transient | ParamId::Keep => Touch::Sweep,
        }
    }

    /// The valid range, as shown in refusals.
    pub fn range(self) -> &'static str {
        match self {
            ParamId::Table => "sine, quad, cubic, fd:D or the file given at start",
            ParamId::D => "[0, 1]",
            ParamId::Alpha => "(0, 1000]",
            ParamId::R => "(0, 1)",
            ParamId::K => "a whole number in [1, 20]",
            ParamId::T0 => "[0, 1)",
            ParamId::V0 => "auto, or a number ≥ f'(t̂0) within [-1000, 1000]",
            ParamId::Lo => "(0, 1000] and below α to",
            ParamId::Hi => "(0, 1000] and above α from",
            ParamId::Transient => "a whole number in [0, 10000000]",
            ParamId::Keep => "a whole number in [1, 10000]",
        }
    }
}

impl Params {
    /// The table these parameters name.
    pub fn table(&self) -> Table {
        match &self.table {
            TableKind::Sine => Table::sine(),
            TableKind::Fd => Table::fd(self.d).unwrap_or_else(|_| Table::sine()),
            TableKind::File(_, t) => t.clone(),
        }
    }

    /// Short name of the table: sine, fd:0.1, or the file's name.
    pub fn table_label(&self) -> String {
        match &self.table {
            TableKind::Sine => "sine".into(),
            TableKind::Fd => format!("fd:{}", fmt_num(self.d)),
            TableKind::File(p, _) => p.clone(),
        }
    }

    /// The validated system. Every value is kept valid by the setters.
    pub fn system(&self) -> System {
        System::new(self.table(), self.alpha, self.r).expect("parameters are validated on entry")
    }

    /// The initial state, with the same default as `bouncemap orbit`.
    pub fn initial(&self, sys: &System) -> Result<State, String> {
        let v0 = self.v0.unwrap_or_else(|| sys.df(self.t0) + DEFAULT_HOP);
        State::launch(sys, 0, self.t0, v0, 0.0).map_err(|e| e.to_string())
    }

    /// The value of a row as displayed.
    pub fn show(&self, id: ParamId) -> String {
        match id {
            ParamId::Table => self.table_label(),
            ParamId::D => match self.table {
                TableKind::Fd => fmt_num(self.d),
                _ => "—".into(),
            },
            ParamId::Alpha => fmt_num(self.alpha),
            ParamId::R => fmt_num(self.r),
            ParamId::K => self.k.to_string(),
            ParamId::T0 => fmt_num(self.t0),
            ParamId::V0 => match self.v0 {
                Some(v) => fmt_num(v),
                None => "auto".into(),
            },
            ParamId::Lo => fmt_num(self.lo),
            ParamId::Hi => fmt_num(self.hi),
            ParamId::Transient => self.transient.to_string(),
            ParamId::Keep => self.keep.to_string(),
        }
    }

    /// Nudge a row by one coarse or fine step in direction `dir` (±1). Returns an
    /// error (and changes nothing) at the edge of the valid range.
    pub fn nudge(&mut self, id: ParamId, dir: i32, fine: bool) -> Result<(), String> {
        let s = dir.signum() as f64;
        let step = |coarse: f64, f: f64| if fine { f } else { coarse } * s;
        let mut next = self.clone();
        match id {
            ParamId::Table => {
                let order = self.table_order();
                let here = order
                    .iter()
                    .position(|t| kind_eq(t, &self.table))
                    .unwrap_or(0);
                let n = order.len() as i32;
                next.table = order[((here as i32 + dir).rem_euclid(n)) as usize].clone();
            }
            ParamId::D => next.d = round_to(self.d + step(0.1, 0.01), 1e-9),
            ParamId::Alpha => next.alpha = round_to(self.alpha + step(0.01, 0.001), 1e-9),
            ParamId::R => next.r = round_to(self.r + step(0.01, 0.001), 1e-9),
            ParamId::K => next.k = (self.k as i64 + dir as i64).max(0) as u32,
            ParamId::T0 => next.t0 = round_to(self.t0 + step(0.05, 0.005), 1e-9),
            ParamId::V0 => {
                let sys = self.system();
                let cur = self.v0.unwrap_or_else(|| sys.df(self.t0) + DEFAULT_HOP);
                next.v0 = Some(round_to(cur + step(0.1, 0.01), 1e-9));
            }
            ParamId::Lo => {
                let st = step((self.hi - self.lo) * 0.1, (self.hi - self.lo) * 0.01);
                next.lo = round_to(self.lo + st, 1e-9);
            }
            ParamId::Hi => {
                let st = step((self.hi - self.lo) * 0.1, (self.hi - self.lo) * 0.01);
                next.hi = round_to(self.hi + st, 1e-9);
            }
            ParamId::Transient => {
                next.transient = (self.transient as i64 + step(100.0, 10.0) as i64).max(-1) as u32
            }
            ParamId::Keep => next.keep = (self.keep as i64 + step(50.0, 10.0) as i64).max(0) as u32,
        }
        if id == ParamId::Transient && self.transient == 0 && dir < 0 {
            return Err(format!("transient: valid {}", id.range()));
        }
        next.validate(id)?;
        *self = next;
        Ok(())
    }

    /// Set a row from typed text. Refusals name the valid range; nothing changes then.
    pub fn set_text(&mut self, id: ParamId, text: &str) -> Result<(), String> {
        let t = text.trim();
        let mut next = self.clone();
        let num = || -> Result<f64, String> {
            match t.parse::<f64>() {
                Ok(x) if x.is_finite() => Ok(x),
                _ => Err(format!(
                    "{}: '{t}' is not a number; valid {}",
                    id.label(),
                    id.range()
                )),
            }
        };
        let whole = || -> Result<u32, String> {
            t.parse::<u32>().map_err(|_| {
                format!(
                    "{}: '{t}' is not a whole number; valid {}",
                    id.label(),
                    id.range()
                )
            })
        };
        match id {
            ParamId::Table => match t {
                "sine" => next.table = TableKind::Sine,
                "quad" => {
                    next.table = TableKind::Fd;
                    next.d = 0.0
                }
                "cubic" => {
                    next.table = TableKind::Fd;
                    next.d = 1.0
                }
                _ if t.starts_with("fd:") => {
                    let d = t[3..].trim().parse::<f64>().map_err(|_| {
                        format!("table: '{t}' has no number after fd:; valid {}", id.range())
                    })?;
                    next.table = TableKind::Fd;
                    next.d = d;
                    next.validate(ParamId::D)?;
                }
                _ => match &self.table_order().last() {
                    Some(TableKind::File(p, tb)) if p == t => {
                        next.table = TableKind::File(p.clone(), tb.clone())
                    }
                    _ => return Err(format!("table: '{t}' is not a table; valid {}", id.range())),
                },
            },
            ParamId::D => {
                next.d = num()?;
                if !matches!(next.table, TableKind::Fd) {
                    next.table = TableKind::Fd;
                }
            }
            ParamId::Alpha => next.alpha = num()?,
            ParamId::R => next.r = num()?,
            ParamId::K => next.k = whole()?,
            ParamId::T0 => next.t0 = num()?,
            ParamId::V0 => {
                next.v0 = if t == "auto" || t.is_empty() {
                    None
                } else {
                    Some(num()?)
                }
            }
            ParamId::Lo => next.lo = num()?,
            ParamId::Hi => next.hi = num()?,
            ParamId::Transient => next.transient = whole()?,
            ParamId::Keep => next.keep = whole()?,
        }
        next.validate(id)?;
        *self = next;
        Ok(())
    }

    /// Check the row `id` (and what depends on it) of a candidate parameter set.
    pub fn validate(&self, id: ParamId) -> Result<(), String> {
        let bad = |v: String| {
            Err(format!(
                "{}: {v} is out of range; valid {}",
                id.label(),
                id.range()
            ))
        };
        match id {
            ParamId::Table => {}
            ParamId::D if !(0.0..=1.0).contains(&self.d) => return bad(fmt_num(self.d)),
            ParamId::Alpha if crate::engine::system::check_alpha(self.alpha).is_err() => {
                return bad(fmt_num(self.alpha))
            }
            ParamId::R if crate::engine::system::check_r(self.r).is_err() => {
                return bad(fmt_num(self.r))
            }
            ParamId::K if !(1..=20).contains(&self.k) => return bad(self.k.to_string()),
            ParamId::T0 if !(0.0..1.0).contains(&self.t0) => return bad(fmt_num(self.t0)),
            ParamId::Lo | ParamId::Hi => {
                let ok = |x: f64| x > 0.0 && x <= 1000.0;
                if !(ok(self.lo) && ok(self.hi) && self.lo < self.hi) {
                    let v = if id == ParamId::Lo { self.lo } else { self.hi };
                    return bad(fmt_num(v));
                }
            }
            ParamId::Transient if self.transient > 10_000_000 => {
                return bad(self.transient.to_string())
            }
            ParamId::Keep if !(1..=10_000).contains(&self.keep) => {
                return bad(self.keep.to_string())
            }
            _ => {}
        }
        // The start must stay valid for the new system (v0 above the table's velocity).
        if matches!(id.touches(), Touch::System | Touch::Start) && id != ParamId::K {
            let sys = self.system();
            if let Err(e) = self.initial(&sys) {
                return Err(format!(
                    "{}: refused, the initial state would be invalid: {e}",
                    id.label()
                ));
            }
        }
        Ok(())
    }

    fn table_order(&self) -> Vec<TableKind> {
        let mut v = vec![TableKind::Sine, TableKind::Fd];
        if let Some((p, t)) = &self.file {
            v.push(TableKind::File(p.clone(), t.clone()));
        }
        v
    }
}

fn kind_eq(a: &TableKind, b: &TableKind) -> bool {
    std::mem::discriminant(a) == std::mem::discriminant(b)
}

fn round_to(x: f64, q: f64) -> f64 {
    (x / q).round() * q
}

/// A number with up to 6 significant decimals, trailing zeros trimmed.
pub fn fmt_num(x: f64) -> String {
    let s = format!("{x:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.to_string()
    }
}
