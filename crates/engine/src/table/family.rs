//! Table families: a table shape with named parameters, each with a default and a valid
//! range, whose members are [`Table`]s. The paper's F_D is the built-in family with one
//! parameter D; the sine is a family without parameters; a table file may declare
//! parameters and write its pieces' breakpoints and coefficients as [`Expr`]essions in
//! them.
//!
//! A member is built by evaluating the expressions at the parameter values and checking
//! the table as any piecewise table is checked (pieces in order, C¹ across every
//! breakpoint and the wrap): so the C¹ check runs at every parameter value used, and a
//! refusal names the values (`at w = 0.35: not C¹ at breakpoint ...`).

use super::expr::{Expr, ExprError, Number};
use super::{Piece, Table, MAX_TABLE_DEGREE};
use crate::error::{fmt_value, EngineError};
use crate::limits;
use std::borrow::Cow;
use std::fmt;
use std::sync::{Arc, OnceLock};

/// The longest parameter name.
pub const MAX_NAME: usize = 15;

/// The most parameters a family declares.
pub const MAX_PARAMS: usize = 8;

/// Names a parameter may not take: the system's own parameters, which share the axes
/// and flags (`--param`, `--x`, `--y`) with a family's (compared ignoring case).
pub const RESERVED_NAMES: [&str; 3] = ["alpha", "r", "k"];

/// One parameter of a family: its name, default and valid (closed) range.
#[derive(Clone, Debug, PartialEq)]
pub struct Param {
    name: String,
    default: f64,
    lo: f64,
    hi: f64,
}

impl Param {
    /// A parameter; refused if the name is not an identifier of at most [`MAX_NAME`]
    /// characters (letters, digits, `_`, starting with a letter) or is reserved, or if
    /// the range is not finite and ordered, or the default lies outside it.
    pub fn new(name: &str, default: f64, lo: f64, hi: f64) -> Result<Param, EngineError> {
        let bad = |m: String| EngineError::InvalidTable(format!("parameter '{name}': {m}"));
        let mut chars = name.chars();
        let ident = chars.next().is_some_and(|c| c.is_ascii_alphabetic())
            && chars.all(|c| c.is_ascii_alphanumeric() || c == '_');
        if !ident || name.len() > MAX_NAME {
            return Err(bad(format!(
                "a name is a letter followed by letters, digits or _, at most {MAX_NAME} characters"
            )));
        }
        if RESERVED_NAMES.iter().any(|r| r.eq_ignore_ascii_case(name)) {
            return Err(bad(format!(
                "the name is taken by the system's own parameters ({}); choose another",
                RESERVED_NAMES.join(", ")
            )));
        }
        if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
            return Err(bad(format!(
                "range [{}, {}]: valid a finite range with low ≤ high",
                fmt_value(lo),
                fmt_value(hi)
            )));
        }
        if !(lo..=hi).contains(&default) {
            return Err(bad(format!(
                "default {} lies outside its range [{}, {}]",
                fmt_value(default),
                fmt_value(lo),
                fmt_value(hi)
            )));
        }
        Ok(Param {
            name: name.to_string(),
            default,
            lo,
            hi,
        })
    }

    /// A parameter whose range is one of the engine's [`limits`] (closed at both ends).
    fn from_limit(limit: limits::Limit, default: f64) -> Param {
        debug_assert!(!limit.lo_open && !limit.hi_open && !limit.whole);
        Param {
            name: limit.name.to_string(),
            default,
            lo: limit.lo,
            hi: limit.hi,
        }
    }

    /// The name, as the family spells it.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The default value.
    pub fn default_value(&self) -> f64 {
        self.default
    }

    /// The valid range, closed at both ends.
    pub fn range(&self) -> (f64, f64) {
        (self.lo, self.hi)
    }

    /// The range as refusals state it: `[0, 1]`.
    pub fn range_text(&self) -> String {
        format!("[{}, {}]", fmt_value(self.lo), fmt_value(self.hi))
    }

    /// `x` if it lies in the range, else the refusal naming it and the range.
    pub fn check(&self, x: f64) -> Result<f64, EngineError> {
        if x.is_finite() && (self.lo..=self.hi).contains(&x) {
            Ok(x)
        } else {
            Err(EngineError::InvalidParameter {
                name: Cow::Owned(self.name.clone()),
                value: fmt_value(x),
                range: Cow::Owned(self.range_text()),
            })
        }
    }
}

