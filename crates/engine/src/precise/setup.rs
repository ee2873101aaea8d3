//! A system and a start at any precision from the doubles a run was given
//! ([`PreciseSetup`]), what a run at any precision is asked for ([`DigitsAsk`]), and the
//! sticking cycle of one start decided for a job's value, pixel or attractor
//! ([`decide_sticking_cycle`]).
//!
//! Parameters are taken as written: each double is read back as its shortest decimal
//! (what was typed, unless it had more than 17 significant digits), or the text typed
//! where the caller kept it ([`Written`]: every digit of it, for α, r, the start and the
//! table's parameters), and rounded once to the
//! working precision, so α = 0.6 is three fifths; or, asked for, as the double
//! itself. A value of a job's grid (a sweep's or a plane's axis) is the decimal grid
//! point lo + (hi − lo)·i/(N − 1) of the window's ends as typed ([`Written::windows`];
//! else their doubles' shortest decimals), not the double the f64 run used (0.5975, not
//! 0.5974999999999999). [`PreciseSetup::check_written`] refuses a text outside its
//! range whose double is inside.

use super::digits::{sticking_cycle_to_digits, CycleVerdict, DigitsProgress, PATH_EVENTS};
use super::{precise_takes, PreciseState, PreciseSystem};
use crate::error::EngineError;
use crate::limits;
use crate::map::State;
use crate::real::{Big, Number, Real};
use crate::system::System;
use crate::table::{Family, Table};
use std::ops::ControlFlow;
use std::sync::Arc;

/// What a run at any precision is asked for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DigitsAsk {
    /// Significant digits the answer must hold to.
    pub digits: u32,
    /// The most digits the precision is raised to.
    pub max_digits: u32,
    /// Each parameter the double it was read to, exactly (not its shortest decimal).
    pub binary: bool,
}

/// The decimal texts typed for a run's parameters and start, where they were typed
/// (None: the double's shortest decimal stands for it): at any precision each is read
/// as written, all its digits, rather than through its double.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Written {
    /// α.
    pub alpha: Option<String>,
    /// r.
    pub r: Option<String>,
    /// The start's phase, velocity and height.
    pub t0: Option<String>,
    /// See `t0`.
    pub v0: Option<String>,
    /// See `t0`.
    pub z0: Option<String>,
    /// The table's parameters (name, text) as the table's name gave them (`fd:D`,
    /// `PATH.toml:w=...`).
    pub table: Vec<(String, String)>,
    /// The windows of a job's axes (parameter name, low end, high end), as typed
    /// (`--alpha 0.58..0.59`, `--x alpha:0.58..0.59`): a grid point is lo + (hi − lo)·i/
    /// (N − 1) of these decimals.
    pub windows: Vec<(String, String, String)>,
}

/// One parameter at any precision: a double, a decimal text, or a point of a job's
/// grid.
#[derive(Clone, Debug, PartialEq)]
enum Value {
    /// Its shortest decimal, or the double itself.
    Double(f64),
    /// The decimal text typed, or (`binary`) the double it was read to.
    Text { text: String, double: f64 },
    /// lo + (hi − lo)·i/(steps − 1) of the decimals lo and hi; `double` is the grid's
    /// double (what the f64 run used).
    Grid {
        lo: f64,
        hi: f64,
        i: usize,
        steps: usize,
        double: f64,
        /// The ends as typed, where they were (every digit).
        typed: Option<(String, String)>,
    },
}

