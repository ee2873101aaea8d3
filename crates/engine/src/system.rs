//! A bouncing ball system: table shape, amplitude α and restitution r, validated.
//!
//! Nondimensional units throughout: gravity 1, table period 1, f(t) = α F(t).

use crate::error::EngineError;
use crate::limits;
use crate::table::Table;

/// The physical system the impact map runs on.
#[derive(Clone, Debug, PartialEq)]
pub struct System {
    pub table: Table,
    pub alpha: f64,
    pub r: f64,
}

impl System {
    /// Validate α ([`limits::ALPHA`]) and r ([`limits::R`]).
    pub fn new(table: Table, alpha: f64, r: f64) -> Result<System, EngineError> {
        limits::ALPHA.check(alpha)?;
        limits::R.check(r)?;
        Ok(System { table, alpha, r })
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

/// κ_c(r) = −2(1 + r²)/(1 + r)².
pub fn kappa_c(r: f64) -> f64 {
    -2.0 * (1.0 + r * r) / ((1.0 + r) * (1.0 + r))
}
