//! How mixed a basin picture is: the basin entropy and boundary basin entropy of Daza,
//! Wagemakers, Georgeot, Guéry-Odelin and Sanjuán (Sci. Rep. 6, 31416, 2016), and the
//! uncertainty exponent of the basin boundary (McDonald, Grebogi, Ott and Yorke,
//! Physica D 17, 125, 1985), both from the labels of a grid of starts.
//!
//! * [`basin_entropy`]: the grid cut into boxes of [`ENTROPY_BOX`] × [`ENTROPY_BOX`]
//!   starts; in box i, with p_ij the share of its starts going to attractor j, the
//!   Gibbs entropy S_i = Σ_j p_ij ln(1/p_ij). S_b is the mean of S_i over all boxes,
//!   S_bb the mean over the boxes that hold more than one attractor (those on a
//!   boundary). S_bb > ln 2 is a sufficient condition for a fractal boundary (the "ln 2
//!   criterion"): on a smooth boundary between two basins a box is cut in two parts of
//!   any proportion, and the mean of S_i over such boxes stays below ln 2.
//! * [`uncertainty`]: a start is ε-uncertain when a start at distance ε along one of
//!   the grid's axes goes elsewhere. The fraction f(ε) of uncertain starts scales as
//!   ε^a, with a = 1 for a smooth boundary and a < 1 for a fractal one (the boundary's
//!   box-counting dimension is 2 − a). ε is measured in grid steps, k = 1, 2, 3, 4, 6,
//!   8, 11, 16, 23, 32, …, and a is the least-squares slope of ln f against ln k, with
//!   its standard error; the fit needs at least four scales over at least a decade.
//!
//! The phase axis is periodic (phase 0 and phase 1 are one start), so neighbours along
//! it wrap around; along the velocity axis only starts at least the largest k from
//! both edges are counted, the same starts at every k. A grid point with no label (a
//! start that was not run to an attractor) counts as a class of its own.

/// Side of an entropy box, in grid points (Daza et al. use boxes of 5 × 5 starts).
pub const ENTROPY_BOX: usize = 5;
/// Fewest scales the uncertainty fit takes.
pub const MIN_SCALES: usize = 4;
/// Least ratio of the largest to the smallest scale of the fit.
pub const MIN_SPAN: f64 = 10.0;
/// Largest fraction of uncertain starts a scale of the fit may have: beyond, the
/// uncertain starts of neighbouring boundaries overlap and f(ε) saturates towards 1
/// whatever the boundary (bands of a basin thinner than ε).
pub const MAX_FRACTION: f64 = 0.5;
/// Largest difference between the slopes of the smaller and of the larger half of the
/// scales for the fit to be one power law: bands of one basin narrower than the larger
/// scales make f(ε) bend over (slope near 1 below their width, smaller above), and one
/// slope through the bend would read as a fractal boundary where there is none.
pub const MAX_BEND: f64 = 0.2;
/// Fewest uncertain starts at a scale for the fit to take it: fewer are too few to
/// count (and on a grid, a basin of a few isolated starts is below its resolution).
pub const MIN_UNCERTAIN: usize = 25;

/// The basin entropy of one picture.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BasinEntropy {
    /// Side of a box, in grid points.
    pub side: usize,
    /// Whole boxes in the grid (a partial box at an edge is left out).
    pub boxes: usize,
    /// Boxes that hold more than one attractor.
    pub boundary_boxes: usize,
    /// S_b: the mean entropy per box (natural logarithm).
    pub s_b: f64,
    /// S_bb: the mean entropy per boundary box (0 when there is none).
    pub s_bb: f64,
}

impl BasinEntropy {
    /// Whether S_bb exceeds ln 2: then the boundary is fractal (a sufficient condition;
    /// a fractal boundary may also stay below).
    pub fn fractal_by_log2(&self) -> bool {
        self.s_bb > std::f64::consts::LN_2
    }
}