impl Value {
    /// The value at `bits`: as written, or (`binary`) the double.
    fn at(&self, bits: usize, binary: bool) -> Big {
        let decimal = |x: f64| Big::from_decimal(&format!("{x}"), &bits).expect("a finite decimal");
        match (self, binary) {
            (
                Value::Double(x) | Value::Grid { double: x, .. } | Value::Text { double: x, .. },
                true,
            ) => Big::from_f64(*x, &bits),
            (Value::Double(x), false) => decimal(*x),
            (Value::Text { text, double }, false) => {
                Big::from_decimal(text, &bits).unwrap_or_else(|| decimal(*double))
            }
            (
                Value::Grid {
                    lo,
                    hi,
                    i,
                    steps,
                    typed,
                    ..
                },
                false,
            ) => {
                let text =
                    |t: &str, x: f64| Big::from_decimal(t, &bits).unwrap_or_else(|| decimal(x));
                let (lo, hi) = match typed {
                    Some((a, b)) => (text(a, *lo), text(b, *hi)),
                    None => (decimal(*lo), decimal(*hi)),
                };
                if *steps <= 1 || *i == 0 {
                    return lo;
                }
                let n = Big::from_f64((steps - 1) as f64, &bits);
                let i = Big::from_f64(*i as f64, &bits);
                lo.clone() + (hi - lo) * i / n
            }
        }
    }

    /// The double `x` as `text` wrote it, where the text reads back to `x` (it is that
    /// flag's text); else the double alone.
    fn written(x: f64, text: Option<&String>) -> Value {
        match text {
            Some(t) if t.trim().parse::<f64>() == Ok(x) => Value::Text {
                text: t.trim().to_string(),
                double: x,
            },
            _ => Value::Double(x),
        }
    }

    fn double(&self) -> f64 {
        match self {
            Value::Double(x) | Value::Text { double: x, .. } | Value::Grid { double: x, .. } => *x,
        }
    }
}

/// Which parameter of a [`PreciseSetup`] a value sets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Slot<'a> {
    /// α.
    Alpha,
    /// r.
    R,
    /// The table family's parameter of this name.
    Table(&'a str),
}

/// A system and a start at any precision, from doubles.
#[derive(Clone, Debug)]
pub struct PreciseSetup {
    family: Arc<Family>,
    params: Vec<Value>,
    alpha: Value,
    r: Value,
    t0: Value,
    /// None: launched with [`crate::DEFAULT_HOP`] relative to the table.
    v0: Option<Value>,
    /// Height above the table at the start.
    z0: Value,
    binary: bool,
    sine: bool,
    /// Windows as typed (see [`Written::windows`]), for [`PreciseSetup::on_grid`].
    windows: Vec<(String, String, String)>,
}

impl PreciseSetup {
    /// The system of `table`, α and r with a ball launched from the table at phase `t0`
    /// with velocity `v0` (None: [`crate::DEFAULT_HOP`] relative to the table). None
    /// where the map at any precision does not take the table ([`precise_takes`]).
    pub fn new(
        table: &Table,
        alpha: f64,
        r: f64,
        t0: f64,
        v0: Option<f64>,
        binary: bool,
    ) -> Option<PreciseSetup> {
        if !precise_takes(table) {
            return None;
        }
        let (family, params) = table.family()?;
        Some(PreciseSetup {
            sine: Arc::ptr_eq(family, Family::sine()),
            family: family.clone(),
            params: params.iter().map(|&x| Value::Double(x)).collect(),
            alpha: Value::Double(alpha),
            r: Value::Double(r),
            t0: Value::Double(t0),
            v0: v0.map(Value::Double),
            z0: Value::Double(0.0),
            binary,
            windows: Vec::new(),
        })
    }

    /// This setup with the ball starting `z0` ≥ 0 above the table.
    pub fn above(mut self, z0: f64) -> PreciseSetup {
        self.z0 = Value::Double(z0);
        self
    }

    /// α or r (a [`Slot`] of the system's own) as this setup reads it, as a decimal: the
    /// text typed, else (and with the doubles asked for) the double's shortest decimal.
    pub fn decimal(&self, slot: Slot<'_>) -> String {
        let v = match slot {
            Slot::Alpha => &self.alpha,
            Slot::R => &self.r,
            Slot::Table(name) => match self.family.param_index(name) {
                Some(k) => &self.params[k],
                None => return String::new(),
            },
        };
        match v {
            Value::Text { text, .. } if !self.binary => text.clone(),
            other => format!("{}", other.double()),
        }
    }