/// The variable a family's coefficients are written in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Variable {
    /// Ascending powers of the phase t̂.
    Phase,
    /// Ascending powers of s = t̂ − start, the piece's own variable (what the engine
    /// stores; coefficients written so are used without a change of variable).
    Local,
}

/// One piece of a family: its start and coefficients as expressions.
#[derive(Clone, Debug, PartialEq)]
pub struct PieceTemplate {
    start: Expr,
    coeffs: Vec<Expr>,
}

#[derive(Clone, Debug, PartialEq)]
enum Template {
    Sine,
    Pieces {
        variable: Variable,
        pieces: Vec<PieceTemplate>,
    },
}

/// A family of tables.
#[derive(Clone, Debug, PartialEq)]
pub struct Family {
    name: String,
    params: Vec<Param>,
    template: Template,
    /// A built-in family: valid over its parameters' whole ranges and affine in each
    /// (proved by construction), its members named `name:value` as the command line
    /// writes them rather than `name (p = value, ...)`.
    builtin: bool,
    alpha_window: Option<(f64, f64)>,
}

/// The built-in F_D written as a family: the paper's factored forms multiplied out in
/// each piece's own variable s, in the order that rounds exactly as the factored
/// product does (so members equal the tables the factored form builds, bit for bit).
///   [0, ½):  s (s − ½)(D s − 1)          = ½ s − (1 + D/2) s² + D s³
///   [½, 1):  s (s − ½)(D s + 1 − D/2)    = −(1 − D/2)/2 s + (1 − D/2 − D/2) s² + D s³
const FD_PIECES: [(&str, [&str; 4]); 2] = [
    ("0", ["0", "1/2", "-1 - D/2", "D"]),
    ("1/2", ["0", "-(1 - D/2)/2", "1 - D/2 - D/2", "D"]),
];

