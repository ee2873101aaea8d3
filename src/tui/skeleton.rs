//! The skeleton under the diagram: the periodic branches continued in an α window
//! from the (1, k) solution ([`compute`], run in the background by the `branches`
//! component), and the branch under a point of the diagram ([`Skeleton::under`]).

use bouncemap_engine::orbits::continuation::{branches, point_at, Branch, Options, Start};
use bouncemap_engine::orbits::periodic::CyclePoint;
use bouncemap_engine::Table;

/// Finer steps than the command's default, so the branches are smooth curves at a
/// terminal's resolution; periods up to 16.
pub const OPTIONS: Options = Options {
    max_steps: 4000,
    max_period: 16,
    max_branches: 64,
    stop_at_pd: false,
    h_init: 1e-3,
    h_max: 0.004,
};

/// The branches of one window, as computed.
#[derive(Clone, Debug)]
pub struct Skeleton {
    pub table: Table,
    pub r: f64,
    pub k: u32,
    pub window: (f64, f64),
    pub branches: Vec<Branch>,
}

impl Skeleton {
    /// The branch nearest to (α, y) among those that exist at α (y a phase t̂, or a
    /// velocity when `velocity`), with its cycle at α exactly (Newton at fixed α).
    pub fn under(&self, alpha: f64, y: f64, velocity: bool) -> Option<(usize, CyclePoint)> {
        let mut best: Option<(f64, usize, CyclePoint)> = None;
        for (i, b) in self.branches.iter().enumerate() {
            let (lo, hi) = b
                .points
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| {
                    (l.min(p.alpha), h.max(p.alpha))
                });
            if !(lo..=hi).contains(&alpha) {
                continue;
            }
            let Some(p) = point_at(&self.table, self.r, b, alpha) else {
                continue;
            };
            let ys = if velocity { &p.velocities } else { &p.phases };
            let d = ys
                .iter()
                .map(|&q| {
                    let d = (q - y).abs();
                    if velocity {
                        d
                    } else {
                        d.min(1.0 - d)
                    }
                })
                .fold(f64::INFINITY, f64::min);
            if best.as_ref().is_none_or(|(bd, _, _)| d < *bd) {
                best = Some((d, i, p));
            }
        }
        best.map(|(_, i, p)| (i, p))
    }
}

/// The skeleton of `table` at `r` in `window` from the (1, k) solution.
pub fn compute(table: Table, r: f64, k: u32, window: (f64, f64)) -> Result<Skeleton, String> {
    let found =
        branches(&table, r, window, Start::Fixed { k }, OPTIONS).map_err(|e| e.to_string())?;
    Ok(Skeleton {
        table,
        r,
        k,
        window,
        branches: found,
    })
}