    /// This setup with each value that `texts` has as typed (and that reads back to
    /// the double the setup has) taken as written.
    pub fn as_written(mut self, texts: &Written) -> PreciseSetup {
        self.alpha = Value::written(self.alpha.double(), texts.alpha.as_ref());
        self.r = Value::written(self.r.double(), texts.r.as_ref());
        self.t0 = Value::written(self.t0.double(), texts.t0.as_ref());
        self.v0 = self
            .v0
            .take()
            .map(|v| Value::written(v.double(), texts.v0.as_ref()));
        self.z0 = Value::written(self.z0.double(), texts.z0.as_ref());
        for (name, text) in &texts.table {
            if let Some(k) = self.family.param_index(name) {
                self.params[k] = Value::written(self.params[k].double(), Some(text));
            }
        }
        self.windows = texts.windows.clone();
        self
    }

    /// Whether every parameter typed lies in its range as written, not only as the
    /// double it was read to (a decimal just above a closed range's end, such as D =
    /// 1.000000000000000000001, rounds to the end): the first that does not, named
    /// with its valid range. With the doubles asked for, nothing to check.
    pub fn check_written(&self) -> Result<(), String> {
        if self.binary {
            return Ok(());
        }
        // (name, low, high, low open, high open, range text)
        type Range = (String, f64, f64, bool, bool, String);
        let limit = |l: &crate::limits::Limit| -> Range {
            (
                l.name.to_string(),
                l.lo,
                l.hi,
                l.lo_open,
                l.hi_open,
                l.text.to_string(),
            )
        };
        let mut slots: Vec<(&Value, Range)> = vec![
            (&self.alpha, limit(&limits::ALPHA)),
            (&self.r, limit(&limits::R)),
            (&self.t0, limit(&limits::PHASE)),
            (&self.z0, limit(&limits::HEIGHT)),
        ];
        if let Some(v0) = &self.v0 {
            slots.push((v0, limit(&limits::VELOCITY)));
        }
        for (p, v) in self.family.params().iter().zip(&self.params) {
            let (lo, hi) = p.range();
            slots.push((
                v,
                (p.name().to_string(), lo, hi, false, false, p.range_text()),
            ));
        }
        // The ends of the windows typed, each against its parameter's range.
        let ends: Vec<(Value, Range)> = self
            .windows
            .iter()
            .flat_map(|(name, a, b)| {
                let range = slots
                    .iter()
                    .map(|(_, r)| r)
                    .find(|r| r.0.eq_ignore_ascii_case(name))
                    .cloned();
                [a, b].into_iter().filter_map(move |t| {
                    let double = t.trim().parse::<f64>().ok()?;
                    let text = t.trim().to_string();
                    Some((Value::Text { text, double }, range.clone()?))
                })
            })
            .collect();
        slots.extend(ends.iter().map(|(v, r)| (v, r.clone())));
        for (v, (name, lo, hi, lo_open, hi_open, text)) in slots {
            let Value::Text { text: typed, .. } = v else {
                continue;
            };
            // Enough bits to tell a decimal of this many digits from a double.
            let bits = 128 + 4 * typed.len();
            let Some(x) = Big::from_decimal(typed, &bits) else {
                continue;
            };
            let (lo, hi) = (Big::from_f64(lo, &bits), Big::from_f64(hi, &bits));
            let below = if lo_open { x <= lo } else { x < lo };
            let above = if hi_open { x >= hi } else { x > hi };
            if below || above {
                return Err(format!(
                    "{name} {typed} is outside its range as written: valid {text} (the double it rounds to is inside, which --binary-params takes)"
                ));
            }
        }
        Ok(())
    }

