//! The parameters the user edits: table, the table family's own parameters (F_D's D, a
//! table file's), α, r, k, initial state, the diagram's swept parameter, window, start
//! mode, transient and keep. Each row parses and checks
//! typed text through the shared rule for it ([`crate::config::rules`], the same ranges
//! and messages as the command line) and knows its coarse and fine steps; a refused
//! value leaves everything unchanged and comes back as a one-line message naming the
//! valid range. The rows themselves (their rules, labels and ranges) are [`ParamId`].
//!
//! Where α goes when the table's kind changes or a preset loads: just below α_PD of the
//! (1, k) solution when that lies in the window (the last stable period-1 value, the
//! most telling place to start stepping), else the window's middle.

mod rows;

pub use rows::{ParamId, StartMode, Touch};

use crate::config::presets::Preset;
use crate::config::rules;
use crate::config::table_spec::TableSpec;
use crate::output::text::{quoted, shortest};
use bouncemap_engine::jobs::grid::{ParamName, SweepParam};
use bouncemap_engine::orbits::stability_windows;
use bouncemap_engine::sweep::Warm;
use bouncemap_engine::table::builtin::{families, Builtin};
use bouncemap_engine::{State, System, Table, DEFAULT_HOP};

/// Every editable value.
#[derive(Clone, Debug, PartialEq)]
pub struct Params {
    /// The table's name (sine, fd:D, or a file).
    pub table: TableSpec,
    /// The table itself (a file is read once, when named).
    loaded: Table,
    /// The file given at start or typed, if any (the table row can cycle back to it).
    pub file: Option<(TableSpec, Table)>,
    pub alpha: f64,
    pub r: f64,
    pub k: u32,
    pub t0: f64,
    /// None: f'(t0) + 0.5, the same default as `bouncemap orbit`.
    pub v0: Option<f64>,
    /// The diagram's α window.
    pub lo: f64,
    pub hi: f64,
    pub transient: u64,
    pub keep: usize,
    /// Values in the diagram's sweep (the data's resolution: exports have as many,
    /// whatever the screen).
    pub steps: usize,
    /// The diagram's swept parameter (its window is `lo..hi`).
    pub param: SweepParam,
    /// How every value of the diagram starts.
    pub start: StartMode,
}

/// The window of r sweeps (a family parameter's is its whole range).
pub const R_WINDOW: (f64, f64) = (0.5, 0.95);
/// The transient the application opens with; its window is the default table's (fd:0.1:
/// the (1, 1) branch, its period doubling at α_PD = 0.50997, the narrow (2, 2) window
/// up to 0.51184 and the chaos after it), with the paper's start (values next to the
/// (1, 1) solution).
pub const START_TRANSIENT: u64 = 20_000;

/// The window a sweep of `param` opens with on `table` (named `spec`).
pub fn default_window(param: SweepParam, spec: &TableSpec, table: &Table) -> (f64, f64) {
    match param {
        SweepParam::Alpha => spec.alpha_window(),
        SweepParam::R => R_WINDOW,
        SweepParam::Table(_) => param.range(table).unwrap_or((0.0, 1.0)),
    }
}

impl Default for Params {
    fn default() -> Self {
        let table = TableSpec::fd(rules::D.default);
        let (lo, hi) = table.alpha_window();
        Params {
            loaded: table.load().expect("the default table is built in"),
            table,
            file: None,
            alpha: rules::ALPHA.default,
            r: rules::R.default,
            k: rules::K.default as u32,
            t0: rules::T0.default,
            v0: None,
            lo,
            hi,
            transient: START_TRANSIENT,
            keep: rules::KEEP.default as usize,
            steps: rules::STEPS.default as usize,
            param: SweepParam::Alpha,
            start: StartMode::NearFixedPoint,
        }
    }
}

impl Params {
    /// The panel's rows: the table, its family's parameters, then the rest.
    pub fn rows(&self) -> Vec<ParamId> {
        let n = self.family_params().len();
        let mut v = vec![ParamId::Table];
        v.extend((0..n).map(|i| ParamId::Family(i as u8)));
        v.extend(ParamId::SYSTEM);
        v
    }