impl Family {
    /// F(t̂) = sin 2πt̂: no parameters.
    pub fn sine() -> &'static Arc<Family> {
        static SINE: OnceLock<Arc<Family>> = OnceLock::new();
        SINE.get_or_init(|| {
            Arc::new(Family {
                name: "sine".into(),
                params: Vec::new(),
                template: Template::Sine,
                builtin: true,
                alpha_window: Some((0.02, 0.04)),
            })
        })
    }

    /// The paper's F_D, D in [`limits::D`].
    pub fn fd() -> &'static Arc<Family> {
        static FD: OnceLock<Arc<Family>> = OnceLock::new();
        FD.get_or_init(|| {
            let params = vec![Param::from_limit(limits::D, 0.0)];
            let pieces = FD_PIECES
                .iter()
                .map(|(start, coeffs)| (start.to_string(), coeffs.map(String::from).to_vec()))
                .collect::<Vec<_>>();
            let mut fam = Family::piecewise("fd", params, Variable::Local, &pieces)
                .expect("F_D's template is valid");
            fam.builtin = true;
            fam.alpha_window = Some((0.45, 0.6));
            Arc::new(fam)
        })
    }

    /// A piecewise family from its parameters and its pieces' (start, coefficients) as
    /// expression texts in `variable`. Refusals name the piece, the coefficient and the
    /// column of a bad expression, or the parameter values at which the defaults fail
    /// to make a valid table.
    pub fn piecewise(
        name: &str,
        params: Vec<Param>,
        variable: Variable,
        pieces: &[(String, Vec<String>)],
    ) -> Result<Family, EngineError> {
        let bad = |m: String| EngineError::InvalidTable(m);
        if params.len() > MAX_PARAMS {
            return Err(bad(format!(
                "{} parameters: valid at most {MAX_PARAMS}",
                params.len()
            )));
        }
        for (i, p) in params.iter().enumerate() {
            if let Some(q) = params[..i]
                .iter()
                .find(|q| q.name.eq_ignore_ascii_case(&p.name))
            {
                return Err(bad(format!(
                    "parameter '{}' is declared twice (as '{}' and '{}'; names are compared ignoring case)",
                    p.name, q.name, p.name
                )));
            }
        }
        if pieces.is_empty() {
            return Err(bad("no [[piece]] given (need at least one)".into()));
        }
        let names: Vec<&str> = params.iter().map(|p| p.name.as_str()).collect();
        let parse = |text: &str, what: String| {
            Expr::parse(text, &names).map_err(|e: ExprError| {
                bad(format!("{what}: '{}' {e}", crate::error::short_text(text)))
            })
        };
        let mut built = Vec::with_capacity(pieces.len());
        for (i, (start, coeffs)) in pieces.iter().enumerate() {
            if coeffs.is_empty() || coeffs.len() > MAX_TABLE_DEGREE + 1 {
                return Err(bad(format!(
                    "piece {} has {} coefficients; allowed 1 to {} (degree up to {})",
                    i + 1,
                    coeffs.len(),
                    MAX_TABLE_DEGREE + 1,
                    MAX_TABLE_DEGREE
                )));
            }
            built.push(PieceTemplate {
                start: parse(start, format!("piece {} start", i + 1))?,
                coeffs: coeffs
                    .iter()
                    .enumerate()
                    .map(|(k, c)| parse(c, format!("piece {} coefficient {}", i + 1, k + 1)))
                    .collect::<Result<_, _>>()?,
            });
        }
        let fam = Family {
            name: name.to_string(),
            params,
            template: Template::Pieces {
                variable,
                pieces: built,
            },
            builtin: false,
            alpha_window: None,
        };
        fam.pieces_at(&fam.defaults()).map_err(|e| {
            if fam.params.is_empty() {
                e
            } else {
                bad(format!("{e} (with every parameter at its default)"))
            }
        })?;
        Ok(fam)
    }

    /// Whether it is built in: valid over its parameters' whole ranges and affine in
    /// each, so a window's ends stand for every value between them.
    pub fn is_builtin(&self) -> bool {
        self.builtin
    }

    /// The family's name (`fd`, `sine`, or the name a file gives).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The parameters, in the order declared.
    pub fn params(&self) -> &[Param] {
        &self.params
    }

    /// The parameter called `name`: exactly as spelled, else ignoring case.
    pub fn param_index(&self, name: &str) -> Option<usize> {
        let n = name.trim();
        self.params.iter().position(|p| p.name == n).or_else(|| {
            self.params
                .iter()
                .position(|p| p.name.eq_ignore_ascii_case(n))
        })
    }

    /// The parameters' names, for refusals: `D, w` or `none`.
    pub fn param_names(&self) -> String {
        if self.params.is_empty() {
            "none".to_string()
        } else {
            let names: Vec<&str> = self.params.iter().map(|p| p.name.as_str()).collect();
            names.join(", ")
        }
    }

    /// The first piece (1-based) whose start moves with parameter `i`, if any.
    pub fn breakpoint_moved_by(&self, i: usize) -> Option<usize> {
        match &self.template {
            Template::Sine => None,
            Template::Pieces { pieces, .. } => {
                pieces.iter().position(|p| p.start.uses(i)).map(|k| k + 1)
            }
        }
    }

    /// Every parameter at its default.
    pub fn defaults(&self) -> Vec<f64> {
        self.params.iter().map(|p| p.default).collect()
    }

    /// The α window where its (1, 1) orbit, its period doublings and the chaos after
    /// them lie at r = 0.8, if known (the built-in families'); a file's family has none.
    pub fn alpha_window(&self) -> Option<(f64, f64)> {
        self.alpha_window
    }

    /// The name of the member with these values: `fd:0.1`, `sine`, `asym (w = 0.2)`.
    pub fn member_name(&self, values: &[f64]) -> String {
        self.name_with(values, None)
    }

    /// The name of the members with these values but parameter `free` left free, as
    /// a caption names a sweep or a plane over it: `fd:D`, `asym (w, h = 0.3)`.
    pub fn member_name_free(&self, values: &[f64], free: usize) -> String {
        self.name_with(values, Some(free))
    }

    /// The family's name with each parameter's value, or its name where it is `free`:
    /// `name:v,...` for a built-in family, `name (p = v, ...)` for a file's.
    fn name_with(&self, values: &[f64], free: Option<usize>) -> String {
        let texts: Vec<String> = values.iter().map(|&x| fmt_value(x + 0.0)).collect();
        self.name_with_texts(&texts, free)
    }

    /// The name of the member whose parameters are the decimals `texts` (as a run at any
    /// precision reads them, with more digits than a double holds).
    pub fn member_name_texts(&self, texts: &[String]) -> String {
        self.name_with_texts(texts, None)
    }

    fn name_with_texts(&self, texts: &[String], free: Option<usize>) -> String {
        if self.params.is_empty() {
            return self.name.clone();
        }
        let parts: Vec<String> = self
            .params
            .iter()
            .zip(texts)
            .enumerate()
            .map(|(i, (p, x))| match (Some(i) == free, self.builtin) {
                (true, _) => p.name.clone(),
                (false, true) => x.clone(),
                (false, false) => format!("{} = {x}", p.name),
            })
            .collect();
        if self.builtin {
            format!("{}:{}", self.name, parts.join(","))
        } else {
            format!("{} ({})", self.name, parts.join(", "))
        }
    }

    /// The member with parameter i at `values[i]`, checked: each value in its range,
    /// then the table as any piecewise table (refusals name the values).
    pub fn member(family: &Arc<Family>, values: &[f64]) -> Result<Table, EngineError> {
        assert_eq!(values.len(), family.params.len(), "one value per parameter");
        for (p, &x) in family.params.iter().zip(values) {
            p.check(x)?;
        }
        let mut table = match &family.template {
            Template::Sine => Table::sine(),
            Template::Pieces { .. } => {
                let pieces = family.pieces_at(values)?;
                Table::from_pieces(family.member_name(values), pieces)
            }
        };
        table.member = Some(super::Member {
            family: Arc::clone(family),
            values: values.to_vec(),
        });
        Ok(table)
    }

    /// The checked pieces at these values.
    fn pieces_at(&self, values: &[f64]) -> Result<Vec<Piece>, EngineError> {
        let Template::Pieces { variable, pieces } = &self.template else {
            return Ok(Vec::new());
        };
        let at = |e: EngineError| {
            if self.params.is_empty() {
                e
            } else {
                let v: Vec<String> = self
                    .params
                    .iter()
                    .zip(values)
                    .map(|(p, &x)| format!("{} = {}", p.name, fmt_value(x)))
                    .collect();
                EngineError::InvalidTable(format!("at {}: {e}", v.join(", ")))
            }
        };
        let value = |e: &Expr, what: String| -> Result<f64, EngineError> {
            match e.eval(values) {
                Some(x) if x.is_finite() => Ok(x),
                other => Err(at(EngineError::InvalidTable(format!(
                    "{what} '{}' is {}",
                    crate::error::short_text(e.text()),
                    other.map_or("too large".to_string(), |x| format!("{x}"))
                )))),
            }
        };
        let mut numbers = Vec::with_capacity(pieces.len());
        for (i, p) in pieces.iter().enumerate() {
            let start = value(&p.start, format!("piece {} start", i + 1))?;
            let coeffs = p
                .coeffs
                .iter()
                .enumerate()
                .map(|(k, c)| value(c, format!("piece {} coefficient {}", i + 1, k + 1)))
                .collect::<Result<Vec<f64>, _>>()?;
            numbers.push((start, coeffs));
        }
        super::checked_pieces(&numbers, *variable).map_err(at)
    }
}