    /// The table's name with its parameters as this setup reads them (the decimals
    /// typed, every digit; with the doubles asked for, their shortest decimals).
    pub fn table_name(&self) -> String {
        let texts: Vec<String> = (0..self.params.len())
            .map(|k| match &self.params[k] {
                Value::Text { text, .. } if !self.binary => text.clone(),
                other => crate::error::fmt_value(other.double() + 0.0),
            })
            .collect();
        self.family.member_name_texts(&texts)
    }

    /// The setup of `sys` with the ball of `start` (on the table or above it); None
    /// where the table is not taken.
    pub fn of_state(sys: &System, start: &State, binary: bool) -> Option<PreciseSetup> {
        PreciseSetup::new(
            sys.table(),
            sys.alpha(),
            sys.r(),
            start.phase(),
            Some(start.v()),
            binary,
        )
        .map(|s| s.above(start.height()))
    }

    /// This setup with the parameter `slot` at point `i` of the grid of `steps` values
    /// from `lo` to `hi` (a job's axis), whose double is `double` (what the f64 run
    /// used).
    pub fn on_grid(
        mut self,
        slot: Slot<'_>,
        (lo, hi, steps): (f64, f64, usize),
        i: usize,
        double: f64,
    ) -> PreciseSetup {
        let name = match slot {
            Slot::Alpha => "alpha",
            Slot::R => "r",
            Slot::Table(name) => name,
        };
        // The window as typed, where its texts read back to these ends.
        let reads = |t: &str, x: f64| t.trim().parse::<f64>() == Ok(x);
        let typed = self
            .windows
            .iter()
            .find(|(n, a, b)| n.eq_ignore_ascii_case(name) && reads(a, lo) && reads(b, hi))
            .map(|(_, a, b)| (a.trim().to_string(), b.trim().to_string()));
        let v = Value::Grid {
            lo,
            hi,
            i,
            steps,
            double,
            typed,
        };
        match slot {
            Slot::Alpha => self.alpha = v,
            Slot::R => self.r = v,
            Slot::Table(name) => {
                if let Some(k) = self.family.param_index(name) {
                    self.params[k] = v;
                }
            }
        }
        self
    }

    /// The system and the start at `bits`.
    pub fn make(&self, bits: usize) -> (PreciseSystem<Big>, PreciseState<Big>) {
        let num = |x: f64| Value::Double(x).at(bits, self.binary);
        let sys = if self.sine {
            PreciseSystem::sine(
                self.alpha.at(bits, self.binary),
                self.r.at(bits, self.binary),
                bits,
            )
        } else {
            let params: Vec<Big> = self
                .params
                .iter()
                .map(|v| v.at(bits, self.binary))
                .collect();
            let pieces = self
                .family
                .pieces_in(&params, &bits)
                .expect("a member at its doubles is one at its decimals");
            PreciseSystem::new(
                pieces,
                self.alpha.at(bits, self.binary),
                self.r.at(bits, self.binary),
                bits,
            )
            .expect("pieces of a table's degree")
        };
        let t0 = self.t0.at(bits, self.binary);
        let w = match &self.v0 {
            Some(v0) => v0.at(bits, self.binary) - sys.jet(&t0)[1].clone(),
            None => num(crate::map::DEFAULT_HOP),
        };
        let st = if self.z0.double() > 0.0 {
            let v = sys.jet(&t0)[1].clone() + w;
            PreciseState::above(&sys, 0, t0, v, self.z0.at(bits, self.binary))
        } else {
            PreciseState::launch(&sys, 0, t0, w)
        };
        (sys, st)
    }
}

/// Events a sticking cycle is looked for within, at each precision.
pub const CYCLE_EVENTS: u64 = 1_000_000;