    /// The table family's parameters (none for the sine and a file without any).
    pub fn family_params(&self) -> &[bouncemap_engine::table::Param] {
        self.loaded.family().map_or(&[], |(f, _)| f.params())
    }

    /// A row's label: a family parameter by its own name.
    pub fn label(&self, id: ParamId) -> String {
        match id {
            ParamId::Family(i) => self
                .family_params()
                .get(i as usize)
                .map_or("?".into(), |p| p.name().to_string()),
            other => other.label().to_string(),
        }
    }

    /// A row's valid range, as refusals state it.
    pub fn range_of(&self, id: ParamId) -> String {
        match id {
            ParamId::Family(i) => self
                .family_params()
                .get(i as usize)
                .map_or(String::new(), |p| p.range_text()),
            ParamId::Lo | ParamId::Hi => self.window_range(),
            other => other.range(),
        }
    }

    /// The swept parameter's range, as refusals state it.
    fn window_range(&self) -> String {
        match self.param {
            SweepParam::Alpha => rules::ALPHA.limit.text.to_string(),
            SweepParam::R => rules::R.limit.text.to_string(),
            SweepParam::Table(_) => self
                .param
                .range(&self.loaded)
                .map_or(String::new(), |(lo, hi)| {
                    format!("[{}, {}]", shortest(lo), shortest(hi))
                }),
        }
    }

    /// The closed bounds a window of the swept parameter may reach (an open end moved
    /// in by 1e-9).
    pub fn window_bounds(&self) -> (f64, f64) {
        let closed = |l: bouncemap_engine::limits::Limit| {
            (
                if l.lo_open { l.lo + 1e-9 } else { l.lo },
                if l.hi_open { l.hi - 1e-9 } else { l.hi },
            )
        };
        match self.param {
            SweepParam::Alpha => closed(rules::ALPHA.limit),
            SweepParam::R => closed(rules::R.limit),
            SweepParam::Table(_) => self.param.range(&self.loaded).unwrap_or((0.0, 1.0)),
        }
    }

    /// The table these parameters name.
    pub fn table(&self) -> Table {
        self.loaded.clone()
    }

    /// Short name of the table: sine, fd:0.1, or the file's name.
    pub fn table_label(&self) -> String {
        match &self.table {
            TableSpec::File(_) => self.loaded.name().to_string(),
            spec => spec.to_string(),
        }
    }

    /// The current value of `param` (a family's parameter: of the table, if it has it).
    pub fn value(&self, param: SweepParam) -> Option<f64> {
        match param {
            SweepParam::Alpha => Some(self.alpha),
            SweepParam::R => Some(self.r),
            SweepParam::Table(n) => self.loaded.param(n.as_str()),
        }
    }

    /// The row that edits `param`, if the panel has one.
    pub fn row_of(&self, param: SweepParam) -> Option<ParamId> {
        match param {
            SweepParam::Alpha => Some(ParamId::Alpha),
            SweepParam::R => Some(ParamId::R),
            SweepParam::Table(n) => self
                .family_params()
                .iter()
                .position(|p| p.name() == n.as_str())
                .map(|i| ParamId::Family(i as u8)),
        }
    }

    /// The parameter a row edits (the rows of α, r and the family's parameters).
    pub fn param_of(&self, id: ParamId) -> Option<SweepParam> {
        match id {
            ParamId::Alpha => Some(SweepParam::Alpha),
            ParamId::R => Some(SweepParam::R),
            ParamId::Family(i) => self
                .family_params()
                .get(i as usize)
                .and_then(|p| ParamName::new(p.name()))
                .map(SweepParam::Table),
            _ => None,
        }
    }

    /// The swept parameter's symbol (α, r, or the family parameter's name).
    pub fn symbol(param: SweepParam) -> String {
        match param {
            SweepParam::Alpha => "α".into(),
            other => other.as_str().to_string(),
        }
    }

