//! The period-doubling cascade of a (1, k) solution on the exact map.
//!
//! From the stable (1, k) solution the branch is continued in α up to its period
//! doubling α₁; there the continuation switches onto the (2, 2k) branch and follows it
//! to its own end, and so on: each 2ⁿ branch ends where it loses stability. That is a
//! period doubling (αₙ₊₁, and the cascade goes on), or a border collision (an impact
//! phase reaches a breakpoint of the table where f'' jumps: t̂ = 0 or ½ for F_D). A
//! border collision at which a far-side multiplier is below −1 gives birth to a cycle
//! of twice the period ([`super::border`]): if that cycle is stable, αₙ₊₁ is the
//! collision and the cascade goes on along it; otherwise the cascade stops there. The
//! Feigenbaum ratios are δₙ = (αₙ − αₙ₋₁)/(αₙ₊₁ − αₙ).
//!
//! How deep this goes is bounded by `depth` (the number of period doublings looked for)
//! and by the numbers themselves: αₙ₊₁ − αₙ shrinks like δ⁻ⁿ while each αₙ is located
//! to about 1e-13, and long cycles amplify rounding through the multiplier product, so
//! δₙ loses about one digit per level from n ≈ 6 on.

use super::border::Crossing;
use super::continuation::{Family, Kind, NoStart, Options, Special, Start};
use super::fixed::stability_window;
use crate::limits;
use crate::table::Table;

/// One 2ⁿ branch of the cascade and how it ends.
#[derive(Clone, Debug, PartialEq)]
pub struct Level {
    /// 2ⁿ impacts in 2ⁿk periods.
    pub period: usize,
    /// α where the branch is born: at the previous period doubling (smooth or through
    /// a border collision); for the (1, k) branch, its birth from the closed form (it is
    /// stable from there to α₁).
    pub alpha_start: f64,
    /// How it ends (period doubling, border collision with the breakpoint, …).
    pub end: Special,
}

/// The cascade: αₙ, the levels, the δ ratios.
#[derive(Clone, Debug, PartialEq)]
pub struct Cascade {
    /// The k of the (1, k) solution the cascade starts from.
    pub k: u32,
    /// The restitution coefficient.
    pub r: f64,
    /// α₁ < α₂ < …: the period-doubling points found.
    pub alphas: Vec<f64>,
    /// δₙ = (αₙ − αₙ₋₁)/(αₙ₊₁ − αₙ) for n = 2, 3, … (index 0 is δ₂).
    pub deltas: Vec<f64>,
    /// Each 2ⁿ branch: where it is born and how it ends.
    pub levels: Vec<Level>,
    /// Set when no doubled branch is born at the last αₙ.
    pub unborn: Option<String>,
}

impl Cascade {
    /// The estimate of Feigenbaum's δ the cascade supports: its last ratio δₙ, with the
    /// uncertainty of a truncated convergent sequence, |δₙ − δₙ₋₁| (the ratios converge
    /// geometrically, by a factor of about 4.7 per level, so the distance to the limit is
    /// below the last step). None with fewer than two ratios.
    pub fn delta_estimate(&self) -> Option<(f64, f64)> {
        match self.deltas[..] {
            [.., a, b] => Some((b, (b - a).abs())),
            _ => None,
        }
    }

    /// The first branch that ends otherwise than by period doubling (smooth or through
    /// a border collision).
    pub fn interrupted(&self) -> Option<&Level> {
        self.levels.iter().find(|l| {
            l.end.kind != Kind::PeriodDoubling
                && !matches!(
                    l.end.collision.map(|c| c.crossing),
                    Some(Crossing::Doubling { stable: true })
                )
        })
    }
}

/// The cascade from the (1, k) solution of `table` at restitution `r`, looking for at
/// most `depth` period doublings (bounded by [`limits::CASCADE_DEPTH`]).
pub fn cascade(table: &Table, r: f64, k: u32, depth: usize) -> Result<Cascade, NoStart> {
    limits::CASCADE_DEPTH
        .check(depth as f64)
        .map_err(NoStart::Invalid)?;
    let w = stability_window(table, r, k)
        .map_err(NoStart::Invalid)?
        .ok_or_else(|| {
            NoStart::NotFound(format!(
                "{}; a cascade starts from a stable (1, {k}) solution",
                super::fixed::without_window(table, r, k, limits::ALPHA.lo)
            ))
        })?;
    let pd = w.alpha_pd().ok_or_else(|| {
        NoStart::NotFound(format!(
            "the stable (1, {k}) solution ends otherwise than by period doubling ({})",
            w.end.as_str()
        ))
    })?;
    let lo = pd - 0.25 * (pd - w.alpha_birth);
    let hi = (pd + 1.0).min(limits::ALPHA.hi);
    let opts = Options {
        stop_at_pd: true,
        max_period: usize::MAX,
        ..Options::default()
    };
    let mut fam = Family::new(table, r, (lo, hi), opts)?;
    let seed = super::continuation::find_start(&mut fam, table, r, Start::Fixed { k })?;
    let t = fam
        .tangent(&seed, [1.0, 0.0, 0.0])
        .unwrap_or([1.0, 0.0, 0.0]);
    let run = fam.follow(seed.clone(), t);
    let mut levels = vec![Level {
        period: 1,
        alpha_start: w.alpha_birth,
        end: run.end,
    }];
    let mut alphas = Vec::new();
    let mut unborn = None;
    while alphas.len() < depth {
        let last = levels.last().expect("one level at least");
        // A stable cycle of twice the period born at the border collision the branch
        // ends at continues the cascade.
        let through_border = matches!(
            last.end.collision.map(|c| c.crossing),
            Some(Crossing::Doubling { stable: true })
        );
        if last.end.kind != Kind::PeriodDoubling && !through_border {
            break;
        }
        // The cascade moves one way in α; a period doubling behind the previous one means
        // the continuation lost the branch (rounding in a long cycle): stop there.
        if let [.., a, b] = alphas[..] {
            let (a, b): (f64, f64) = (a, b);
            if (last.end.alpha - b) * (b - a) <= 0.0 {
                let lost = levels.last_mut().expect("one level at least");
                lost.end.kind = Kind::NoConvergence;
                break;
            }
        }
        let last = levels.last().expect("one level at least");
        alphas.push(last.end.alpha);
        if alphas.len() == depth {
            break;
        }
        let pd = last.end.clone();
        let period = 2 * last.period;
        let born = if through_border {
            fam.doubled_at_border(&pd)
        } else {
            fam.doubled(&pd)
        };
        match born {
            Some(b) => levels.push(Level {
                period,
                alpha_start: pd.alpha,
                end: b.end,
            }),
            None if through_border => {
                unborn = Some(format!(
                    "the ({period}, {}) cycle born at the border collision at alpha = {} could not be found by Newton's method next to it",
                    period as u32 * k,
                    pd.alpha
                ));
                break;
            }
            None => {
                unborn = Some(format!(
                    "no ({period}, {}) branch is born at alpha = {}: a degenerate period doubling (f''' = 0 there, so doubled cycles exist at that alpha alone)",
                    period as u32 * k,
                    pd.alpha
                ));
                break;
            }
        }
    }
    let deltas = alphas
        .windows(3)
        .map(|a| (a[1] - a[0]) / (a[2] - a[1]))
        .collect();
    Ok(Cascade {
        k,
        r,
        alphas,
        deltas,
        levels,
        unborn,
    })
}