/// The sticking cycle the ball of `setup` reaches, decided at any precision as `ask`
/// says ([`sticking_cycle_to_digits`], within [`CYCLE_EVENTS`] events and `max_periods`
/// table periods a run). `progress` hears how far each run has got and may stop the
/// work (then None).
pub fn decide_sticking_cycle(
    setup: &PreciseSetup,
    ask: DigitsAsk,
    max_periods: i64,
    progress: &mut dyn FnMut(DigitsProgress) -> ControlFlow<()>,
) -> Option<CycleVerdict> {
    sticking_cycle_to_digits(
        &|bits| setup.make(bits),
        ask.digits,
        ask.max_digits,
        CYCLE_EVENTS,
        max_periods,
        progress,
    )
}

/// The most a [`decide_sticking_cycle`] run holds at once, in bytes: the two runs'
/// paths from the release ([`PATH_EVENTS`] events at most, each a number at the
/// higher precision of the last pair, at most twice `ask.max_digits`) and an allowance
/// for the map's state and the cycle's numbers (the bound of a memory estimate).
pub fn digits_bytes(ask: DigitsAsk) -> u64 {
    let bits = crate::real::bits_for_digits(ask.max_digits.saturating_mul(2)) as u64;
    let events = PATH_EVENTS as u64;
    // A path's slots (a vector grown by doubling) and each number's limbs (64-bit
    // words, with the allocator's rounding).
    let slots = events.next_power_of_two()
        * std::mem::size_of::<(crate::map::EventKind, i64, Big)>() as u64;
    let limbs = events * (bits.div_ceil(64) * 8 + 16);
    2 * (slots + limbs) + (1 << 20)
}

/// [`decide_sticking_cycle`] for a job's worker, the orbit followed within the job's
/// `transient` (table periods): `tick` hears the events done since its last call, as a
/// job counts them (a run's count starts again at each precision), and returns true to
/// stop the work (then None).
pub fn decide_in_job(
    setup: &PreciseSetup,
    ask: DigitsAsk,
    transient: u64,
    tick: &mut dyn FnMut(u64) -> bool,
) -> Option<CycleVerdict> {
    let periods = i64::try_from(transient).unwrap_or(i64::MAX);
    let mut last = 0u64;
    decide_sticking_cycle(setup, ask, periods, &mut |p| {
        let new = p.done.saturating_sub(last);
        last = p.done;
        match tick(new) {
            true => ControlFlow::Break(()),
            false => ControlFlow::Continue(()),
        }
    })
}