    /// α just below α_PD of the (1, k) solution if that lies inside the window (an α
    /// window only), else the window's middle; α unchanged for r and D sweeps.
    pub fn place_alpha(&mut self) {
        if self.param != SweepParam::Alpha {
            return;
        }
        let (lo, hi) = (self.lo, self.hi);
        let pd = stability_windows(&self.table(), self.r, self.k)
            .ok()
            .and_then(|w| w.first().and_then(|w| w.alpha_pd()))
            .filter(|a| *a > lo && *a <= hi);
        let a = match pd {
            Some(pd) => (pd - 0.02 * (hi - lo)).max(lo),
            None => 0.5 * (lo + hi),
        };
        let mut next = self.clone();
        next.alpha = round_to(a, 1e-6);
        if next.validate(ParamId::Alpha).is_ok() {
            *self = next;
        }
    }

    /// The validated system. Every value is kept valid by the setters.
    pub fn system(&self) -> System {
        System::new(self.table(), self.alpha, self.r).expect("parameters are validated on entry")
    }

    /// The initial state, with the same default as `bouncemap orbit`.
    pub fn initial(&self, sys: &System) -> Result<State, String> {
        // The application starts on the table (no z0): say so without naming z0.
        State::start(sys, self.t0, self.v0, 0.0)
            .map_err(|e| e.to_string().replace(" (or give z0 > 0)", ""))
    }

    /// Use `table` (already loaded) named `spec`.
    pub fn set_table(&mut self, spec: TableSpec, table: Table) {
        if matches!(spec, TableSpec::File(_)) {
            self.file = Some((spec.clone(), table.clone()));
        }
        self.table = spec;
        self.loaded = table;
    }

    /// The value of a row as displayed.
    pub fn show(&self, id: ParamId) -> String {
        let n = |x: f64| fmt_num(x);
        match id {
            // A file's parameters are rows of their own: its family's name alone.
            ParamId::Table => match &self.table {
                TableSpec::File(_) => self
                    .loaded
                    .family()
                    .map_or(self.loaded.name(), |(f, _)| f.name())
                    .to_string(),
                _ => self.table_label(),
            },
            ParamId::Family(i) => self
                .loaded
                .family()
                .and_then(|(_, v)| v.get(i as usize).copied())
                .map_or("—".into(), n),
            ParamId::Alpha => n(self.alpha),
            ParamId::R => n(self.r),
            ParamId::K => self.k.to_string(),
            ParamId::T0 => n(self.t0),
            ParamId::V0 => self.v0.map_or("auto".into(), n),
            ParamId::Sweep => Params::symbol(self.param),
            ParamId::Lo => n(self.lo),
            ParamId::Hi => n(self.hi),
            ParamId::Start => self.start.label().into(),
            ParamId::Transient => self.transient.to_string(),
            ParamId::Keep => self.keep.to_string(),
            ParamId::Values => self.steps.to_string(),
        }
    }

