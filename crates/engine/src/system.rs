//! A bouncing ball system: table shape, amplitude α and restitution r, validated.
//!
//! Nondimensional units throughout: gravity 1, table period 1, f(t) = α F(t).

use crate::error::EngineError;
use crate::limits;
use crate::table::Table;

/// The physical system the impact map runs on. Its fields are private: every System
/// was checked by [`System::new`] (or [`System::set_alpha`]), so no code can hold one
/// outside the ranges the solvers are established for.
#[derive(Clone, Debug, PartialEq)]
pub struct System {
    table: Table,
    alpha: f64,
    r: f64,
}

impl System {
    /// Validate α ([`limits::ALPHA`]), r ([`limits::R`]) and the size of the table's
    /// motion f = αF ([`limits::MAX_DISPLACEMENT`] and the bounds after it).
    pub fn new(table: Table, alpha: f64, r: f64) -> Result<System, EngineError> {
        limits::ALPHA.check(alpha)?;
        limits::R.check(r)?;
        check_alpha(&table, alpha)?;
        Ok(System { table, alpha, r })
    }

    /// Change α in place, validated as by [`Self::new`] (no copy of the table: for
    /// computations that vary α, such as continuation of periodic orbits).
    pub fn set_alpha(&mut self, alpha: f64) -> Result<(), EngineError> {
        check_alpha(&self.table, alpha)?;
        self.alpha = alpha;
        Ok(())
    }

    /// The table shape F.
    #[inline]
    pub fn table(&self) -> &Table {
        &self.table
    }

    /// The amplitude α.
    #[inline]
    pub fn alpha(&self) -> f64 {
        self.alpha
    }

    /// The restitution coefficient r.
    #[inline]
    pub fn r(&self) -> f64 {
        self.r
    }

    /// f, f', f'', f''' at `phase` (α included; right derivatives at breakpoints).
    #[inline]
    pub fn jet(&self, phase: f64) -> [f64; 4] {
        self.table.jet(phase).map(|x| self.alpha * x)
    }

    /// f at `phase`.
    #[inline]
    pub fn f(&self, phase: f64) -> f64 {
        self.alpha * self.table.derivative(phase, 0)
    }

    /// f' at `phase`.
    #[inline]
    pub fn df(&self, phase: f64) -> f64 {
        self.alpha * self.table.derivative(phase, 1)
    }

    /// f'' at `phase` (right derivative at breakpoints).
    #[inline]
    pub fn ddf(&self, phase: f64) -> f64 {
        self.alpha * self.table.derivative(phase, 2)
    }

    /// κ_c(r) = −2(1 + r²)/(1 + r)², the period-doubling edge of the stable band.
    pub fn kappa_c(&self) -> f64 {
        kappa_c(self.r)
    }
}

/// α within [`limits::ALPHA`] and the table's motion f = αF within the bounds after
/// [`limits::MAX_DISPLACEMENT`].
fn check_alpha(table: &Table, alpha: f64) -> Result<(), EngineError> {
    limits::ALPHA.check(alpha)?;
    let (lo, hi) = table.range();
    for (what, size, bound) in [
        ("max|F|", lo.abs().max(hi.abs()), limits::MAX_DISPLACEMENT),
        ("max|F'|", table.velocity_bound(), limits::MAX_VELOCITY),
        ("max|F''|", table.accel_bound(), limits::MAX_ACCELERATION),
    ] {
        let product = alpha * size;
        if product.is_nan() || product > bound {
            return Err(EngineError::InvalidTable(format!(
                    "table {} at alpha = {}: alpha·{what} = {} is out of range: valid at most {} (the sine's at alpha = 1000, up to where the solver's guarantees are established)",
                    table.name(),
                    crate::error::fmt_value(alpha),
                    crate::error::fmt_value(product),
                    crate::error::fmt_value(bound)
                )));
        }
    }
    Ok(())
}

/// κ_c(r) = −2(1 + r²)/(1 + r)².
pub fn kappa_c(r: f64) -> f64 {
    -2.0 * (1.0 + r * r) / ((1.0 + r) * (1.0 + r))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_builtin_table_is_accepted_up_to_alpha_1000() {
        for t in [
            Table::sine(),
            Table::fd(0.0).unwrap(),
            Table::fd(1.0).unwrap(),
        ] {
            assert!(System::new(t, 1000.0, 0.8).is_ok());
        }
    }

    #[test]
    fn a_table_wilder_than_the_sine_at_alpha_1000_is_refused_naming_the_bound() {
        // F = 1e15 (t̂² − t̂)² … as a C¹ quartic on one piece: F(0) = F(1), F'(0) = F'(1).
        let c = 1e15;
        let t = Table::piecewise("huge", &[(0.0, vec![0.0, 0.0, c, -2.0 * c, c])]).unwrap();
        let e = System::new(t, 0.45, 0.8).unwrap_err().to_string();
        assert!(
            e.starts_with("table huge at alpha = 0.45: alpha·max|F|"),
            "{e}"
        );
        assert!(e.contains("valid at most 1000"), "{e}");
    }
}