/// Whether a job can decide its sticking cycles at any precision as `ask` says: digits
/// within [`crate::limits::DIGITS`], `max_digits` at least `digits`, a table the map at
/// any precision takes.
pub fn check_digits(ask: DigitsAsk, table: &Table) -> Result<(), EngineError> {
    limits::DIGITS.check(ask.digits as f64)?;
    limits::DIGITS.check(ask.max_digits as f64)?;
    if ask.max_digits < ask.digits {
        return Err(EngineError::Inconsistent(format!(
            "max digits {} is below digits {}: valid max digits ≥ digits",
            ask.max_digits, ask.digits
        )));
    }
    if !precise_takes(table) {
        return Err(EngineError::Inconsistent(format!(
            "digits: table {} is not computed at any precision: valid the sine or a piecewise polynomial table (of degree ≤ {})",
            table.name(),
            super::PRECISE_MAX_DEGREE
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::jobs::grid::grid_value;
    use crate::real::bits_for_digits;

    /// The middle of 0.595..0.6 in three steps is 0.5975 as written, not the double
    /// 0.5974999999999999 the f64 grid gives, and the doubles themselves where asked.
    #[test]
    fn a_grid_point_is_the_decimal_of_the_window_not_its_double() {
        let bits = bits_for_digits(60);
        let grid = Value::Grid {
            lo: 0.595,
            hi: 0.6,
            i: 1,
            steps: 3,
            double: grid_value(0.595, 0.6, 3, 1),
            typed: None,
        };
        assert_eq!(
            format!("{}", grid_value(0.595, 0.6, 3, 1)),
            "0.5974999999999999"
        );
        let exact = Big::from_decimal("0.5975", &bits).unwrap();
        let d = (grid.at(bits, false) - exact.clone()).abs();
        assert!(d <= Big::epsilon(&bits) * exact.clone(), "{d:?}");
        assert_eq!(
            grid.at(bits, true),
            Big::from_f64(0.5974999999999999, &bits)
        );
        // The ends are the window's decimals.
        let end = |i| Value::Grid {
            lo: 0.595,
            hi: 0.6,
            i,
            steps: 3,
            double: grid_value(0.595, 0.6, 3, i),
            typed: None,
        };
        assert_eq!(
            end(0).at(bits, false),
            Big::from_decimal("0.595", &bits).unwrap()
        );
        let six = Big::from_decimal("0.6", &bits).unwrap();
        assert!((end(2).at(bits, false) - six.clone()).abs() <= Big::epsilon(&bits) * six);
    }

    /// A window typed with more digits than a double holds is read as typed: the middle
    /// of 0.1..0.30000000000000000001 in three steps is 0.200000000000000000005, where
    /// the doubles' shortest decimals give 0.2; a window whose texts are not those of the
    /// grid's ends is not taken; an end outside its range as written is refused.
    #[test]
    fn a_window_typed_is_read_with_every_digit() {
        let bits = bits_for_digits(40);
        let table = Table::fd(0.1).unwrap();
        let typed = |hi: &str| Written {
            windows: vec![("alpha".into(), "0.1".into(), hi.into())],
            ..Written::default()
        };
        let setup = PreciseSetup::new(&table, 0.45, 0.8, 0.2, None, false)
            .unwrap()
            .as_written(&typed("0.30000000000000000001"));
        assert_eq!(setup.check_written(), Ok(()));
        let mid = setup.clone().on_grid(Slot::Alpha, (0.1, 0.3, 3), 1, 0.2);
        let want = Big::from_decimal("0.200000000000000000005", &bits).unwrap();
        let got = mid.alpha.at(bits, false);
        assert!((got - want.clone()).abs() <= Big::epsilon(&bits) * want);
        let other = setup.on_grid(Slot::Alpha, (0.1, 0.4, 3), 1, 0.25);
        assert_eq!(
            other.alpha.at(bits, false),
            Big::from_decimal("0.25", &bits).unwrap()
        );
        let r = PreciseSetup::new(&table, 0.45, 0.8, 0.2, None, false)
            .unwrap()
            .as_written(&Written {
                windows: vec![("r".into(), "0.5".into(), "0.99999999999999999999".into())],
                ..Written::default()
            });
        assert_eq!(r.check_written(), Ok(()));
        let over = PreciseSetup::new(&table, 0.45, 0.8, 0.2, None, false)
            .unwrap()
            .as_written(&typed("1000.0000000000000000001"));
        assert!(over.check_written().unwrap_err().contains("(0, 1000]"));
    }

    /// A setup on a job's grid puts the value where the parameter is: α, r, or the
    /// family's parameter by name.
    #[test]
    fn on_grid_sets_the_swept_parameter() {
        let bits = bits_for_digits(30);
        let table = Table::fd(0.1).unwrap();
        let setup = PreciseSetup::new(&table, 0.45, 0.8, 0.2, None, false).unwrap();
        let window = (0.0, 1.0, 5);
        let alpha = setup.clone().on_grid(Slot::Alpha, window, 1, 0.25);
        assert_eq!(
            alpha.alpha.at(bits, false),
            Big::from_decimal("0.25", &bits).unwrap()
        );
        let r = setup.clone().on_grid(Slot::R, window, 3, 0.75);
        assert_eq!(
            r.r.at(bits, false),
            Big::from_decimal("0.75", &bits).unwrap()
        );
        let d = setup.on_grid(Slot::Table("D"), window, 2, 0.5);
        assert_eq!(
            d.params[0].at(bits, false),
            Big::from_decimal("0.5", &bits).unwrap()
        );
    }
}