    /// Nudge a row by one coarse or fine step in direction `dir` (±1). Returns an
    /// error (and changes nothing) at the edge of the valid range.
    pub fn nudge(&mut self, id: ParamId, dir: i32, fine: bool) -> Result<(), String> {
        let s = dir.signum() as f64;
        let step = |coarse: f64, f: f64| if fine { f } else { coarse } * s;
        let value = match id {
            ParamId::Table => {
                let order = self.table_order();
                let here = order
                    .iter()
                    .position(|(t, _)| same_kind(t, &self.table))
                    .unwrap_or(0);
                let n = order.len() as i32;
                let (spec, table) = order[((here as i32 + dir).rem_euclid(n)) as usize].clone();
                let mut next = self.clone();
                next.change_table(spec, table);
                next.validate(id)?;
                *self = next;
                return Ok(());
            }
            ParamId::Sweep => {
                let all = self.sweepable();
                let here = all.iter().position(|p| *p == self.param).unwrap_or(0);
                let n = all.len() as i32;
                let next = all[((here as i32 + dir).rem_euclid(n)) as usize];
                return self.set_param(next);
            }
            ParamId::Start => {
                let all = StartMode::ALL;
                let here = all.iter().position(|m| *m == self.start).unwrap_or(0);
                self.start = all[((here as i32 + dir).rem_euclid(4)) as usize];
                return Ok(());
            }
            ParamId::Family(i) => {
                // Tenths and hundredths of the parameter's range (F_D's D: 0.1, 0.01).
                let Some(p) = self.family_params().get(i as usize) else {
                    return Ok(());
                };
                let (lo, hi) = p.range();
                let cur = self.show_value(id).unwrap_or(p.default_value());
                let x = round_to(cur + step(0.1 * (hi - lo), 0.01 * (hi - lo)), 1e-9);
                x.clamp(lo, hi)
            }
            ParamId::Alpha => round_to(self.alpha + step(0.01, 0.001), 1e-9),
            ParamId::R => round_to(self.r + step(0.01, 0.001), 1e-9),
            ParamId::K => self.k as f64 + s,
            ParamId::T0 => round_to(self.t0 + step(0.05, 0.005), 1e-9),
            ParamId::V0 => {
                let sys = self.system();
                let cur = self.v0.unwrap_or_else(|| sys.df(self.t0) + DEFAULT_HOP);
                round_to(cur + step(0.1, 0.01), 1e-9)
            }
            ParamId::Lo => round_to(
                self.lo + step((self.hi - self.lo) * 0.1, (self.hi - self.lo) * 0.01),
                1e-9,
            ),
            ParamId::Hi => round_to(
                self.hi + step((self.hi - self.lo) * 0.1, (self.hi - self.lo) * 0.01),
                1e-9,
            ),
            ParamId::Transient => {
                // Coarse steps scale the transient by 10, fine ones by 2.
                let f = if fine { 2.0 } else { 10.0 };
                let t = self.transient as f64;
                (if s > 0.0 { t * f } else { (t / f).floor() }).max(1.0)
            }
            ParamId::Keep => self.keep as f64 + step(50.0, 10.0),
            ParamId::Values => {
                // Coarse steps double or halve the values, fine ones add or take 10 %.
                let v = self.steps as f64;
                let f = if fine { 1.1 } else { 2.0 };
                (if s > 0.0 { v * f } else { v / f }).round().max(1.0)
            }
        };
        self.set_value(id, value)
    }

    /// The current value of a family parameter's row.
    fn show_value(&self, id: ParamId) -> Option<f64> {
        let ParamId::Family(i) = id else {
            return None;
        };
        self.loaded
            .family()
            .and_then(|(_, v)| v.get(i as usize).copied())
    }

    /// The parameters a diagram can sweep on this table: α, r and its family's.
    pub fn sweepable(&self) -> Vec<SweepParam> {
        SweepParam::all(&self.loaded)
    }

    /// Sweep `param`: its default window, α placed for an α sweep.
    pub fn set_param(&mut self, param: SweepParam) -> Result<(), String> {
        if !self.sweepable().contains(&param) {
            return Err(format!(
                "sweep: {} is not a parameter of {}; valid {}",
                param.as_str(),
                self.table_label(),
                SweepParam::names(&self.loaded)
            ));
        }
        self.param = param;
        (self.lo, self.hi) = default_window(param, &self.table, &self.loaded);
        self.place_alpha();
        Ok(())
    }

    /// Use another table; a table of another kind (sine, F_D, a file) brings its own
    /// α window, and α is placed in it (an r or D sweep keeps its window; D becomes α
    /// on a table without D).
    pub fn change_table(&mut self, spec: TableSpec, table: Table) {
        let kind_changed = !same_kind(&spec, &self.table);
        self.set_table(spec, table);
        if !self.sweepable().contains(&self.param) {
            self.param = SweepParam::Alpha;
            (self.lo, self.hi) = default_window(SweepParam::Alpha, &self.table, &self.loaded);
            self.place_alpha();
        } else if kind_changed && self.param == SweepParam::Alpha {
            (self.lo, self.hi) = default_window(SweepParam::Alpha, &self.table, &self.loaded);
            self.place_alpha();
        } else if kind_changed && self.param.is_table() {
            (self.lo, self.hi) = default_window(self.param, &self.table, &self.loaded);
        }
    }