/// The basin entropy of `labels` (index j·nx + i) on an `nx` × `ny` grid, in boxes of
/// `side` × `side` points. None when not one whole box fits.
pub fn basin_entropy(
    labels: &[Option<u32>],
    nx: usize,
    ny: usize,
    side: usize,
) -> Option<BasinEntropy> {
    assert_eq!(labels.len(), nx * ny, "labels of an nx × ny grid");
    let side = side.max(1);
    let (bx, by) = (nx / side, ny / side);
    if bx == 0 || by == 0 {
        return None;
    }
    let mut total = 0.0;
    let mut boundary_total = 0.0;
    let mut boundary_boxes = 0;
    let mut counts: Vec<(Option<u32>, usize)> = Vec::new();
    for b in 0..by {
        for a in 0..bx {
            counts.clear();
            for j in b * side..(b + 1) * side {
                for i in a * side..(a + 1) * side {
                    let l = labels[j * nx + i];
                    match counts.iter_mut().find(|(c, _)| *c == l) {
                        Some((_, n)) => *n += 1,
                        None => counts.push((l, 1)),
                    }
                }
            }
            let n = (side * side) as f64;
            let s: f64 = counts
                .iter()
                .map(|&(_, c)| {
                    let p = c as f64 / n;
                    -p * p.ln()
                })
                .sum();
            total += s;
            if counts.len() > 1 {
                boundary_total += s;
                boundary_boxes += 1;
            }
        }
    }
    let boxes = bx * by;
    Some(BasinEntropy {
        side,
        boxes,
        boundary_boxes,
        s_b: total / boxes as f64,
        s_bb: if boundary_boxes == 0 {
            0.0
        } else {
            boundary_total / boundary_boxes as f64
        },
    })
}

/// The uncertainty exponent of one picture's boundaries.
#[derive(Clone, Debug, PartialEq)]
pub struct Uncertainty {
    /// The exponent a of f(ε) ∝ ε^a.
    pub exponent: f64,
    /// Its standard error from the fit.
    pub error: f64,
    /// The measurements: (ε, fraction of uncertain starts), every scale measured
    /// (those the fit leaves out too); ε in grid steps for the grid's exponent, in
    /// table periods of t̂0 for a sampled one.
    pub fractions: Vec<(f64, f64)>,
    /// Starts counted at every scale.
    pub starts: usize,
}

/// Why a picture has no uncertainty exponent.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NoExponent {
    /// The grid is too small for scales spanning a decade (with the velocity margin).
    GridTooSmall,
    /// No start is uncertain at any scale: a single basin, no boundary to measure.
    NoBoundary,
    /// Fewer than [`MIN_UNCERTAIN`] uncertain starts at every scale.
    TooFewUncertain,
    /// Fewer than [`MIN_SCALES`] scales over a decade with uncertain starts, at most
    /// [`MAX_FRACTION`] of them.
    TooFewScales,
    /// f(ε) is no power law over the scales: the slopes of their smaller and larger
    /// halves differ by more than [`MAX_BEND`].
    NotPowerLaw,
}

impl NoExponent {
    /// Why, in words.
    pub fn as_str(self) -> &'static str {
        match self {
            NoExponent::GridTooSmall => "grid too small for scales over a decade",
            NoExponent::NoBoundary => "no boundary",
            NoExponent::TooFewUncertain => "too few uncertain starts",
            NoExponent::TooFewScales => {
                "fewer than 4 scales over a decade with 25 or more, and at most half, of the starts uncertain"
            }
            NoExponent::NotPowerLaw => {
                "no power law over the grid's scales (the slope bends by more than 0.2)"
            }
        }
    }
}

/// The scales k = round(√2^m), m = 0, 1, …, up to `max`, without repeats.
fn scales(max: usize) -> Vec<usize> {
    let mut out: Vec<usize> = Vec::new();
    let mut m = 0;
    loop {
        let k = 2f64.powf(m as f64 / 2.0).round() as usize;
        if k > max {
            break;
        }
        if out.last() != Some(&k) {
            out.push(k);
        }
        m += 1;
    }
    out
}

/// The uncertainty exponent of `labels` (index j·nx + i) on an `nx` × `ny` grid, the
/// first axis periodic (see the module's header).
pub fn uncertainty(
    labels: &[Option<u32>],
    nx: usize,
    ny: usize,
) -> Result<Uncertainty, NoExponent> {
    assert_eq!(labels.len(), nx * ny, "labels of an nx × ny grid");
    // The largest scale: the velocity margin leaves at least a third of the rows, and a
    // phase neighbour at ±k stays distinct from the start itself.
    let max_k = ((ny.saturating_sub(1)) / 3).min(nx.saturating_sub(1) / 2);
    let ks = scales(max_k);
    if ks.len() < MIN_SCALES || (*ks.last().unwrap_or(&0) as f64) < MIN_SPAN * ks[0] as f64 {
        return Err(NoExponent::GridTooSmall);
    }
    let margin = *ks.last().expect("scales");
    let rows = margin..ny - margin;
    let starts = rows.len() * nx;
    let label = |i: usize, j: usize| labels[j * nx + i];
    let fractions: Vec<(usize, f64)> = ks
        .iter()
        .map(|&k| {
            let mut uncertain = 0usize;
            for j in rows.clone() {
                for i in 0..nx {
                    let l = label(i, j);
                    let differs = label((i + k) % nx, j) != l
                        || label((i + nx - k % nx) % nx, j) != l
                        || label(i, j + k) != l
                        || label(i, j - k) != l;
                    uncertain += usize::from(differs);
                }
            }
            (k, uncertain as f64 / starts as f64)
        })
        .collect();
    let fractions: Vec<(f64, f64)> = fractions.into_iter().map(|(k, f)| (k as f64, f)).collect();
    fit(fractions, starts)
}