/// One piece of a member at any precision: where it starts and ends in phase, and F on
/// it as a polynomial in the piece's own variable s = t̂ − start (ascending powers).
#[derive(Clone, Debug)]
pub struct PieceIn<N> {
    /// Phase where the piece starts.
    pub start: N,
    /// Phase where it ends (the next piece's start, or 1).
    pub end: N,
    /// F's coefficients in s.
    pub coeffs: Vec<N>,
}

impl Family {
    /// The member's pieces at `values` (each parameter's value in `N`, as the caller read
    /// it at the precision of `ctx`: a decimal parameter exactly, then rounded once),
    /// evaluated in `N`: every constant of the expressions read at that precision, and
    /// coefficients written in the phase shifted to the piece's own variable in `N`.
    /// None for the sine (not piecewise) or a constant `N` cannot hold. The checks (C¹,
    /// ranges) are the f64 member's ([`Family::member`]), made at the same values.
    pub fn pieces_in<N: Number>(&self, values: &[N], ctx: &N::Context) -> Option<Vec<PieceIn<N>>> {
        let Template::Pieces { variable, pieces } = &self.template else {
            return None;
        };
        let mut out: Vec<PieceIn<N>> = Vec::with_capacity(pieces.len());
        for p in pieces {
            let start = p.start.eval_in(values, ctx)?;
            let mut coeffs = p
                .coeffs
                .iter()
                .map(|c| c.eval_in(values, ctx))
                .collect::<Option<Vec<N>>>()?;
            if *variable == Variable::Phase {
                // p(start + s): Taylor shift by repeated synthetic division.
                let n = coeffs.len();
                for k in 0..n {
                    for j in (k..n - 1).rev() {
                        coeffs[j] = coeffs[j].clone() + start.clone() * coeffs[j + 1].clone();
                    }
                }
            }
            if let Some(prev) = out.last_mut() {
                prev.end = start.clone();
            }
            out.push(PieceIn {
                end: N::one(ctx),
                start,
                coeffs,
            });
        }
        Some(out)
    }
}

