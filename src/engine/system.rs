//! A bouncing ball system: table shape, amplitude α and restitution r, validated.
//!
//! Nondimensional units throughout: gravity 1, table period 1, f(t) = α F(t).

use super::error::EngineError;
use super::table::Table;

/// Largest accepted amplitude. Above it flights span so many periods that the f64
/// height of the ball loses the precision the solver promises.
pub const MAX_ALPHA: f64 = 1e3;

/// The physical system the impact map runs on.
#[derive(Clone, Debug, PartialEq)]
pub struct System {
    pub table: Table,
    pub alpha: f64,
    pub r: f64,
}

impl System {
    /// Validate α in (0, 1000] and r in (0, 1).
    pub fn new(table: Table, alpha: f64, r: f64) -> Result<System, EngineError> {
        check_alpha(alpha)?;
        check_r(r)?;
        Ok(System { table, alpha, r })
    }

    /// f, f', f'', f''' at `phase` (α included; right derivatives at breakpoints).
    #[inline]
    pub fn jet(&self, phase: f64) -> [f64; 4] {
        let j = self.table.jet(phase);
        [
            self.alpha * j[0],
            self.alpha * j[1],
            self.alpha * j[2],
            self.alpha * j[3],
        ]
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

/// α must be finite and in (0, 1000].
pub fn check_alpha(alpha: f64) -> Result<(), EngineError> {
    if alpha.is_finite() && alpha > 0.0 && alpha <= MAX_ALPHA {
        Ok(())
    } else {
        Err(EngineError::InvalidParameter {
            name: "alpha",
            value: alpha.to_string(),
            range: "(0, 1000]",
        })
    }
}

/// r must be in the open interval (0, 1).
pub fn check_r(r: f64) -> Result<(), EngineError> {
    if r.is_finite() && r > 0.0 && r < 1.0 {
        Ok(())
    } else {
        Err(EngineError::InvalidParameter {
            name: "r",
            value: r.to_string(),
            range: "(0, 1) (open interval)",
        })
    }
}