/// The power law f(ε) ∝ ε^a through `fractions` (ε, f), measured over `starts` starts
/// at every scale, under the rules of the module's header: scales with at least
/// [`MIN_UNCERTAIN`] uncertain starts and f ≤ [`MAX_FRACTION`], at least [`MIN_SCALES`]
/// of them over [`MIN_SPAN`], no bend beyond [`MAX_BEND`].
pub fn fit(mut fractions: Vec<(f64, f64)>, starts: usize) -> Result<Uncertainty, NoExponent> {
    fractions.sort_by(|a, b| a.0.total_cmp(&b.0));
    if fractions.iter().all(|(_, f)| *f == 0.0) {
        return Err(NoExponent::NoBoundary);
    }
    let enough = |f: f64| f * starts as f64 >= MIN_UNCERTAIN as f64 - 0.5;
    if !fractions.iter().any(|&(_, f)| enough(f)) {
        return Err(NoExponent::TooFewUncertain);
    }
    let used: Vec<(f64, f64)> = fractions
        .iter()
        .filter(|&&(_, f)| enough(f) && f <= MAX_FRACTION)
        .map(|&(k, f)| (k.ln(), f.ln()))
        .collect();
    let span = match (used.first(), used.last()) {
        (Some(a), Some(b)) => b.0 - a.0,
        _ => 0.0,
    };
    if used.len() < MIN_SCALES || span < MIN_SPAN.ln() - 1e-12 {
        return Err(NoExponent::TooFewScales);
    }
    let half = used.len() / 2;
    let (small, _) = slope(&used[..=half]);
    let (large, _) = slope(&used[half..]);
    if (small - large).abs() > MAX_BEND {
        return Err(NoExponent::NotPowerLaw);
    }
    let (exponent, error) = slope(&used);
    Ok(Uncertainty {
        exponent,
        error,
        fractions,
        starts,
    })
}