    /// Set a row from typed text. Refusals name the valid range; nothing changes then.
    pub fn set_text(&mut self, id: ParamId, text: &str) -> Result<(), String> {
        let t = text.trim();
        let label = self.label(id);
        let refuse = |e: String| format!("{label}: {e}");
        match id {
            ParamId::Table => {
                let spec = TableSpec::parse(t).map_err(refuse)?;
                let table = match (&spec, &self.file) {
                    (TableSpec::File(_), Some((f, tb))) if *f == spec => tb.clone(),
                    _ => spec.load().map_err(|e| e.0)?,
                };
                let mut next = self.clone();
                next.change_table(spec, table);
                next.validate(id)?;
                *self = next;
                Ok(())
            }
            ParamId::Sweep => {
                let p = SweepParam::parse(t, &self.loaded).map_err(refuse)?;
                self.set_param(p)
            }
            ParamId::Start => {
                self.start = StartMode::parse(t).map_err(refuse)?;
                Ok(())
            }
            ParamId::Lo | ParamId::Hi => {
                let x = rules::param_value(self.param, &self.loaded, t).map_err(refuse)?;
                self.set_value(id, x)
            }
            ParamId::Family(_) => {
                let param = self
                    .param_of(id)
                    .ok_or_else(|| refuse("the table has no such parameter".into()))?;
                let x = rules::param_value(param, &self.loaded, t).map_err(refuse)?;
                self.set_value(id, x)
            }
            ParamId::V0 if t == "auto" || t.is_empty() => {
                let mut next = self.clone();
                next.v0 = None;
                next.validate(id)?;
                *self = next;
                Ok(())
            }
            ParamId::V0 => {
                // The one number parser (its refusal quotes the text cut short), then
                // this row's own range.
                let x = rules::V0.parse(t).map_err(|_| {
                    refuse(format!(
                        "{} is not a number: valid {}",
                        quoted(t),
                        id.range()
                    ))
                })?;
                self.set_value(id, x)
            }
            _ => {
                let rule = id.rule().expect("numeric row");
                let x = rule.parse(t).map_err(refuse)?;
                self.set_value(id, x)
            }
        }
    }

    /// Set a numeric row to `x`, checking it and what depends on it.
    fn set_value(&mut self, id: ParamId, x: f64) -> Result<(), String> {
        let label = self.label(id);
        match id {
            ParamId::Lo | ParamId::Hi => {
                self.param
                    .check(&self.loaded, x)
                    .map_err(|e| format!("{}: {e}", label.trim()))?;
            }
            _ => {
                if let Some(rule) = id.rule() {
                    rule.check(x)
                        .map_err(|e| format!("{}: {e}", label.trim()))?;
                }
            }
        }
        let mut next = self.clone();
        match id {
            ParamId::Table | ParamId::Sweep | ParamId::Start => {
                unreachable!("the table, sweep and start rows are not numeric")
            }
            ParamId::Family(_) => {
                let param = self
                    .param_of(id)
                    .ok_or_else(|| format!("{label}: the table has no such parameter"))?;
                let table = param
                    .table(&self.loaded, x)
                    .map_err(|e| format!("{label}: {e}"))?;
                next.set_table(self.table.with_value(param.as_str(), x), table);
            }
            ParamId::Alpha => next.alpha = x,
            ParamId::R => next.r = x,
            ParamId::K => next.k = x as u32,
            ParamId::T0 => next.t0 = x,
            ParamId::V0 => next.v0 = Some(x),
            ParamId::Lo => next.lo = x,
            ParamId::Hi => next.hi = x,
            ParamId::Transient => next.transient = x as u64,
            ParamId::Keep => next.keep = x as usize,
            ParamId::Values => next.steps = x as usize,
        }
        next.validate(id)?;
        *self = next;
        Ok(())
    }

