//! One record type per output, serialized to csv by the `csv` crate and to json by
//! `serde_json`: a field is named and formatted in one place. Floats are written in the
//! shortest form that reads back to the same f64 (NaN, which the engine never emits,
//! would be `null` in json). Records that `merge` reads back also derive `Deserialize`,
//! and their enums refuse anything but the documented names.

use bouncemap_engine::orbits::{FixedPoint, StabilityWindow};
use bouncemap_engine::Complex;
use bouncemap_engine::{Event, EventKind, Solver};
use serde::{Deserialize, Serialize};
use std::io::Write;

mod attractors;
mod branches;
mod certify;
mod cycle;
mod global;
mod manifold;
mod sweep;
pub use attractors::*;
pub use branches::*;
pub use certify::*;
pub use cycle::*;
pub use global::*;
pub use manifold::*;
pub use sweep::*;
// (`records::PointRecord` is the sweep's; a continued branch's points have a record of
// the same name of their own in `branches`.)
pub use sweep::PointRecord;

/// A csv writer over `out` that writes its header itself (so an empty table still has
/// one): `header` then rows serialized in field order.
pub fn csv_writer<W: Write>(out: W, header: &[&str]) -> csv::Result<csv::Writer<W>> {
    let mut w = csv::WriterBuilder::new()
        .has_headers(false)
        .from_writer(out);
    w.write_record(header)?;
    Ok(w)
}

// ------------------------------------------------------------------ shared

/// An event's kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Kind {
    Impact,
    Stick,
    Release,
}

impl From<EventKind> for Kind {
    fn from(k: EventKind) -> Kind {
        match k {
            EventKind::Impact => Kind::Impact,
            EventKind::Stick => Kind::Stick,
            EventKind::Release => Kind::Release,
        }
    }
}

/// A complex number (eigenvalue, multiplier).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ComplexRecord {
    pub re: f64,
    pub im: f64,
}

impl From<Complex> for ComplexRecord {
    fn from(z: Complex) -> Self {
        ComplexRecord { re: z.re, im: z.im }
    }
}

/// The solver's name in outputs.
pub fn solver_name(s: Solver) -> &'static str {
    match s {
        Solver::Exact => "exact",
        Solver::Grid => "grid",
    }
}

// ------------------------------------------------------------------ orbit

/// One event of `orbit` (a csv row, and an element of the json `events`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EventRecord {
    pub index: u64,
    pub period: i64,
    pub phase: f64,
    pub v: f64,
    pub vrel: f64,
    pub kind: Kind,
}

impl EventRecord {
    pub const HEADER: [&'static str; 6] = ["index", "period", "phase", "v", "vrel", "kind"];

    pub fn new(index: u64, e: &Event) -> EventRecord {
        EventRecord {
            index,
            period: e.period,
            phase: e.phase,
            v: e.v,
            vrel: e.vrel,
            kind: e.kind.into(),
        }
    }
}

/// The fields of `orbit`'s json before its events.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct OrbitHeader<'a> {
    pub table: &'a str,
    pub alpha: f64,
    pub r: f64,
    pub solver: &'static str,
}

// ------------------------------------------------------------------ fixed

/// One (1, k) solution (json).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FixedSolution {
    pub phase: f64,
    pub v: f64,
    pub df: f64,
    pub ddf: f64,
    pub dddf: f64,
    pub delta_kappa: f64,
    pub jacobian: [[f64; 2]; 2],
    pub eigenvalues: [ComplexRecord; 2],
    pub flight: Option<f64>,
    pub admissible: bool,
    pub classification: &'static str,
}

impl From<&FixedPoint> for FixedSolution {
    fn from(p: &FixedPoint) -> Self {
        FixedSolution {
            phase: p.phase,
            v: p.v,
            df: p.df,
            ddf: p.ddf,
            dddf: p.dddf,
            delta_kappa: p.delta_kappa,
            jacobian: p.jacobian,
            eigenvalues: p.eigenvalues.map(Into::into),
            flight: p.flight,
            admissible: p.admissible,
            classification: p.classification.as_str(),
        }
    }
}

/// One α window of stability (json).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct WindowRecord {
    pub alpha_birth: f64,
    pub phase_birth: f64,
    pub alpha_end: f64,
    pub phase_end: f64,
    pub end: &'static str,
}

impl From<&StabilityWindow> for WindowRecord {
    fn from(w: &StabilityWindow) -> Self {
        WindowRecord {
            alpha_birth: w.alpha_birth,
            phase_birth: w.phase_birth,
            alpha_end: w.alpha_end,
            phase_end: w.phase_end,
            end: w.end.as_str(),
        }
    }
}

/// `fixed`'s json.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FixedDoc<'a> {
    pub table: &'a str,
    pub alpha: f64,
    pub r: f64,
    pub k: u32,
    pub kappa_c: f64,
    pub solutions: Vec<FixedSolution>,
    pub alpha_birth: Option<f64>,
    pub alpha_pd: Option<f64>,
    pub windows: Vec<WindowRecord>,
}