impl fmt::Display for Family {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::poly::Poly;

    /// F_D built from the paper's factored form, piece by piece, as products of linear
    /// factors in the piece's own variable.
    fn fd_factored(d: f64) -> Vec<Poly> {
        let lin = |a: f64, b: f64| Poly::new(&[a, b]);
        vec![
            lin(0.0, 1.0).mul(&lin(-0.5, 1.0)).mul(&lin(-1.0, d)),
            lin(0.0, 1.0)
                .mul(&lin(-0.5, 1.0))
                .mul(&lin(1.0 - 0.5 * d, d)),
        ]
    }

    #[test]
    fn fd_members_equal_the_factored_form_bit_for_bit() {
        let mut x = 0.123_456_789_f64;
        for i in 0..2000 {
            // Exact ends, simple decimals and arbitrary doubles.
            let d = match i {
                0 => 0.0,
                1 => 1.0,
                2..=100 => (i - 2) as f64 / 98.0,
                _ => {
                    x = (x * 3.987_654_321 + 0.1).fract();
                    x
                }
            };
            let t = Table::fd(d).unwrap();
            let want = fd_factored(d);
            for (p, q) in t.pieces().iter().zip(&want) {
                let a: Vec<u64> = p.f.coeffs().iter().map(|c| c.to_bits()).collect();
                let b: Vec<u64> = q.coeffs().iter().map(|c| (c + 0.0).to_bits()).collect();
                assert_eq!(a, b, "D = {d}");
            }
        }
    }

    #[test]
    fn members_are_checked_at_their_values() {
        let params = vec![Param::new("w", 0.0, -1.0, 1.0).unwrap()];
        // F = w t̂ (1 − t̂) on one piece: C¹ across the wrap only when w = 0.
        let pieces = [("0".to_string(), vec!["0".into(), "w".into(), "-w".into()])];
        let fam = Arc::new(Family::piecewise("bump", params, Variable::Phase, &pieces).unwrap());
        assert!(Family::member(&fam, &[0.0]).is_ok());
        let e = Family::member(&fam, &[0.25]).unwrap_err().to_string();
        assert!(e.starts_with("at w = 0.25: not C¹"), "{e}");
        let e = Family::member(&fam, &[2.0]).unwrap_err().to_string();
        assert_eq!(e, "w = 2 is out of range: valid [-1, 1]");
        assert_eq!(Family::member(&fam, &[0.0]).unwrap().name(), "bump (w = 0)");
    }

    #[test]
    fn bad_families_are_refused_with_the_place() {
        let p = |n: &str| Param::new(n, 0.0, 0.0, 1.0);
        assert!(p("alpha").unwrap_err().to_string().contains("taken"));
        assert!(p("R").is_err() && p("2x").is_err() && p("a-b").is_err());
        assert!(Param::new("w", 2.0, 0.0, 1.0).is_err());
        assert!(Param::new("w", 0.0, 1.0, 0.0).is_err());
        let pieces = [("0".to_string(), vec!["0".into(), "1 + * w".into()])];
        let e = Family::piecewise("x", vec![p("w").unwrap()], Variable::Phase, &pieces)
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "piece 1 coefficient 2: '1 + * w' at column 5: unexpected '*': expected a number, a parameter or '('"
        );
        let twice = vec![p("w").unwrap(), p("W").unwrap()];
        assert!(Family::piecewise("x", twice, Variable::Phase, &pieces).is_err());
        // A division by zero at the defaults is named.
        let pieces = [("0".to_string(), vec!["1/w".into()])];
        let e = Family::piecewise("x", vec![p("w").unwrap()], Variable::Phase, &pieces)
            .unwrap_err()
            .to_string();
        assert!(e.contains("'1/w' is inf") && e.contains("at w = 0"), "{e}");
    }

    #[test]
    fn parameters_are_found_by_name() {
        let fd = Family::fd();
        assert_eq!(fd.param_index("D"), Some(0));
        assert_eq!(fd.param_index("d"), Some(0));
        assert_eq!(fd.param_index("x"), None);
        assert_eq!(Family::sine().param_names(), "none");
        assert_eq!(fd.member_name(&[0.25]), "fd:0.25");
        assert_eq!(fd.member_name(&[-0.0]), "fd:0");
        assert_eq!(fd.member_name_free(&[0.3], 0), "fd:D");
    }
}