/// Least-squares slope of y against x and its standard error.
fn slope(points: &[(f64, f64)]) -> (f64, f64) {
    let n = points.len() as f64;
    let mx = points.iter().map(|p| p.0).sum::<f64>() / n;
    let my = points.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let b = sxy / sxx;
    let a = my - b * mx;
    let rss: f64 = points.iter().map(|p| (p.1 - a - b * p.0).powi(2)).sum();
    let error = if points.len() > 2 {
        (rss / (n - 2.0) / sxx).sqrt()
    } else {
        f64::INFINITY
    };
    (b, error)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn picture(nx: usize, ny: usize, f: impl Fn(usize, usize) -> Option<u32>) -> Vec<Option<u32>> {
        (0..nx * ny).map(|k| f(k % nx, k / nx)).collect()
    }

    #[test]
    fn one_basin_has_no_entropy_and_no_exponent() {
        let l = picture(40, 40, |_, _| Some(0));
        let e = basin_entropy(&l, 40, 40, ENTROPY_BOX).unwrap();
        assert_eq!(
            (e.boxes, e.boundary_boxes, e.s_b, e.s_bb),
            (64, 0, 0.0, 0.0)
        );
        assert!(!e.fractal_by_log2());
        assert_eq!(uncertainty(&l, 40, 40), Err(NoExponent::NoBoundary));
    }

    #[test]
    fn a_straight_boundary_inside_boxes_has_the_entropy_of_its_split() {
        // Basin 1 for w-rows j < 12 of 40: every box of rows 10..15 is cut 2 : 3, the
        // other 7 rows of boxes are pure. 8 boxes across.
        let l = picture(40, 40, |_, j| Some(u32::from(j < 12)));
        let e = basin_entropy(&l, 40, 40, 5).unwrap();
        let s = -(0.4f64 * 0.4f64.ln() + 0.6 * 0.6f64.ln());
        assert_eq!((e.boxes, e.boundary_boxes), (64, 8));
        assert!((e.s_bb - s).abs() < 1e-15, "{}", e.s_bb);
        assert!((e.s_b - s / 8.0).abs() < 1e-15);
        assert!(!e.fractal_by_log2());
    }

    #[test]
    fn a_checkerboard_is_past_the_log_2_criterion() {
        // Every 5 × 5 box holds 13 of one label and 12 of the other.
        let l = picture(50, 50, |i, j| Some(((i + j) % 2) as u32));
        let e = basin_entropy(&l, 50, 50, 5).unwrap();
        let (p, q) = (13.0 / 25.0, 12.0 / 25.0);
        let s: f64 = -(p * f64::ln(p) + q * f64::ln(q));
        assert!((e.s_b - s).abs() < 1e-15 && (e.s_bb - s).abs() < 1e-15);
        // Three classes in equal thirds would exceed ln 2 by far; two in near halves
        // stay just under it: the criterion is strict.
        assert!(s < std::f64::consts::LN_2);
        let l = picture(60, 60, |i, j| Some(((i + 2 * j) % 3) as u32));
        assert!(basin_entropy(&l, 60, 60, 5).unwrap().fractal_by_log2());
    }

    #[test]
    fn a_smooth_boundary_has_exponent_one() {
        // Two slanted parallel lines across a 400 × 200 grid (periodic along the first
        // axis): the uncertain starts at scale k lie within k of a line along an axis,
        // a band whose area is proportional to k while the bands stay apart: f(k) ∝ k.
        let l = picture(400, 200, |i, j| {
            Some(u32::from((i as f64 + 0.3 * j as f64) % 400.0 < 200.0))
        });
        let u = uncertainty(&l, 400, 200).unwrap();
        assert!((u.exponent - 1.0).abs() < 0.02, "{u:?}");
        assert!(u.error < 0.02, "{u:?}");
        let span = u.fractions.last().unwrap().0 / u.fractions[0].0;
        assert!(span >= 10.0);
    }

    #[test]
    fn labels_random_at_every_scale_saturate_and_give_no_exponent() {
        // A random picture: every start is uncertain at every scale (up to chance),
        // f ≈ 1 − 4^-4 everywhere: no scale below saturation to fit.
        let mut rng = crate::test_rng::Xorshift::new(7);
        let l: Vec<Option<u32>> = (0..120 * 120)
            .map(|_| Some((rng.next() * 4.0) as u32))
            .collect();
        assert_eq!(uncertainty(&l, 120, 120), Err(NoExponent::TooFewScales));
    }

    #[test]
    fn thin_bands_bend_the_law_and_give_no_exponent() {
        // One basin in bands 6 rows high every 60 rows: the uncertain rows are a band
        // and k rows on either side, f(k) = (6 + 2k)/60, which bends from slope ≈ 0.4
        // over k = 1..4 to ≈ 0.7 over k = 4..11: no one power law.
        let l = picture(100, 400, |_, j| Some(u32::from(j % 60 < 6)));
        assert_eq!(uncertainty(&l, 100, 400), Err(NoExponent::NotPowerLaw));
    }

    #[test]
    fn bands_saturate_and_only_the_scales_below_are_fitted() {
        // Horizontal bands 10 rows high, alternating: f(k) = 2k/10 for k ≤ 5 (each
        // boundary row pair), then saturated at 1; the fit takes f ≤ ½ only: k ≤ 2
        // here, too few scales. With bands 50 rows high f = 2k/50 up to k = 12.
        let l = picture(100, 400, |_, j| Some(((j / 10) % 2) as u32));
        assert_eq!(uncertainty(&l, 100, 400), Err(NoExponent::TooFewScales));
        let l = picture(100, 400, |_, j| Some(((j / 50) % 2) as u32));
        let u = uncertainty(&l, 100, 400).unwrap();
        assert!((u.exponent - 1.0).abs() < 0.05, "{u:?}");
        assert!(u.fractions.iter().any(|f| f.1 > MAX_FRACTION));
    }

    #[test]
    fn the_phase_axis_wraps_and_small_grids_are_refused() {
        // Two vertical stripes meeting at i = 0 and i = 100 of 200: with wrapping both
        // boundaries count, and the fraction at k is 4k/200 exactly.
        let l = picture(200, 100, |i, _| Some(u32::from(i < 100)));
        let u = uncertainty(&l, 200, 100).unwrap();
        for &(k, f) in &u.fractions {
            assert!((f - 4.0 * k / 200.0).abs() < 1e-12, "{k} {f}");
        }
        assert!((u.exponent - 1.0).abs() < 1e-12 && u.error < 1e-12);
        let l = picture(20, 20, |i, _| Some(u32::from(i < 10)));
        assert_eq!(uncertainty(&l, 20, 20), Err(NoExponent::GridTooSmall));
        // One start going elsewhere is no boundary the grid resolves.
        let l = picture(60, 100, |i, j| Some(u32::from(i == 30 && j == 50)));
        assert_eq!(uncertainty(&l, 60, 100), Err(NoExponent::TooFewUncertain));
    }
}