impl<'a> FixedDoc<'a> {
    /// The json of the (1, k) solutions `points` of `sys` and the stability `windows`.
    pub fn of(
        sys: &'a bouncemap_engine::System,
        k: u32,
        points: &[FixedPoint],
        windows: &[StabilityWindow],
    ) -> FixedDoc<'a> {
        let first = windows.first();
        FixedDoc {
            table: sys.table().name(),
            alpha: sys.alpha(),
            r: sys.r(),
            k,
            kappa_c: sys.kappa_c(),
            solutions: points.iter().map(FixedSolution::from).collect(),
            alpha_birth: first.map(|w| w.alpha_birth),
            alpha_pd: first.and_then(|w| w.alpha_pd()),
            windows: windows.iter().map(WindowRecord::from).collect(),
        }
    }
}

/// One csv row of `fixed`: a (1, k) solution.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FixedRow {
    pub phase: f64,
    pub v: f64,
    pub df: f64,
    pub ddf: f64,
    pub dddf: f64,
    pub delta_kappa: f64,
    pub eig1_re: f64,
    pub eig1_im: f64,
    pub eig2_re: f64,
    pub eig2_im: f64,
    pub admissible: bool,
    pub classification: &'static str,
}

impl FixedRow {
    pub const HEADER: [&'static str; 12] = [
        "phase",
        "v",
        "df",
        "ddf",
        "dddf",
        "delta_kappa",
        "eig1_re",
        "eig1_im",
        "eig2_re",
        "eig2_im",
        "admissible",
        "classification",
    ];
}

impl From<&FixedPoint> for FixedRow {
    fn from(p: &FixedPoint) -> Self {
        FixedRow {
            phase: p.phase,
            v: p.v,
            df: p.df,
            ddf: p.ddf,
            dddf: p.dddf,
            delta_kappa: p.delta_kappa,
            eig1_re: p.eigenvalues[0].re,
            eig1_im: p.eigenvalues[0].im,
            eig2_re: p.eigenvalues[1].re,
            eig2_im: p.eigenvalues[1].im,
            admissible: p.admissible,
            classification: p.classification.as_str(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use bouncemap_engine::jobs::grid::SweepParam;

    /// The field names a record serializes with, read from an auto-generated header.
    fn fields<T: Serialize>(record: &T) -> String {
        let mut w = csv::Writer::from_writer(Vec::new());
        w.serialize(record).unwrap();
        let text = String::from_utf8(w.into_inner().unwrap()).unwrap();
        text.lines().next().unwrap().to_string()
    }

    #[test]
    fn headers_name_the_fields_in_order() {
        let e = EventRecord {
            index: 0,
            period: 0,
            phase: 0.0,
            v: 0.0,
            vrel: 0.0,
            kind: Kind::Impact,
        };
        assert_eq!(fields(&e), EventRecord::HEADER.join(","));
        for k in 0..8 {
            let columns = SweepColumns {
                lyapunov: k & 1 != 0,
                attractors: k & 2 != 0,
                digits: k & 4 != 0,
            };
            let mut row = SweepRow {
                index: 0,
                value: 0.5,
                phase: None,
                v: None,
                kind: None,
                period: None,
                table_periods: None,
                status: Status::NoLanding,
                sticking: false,
                resolved: None,
                growth_decades: None,
                lyapunov: columns.lyapunov.then_some(Exponent(None)),
                attractor: columns.attractors.then_some(1),
                digits_verdict: None,
                digits_periods: None,
                stick_after: None,
                agreed_digits: None,
                need_digits: None,
            };
            if columns.digits {
                row = row.with_cycle(None);
            }
            assert_eq!(
                fields(&row),
                SweepRow::header(SweepParam::Alpha, columns)
                    .join(",")
                    .replace("alpha", "value")
            );
        }
    }

    #[test]
    fn csv_fields_are_quoted_where_they_must_be() {
        let mut w = csv_writer(Vec::new(), &["a", "b"]).unwrap();
        w.write_record(["x,y", "say \"hi\""]).unwrap();
        let text = String::from_utf8(w.into_inner().unwrap()).unwrap();
        assert_eq!(text, "a,b\n\"x,y\",\"say \"\"hi\"\"\"\n");
    }

    #[test]
    fn floats_are_shortest_round_trip() {
        let mut w = csv_writer(Vec::new(), &["x"]).unwrap();
        for x in [0.45, 1e300, 1e-300, 0.1 + 0.2] {
            w.serialize([x]).unwrap();
        }
        let text = String::from_utf8(w.into_inner().unwrap()).unwrap();
        let back: Vec<f64> = text.lines().skip(1).map(|l| l.parse().unwrap()).collect();
        assert_eq!(back, vec![0.45, 1e300, 1e-300, 0.1 + 0.2]);
        assert!(
            text.contains("1e300") && text.lines().all(|l| l.len() <= 24),
            "{text}"
        );
    }

    #[test]
    fn unknown_status_and_kind_names_are_refused() {
        assert!(serde_json::from_str::<Status>("\"garbage\"").is_err());
        assert!(serde_json::from_str::<Kind>("\"bounce\"").is_err());
        assert_eq!(
            serde_json::from_str::<Status>("\"no-landing\"").unwrap(),
            Status::NoLanding
        );
    }
}