    /// Check what depends on row `id` of a candidate parameter set (its own range was
    /// checked by its rule).
    pub fn validate(&self, id: ParamId) -> Result<(), String> {
        if matches!(id, ParamId::Lo | ParamId::Hi) && self.lo >= self.hi {
            let v = if id == ParamId::Lo { self.lo } else { self.hi };
            return Err(format!(
                "{} {}: {} is out of range; valid {} {} {}",
                Params::symbol(self.param),
                id.label().trim(),
                shortest(v),
                self.window_range(),
                if id == ParamId::Lo { "below" } else { "above" },
                shortest(if id == ParamId::Lo { self.hi } else { self.lo })
            ));
        }
        // The start must stay valid for the new system (v0 above the table's velocity).
        if matches!(id.touches(), Touch::System | Touch::Start) && id != ParamId::K {
            let sys = System::new(self.table(), self.alpha, self.r).map_err(|e| e.to_string())?;
            if let Err(e) = self.initial(&sys) {
                return Err(format!(
                    "{}: refused, the initial state would be invalid: {e}",
                    id.label()
                ));
            }
        }
        Ok(())
    }

    /// These parameters with the settings of a preset: its table, swept parameter, r,
    /// window, values, transient, keep and start (k = 1; α placed in the window, just
    /// below α_PD where that is in it).
    pub fn with_preset(&self, p: &Preset) -> Result<Params, String> {
        let spec = p.sweep_spec().map_err(|e| e.0)?;
        let mut next = self.clone();
        let table = spec.table.clone();
        next.set_table(p.table.clone(), table);
        next.param = spec.param;
        next.r = spec.r;
        next.k = 1;
        next.lo = spec.lo;
        next.hi = spec.hi;
        next.steps = spec.steps;
        next.transient = spec.transient;
        next.keep = spec.keep;
        next.start = match (spec.initial.near_fixed_point, spec.warm) {
            (true, _) => StartMode::NearFixedPoint,
            (false, Warm::Forward) => StartMode::Warm,
            (false, Warm::Backward) => StartMode::WarmBackward,
            (false, Warm::Off) => StartMode::Cold,
        };
        if spec.param == SweepParam::Alpha {
            next.place_alpha();
        } else {
            next.alpha = spec.alpha;
        }
        next.validate(ParamId::Table)?;
        Ok(next)
    }

    /// The tables the table row cycles through: sine, F_D (at the current D), a file.
    fn table_order(&self) -> Vec<(TableSpec, Table)> {
        let d = self.table.d().unwrap_or(rules::D.default);
        // Every built-in family (F_D at the current D), then the file.
        let mut v: Vec<(TableSpec, Table)> = families()
            .into_iter()
            .map(|f| {
                let b = Builtin::of(f.name(), (!f.params().is_empty()).then_some(d));
                (TableSpec::Builtin(b), b.table().expect("D is in range"))
            })
            .collect();
        if let Some(f) = &self.file {
            v.push(f.clone());
        }
        v
    }
}

fn same_kind(a: &TableSpec, b: &TableSpec) -> bool {
    match (a, b) {
        (TableSpec::Builtin(x), TableSpec::Builtin(y)) => x.family() == y.family(),
        (TableSpec::File(_), TableSpec::File(_)) => true,
        _ => false,
    }
}

fn round_to(x: f64, q: f64) -> f64 {
    (x / q).round() * q
}

/// A number with up to 6 decimals, trailing zeros trimmed (exponent form for huge and
/// tiny magnitudes).
pub fn fmt_num(x: f64) -> String {
    let a = x.abs();
    if a >= 1e7 || (a != 0.0 && a < 1e-4) {
        return shortest(x);
    }
    let s = crate::output::text::decimals(x, 6);
    if s == "-0" {
        "0".into()
    } else {
        s
    }
}
