//! The analytic curves of a plane with an α axis, as functions of the other parameter
//! (D or r): where the (1, 1) solution is born stable (α_birth) and where it period-
//! doubles (α_PD), from the first stability window ([`crate::orbits::fixed`]), and where
//! the (2, 2) branch born there collides with a breakpoint of the table
//! ([`crate::orbits::two_cycle::border_collision`]). Each is evaluated at every pixel
//! value of the other axis; None where it does not exist (no window, a window that does
//! not end by period doubling, no branch, a smooth table).

use super::PlaneSpec;
use crate::jobs::grid::SweepParam;
use crate::orbits::fixed::stability_window;
use crate::orbits::two_cycle::border_collision;

/// The curves along the non-α axis.
#[derive(Clone, Debug, PartialEq)]
pub struct Curves {
    /// Whether α is the x axis (else the y axis); the curves are α as a function of
    /// the other axis's values.
    pub alpha_on_x: bool,
    /// The other axis's parameter and its pixel values.
    pub along: SweepParam,
    /// The pixel values of the other axis.
    pub values: Vec<f64>,
    /// α_birth of the stable (1, 1) solution at each value (None where none exists).
    pub birth: Vec<Option<f64>>,
    /// α_PD, its period-doubling point, at each value.
    pub pd: Vec<Option<f64>>,
    /// α of the (2, 2) branch's border collision at each value.
    pub border: Vec<Option<f64>>,
}

impl Curves {
    /// The curves by name, in drawing order: `alpha_birth`, `alpha_pd`,
    /// `border_collision`.
    pub fn named(&self) -> [(&'static str, &[Option<f64>]); 3] {
        [
            ("alpha_birth", &self.birth),
            ("alpha_pd", &self.pd),
            ("border_collision", &self.border),
        ]
    }
}

/// The curves of `spec`'s plane (k = 1), or None when α is not one of its axes.
/// Bounded work: per value of the other axis, a few root isolations and one
/// continuation of the (2, 2) branch.
pub fn curves(spec: &PlaneSpec) -> Option<Curves> {
    let (alpha_on_x, other) = if spec.x.param == SweepParam::Alpha {
        (true, spec.y)
    } else if spec.y.param == SweepParam::Alpha {
        (false, spec.x)
    } else {
        return None;
    };
    let values: Vec<f64> = (0..other.n).map(|i| other.value(i)).collect();
    let mut birth = Vec::with_capacity(values.len());
    let mut pd = Vec::with_capacity(values.len());
    let mut border = Vec::with_capacity(values.len());
    for &v in &values {
        // The windows do not depend on α: any α of the axis will do.
        let (x, y) = if alpha_on_x {
            (spec.x.lo, v)
        } else {
            (v, spec.y.lo)
        };
        let sys = spec.system_at(x, y).ok();
        let sys = match sys {
            Some(s) => s,
            None => {
                birth.push(None);
                pd.push(None);
                border.push(None);
                continue;
            }
        };
        let window = stability_window(sys.table(), sys.r(), 1).ok().flatten();
        birth.push(window.map(|w| w.alpha_birth));
        let alpha_pd = window.and_then(|w| w.alpha_pd());
        pd.push(alpha_pd);
        border.push(
            alpha_pd
                .and_then(|_| border_collision(sys.table(), sys.r(), 1).ok())
                .map(|b| b.alpha),
        );
    }
    Some(Curves {
        alpha_on_x,
        along: other.param,
        values,
        birth,
        pd,
        border,
    })
}
