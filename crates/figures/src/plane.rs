//! `figure plane`: a two-parameter map as a figure. Every pixel is a cell coloured by
//! its orbit's class (the diagram's period colours), the analytic curves drawn over it
//! (α_birth, α_PD of the (1, 1) solution, the (2, 2) border collision), a legend with
//! each class's share of the pixels. The legends sit in the plot's corners where they
//! hide least: the fewest pixels unlike the rest beneath them, no curve if avoidable.

use super::classes::{of_pixel, Class, NO_LANDING};
use super::svg::LEGEND_FONT;
use super::text;
use crate::format::fmt_count;
use crate::labels::param_label;
use crate::model::{Axis, Color, Corner, Dash, Figure, Layer, Legend, Panel, Swatch};
use bouncemap_engine::fmt_value as shortest;
use bouncemap_engine::jobs::grid::SweepParam;
use bouncemap_engine::plane::{Curves, Pixel, PlaneSpec};

/// The colour of a class in print: the one palette ([`Class::rgb`]).
pub fn colour(c: Class) -> Color {
    let (r, g, b) = c.rgb();
    Color(r, g, b)
}

/// Where the ball never lands (or rests).
const NO_LANDING_COLOUR: Color = Color(235, 235, 235);

/// The two-parameter curves drawn over a plane, with the period they were followed up
/// to (the caption says it).
pub struct Continued<'a> {
    pub curves: &'a bouncemap_engine::orbits::curves::Curves,
    pub max_period: usize,
}

/// The figure of a complete plane: its classes (their legend beside the frame, where
/// it hides nothing) and, over the pixels, the continued two-parameter curves if given
/// (they hold the analytic α_PD of (1, 1) and border collision of (2, 2), which are
/// then not drawn twice), else the analytic curves.
pub fn plane_figure(
    spec: &PlaneSpec,
    pixels: &[Option<Pixel>],
    curves: Option<&Curves>,
    continued: Option<Continued<'_>>,
) -> Figure {
    let curves = if continued.is_some() { None } else { curves };
    let step = |a: &bouncemap_engine::jobs::grid::Axis| {
        if a.n > 1 {
            (a.hi - a.lo) / (a.n - 1) as f64
        } else {
            (a.hi - a.lo).abs().max(1e-3)
        }
    };
    let (dx, dy) = (step(&spec.x), step(&spec.y));
    let mut by_class: Vec<(String, Vec<[f64; 2]>)> = Class::ALL
        .iter()
        .map(|c| (c.name().to_string(), Vec::new()))
        .chain([(NO_LANDING.to_string(), Vec::new())])
        .collect();
    // The pixels of the plane's shard, each at its place under its class's name.
    let mut total = 0usize;
    for p in (0..spec.len()).filter(|&p| spec.holds(p)) {
        total += 1;
        let class = pixels[p].as_ref().and_then(of_pixel);
        let name = class.map_or(NO_LANDING, Class::name);
        if let Some(slot) = by_class.iter_mut().find(|(n, _)| n == name) {
            let (x, y) = spec.values(p);
            slot.1.push([x, y]);
        }
    }
    // What the corners' legends would hide: each pixel's class (its index in
    // `by_class`) at its place in the plot, and the curves' points.
    let placed: Vec<([f64; 2], usize)> = by_class
        .iter()
        .enumerate()
        .flat_map(|(k, (_, c))| c.iter().map(move |p| (*p, k)))
        .collect();
    let mut curve_points: Vec<[f64; 2]> = Vec::new();
    let mut panel = Panel::new(
        Axis::new(
            &param_label(spec.x.param),
            spec.x.lo - dx / 2.0,
            spec.x.hi + dx / 2.0,
        ),
        Axis::new(
            &param_label(spec.y.param),
            spec.y.lo - dy / 2.0,
            spec.y.hi + dy / 2.0,
        ),
    );
    let mut entries = Vec::new();
    for (name, centres) in by_class {
        if centres.is_empty() {
            continue;
        }
        let color = Class::from_name(&name).map_or(NO_LANDING_COLOUR, colour);
        let share = 100.0 * centres.len() as f64 / total.max(1) as f64;
        let label = match Class::from_name(&name) {
            Some(c) => describe(c),
            None => "no landing or at rest".to_string(),
        };
        // A class of a few pixels is never shown as 0.0 %.
        let share = if share < 0.05 {
            "<0.1%".to_string()
        } else {
            format!("{share:.1}%")
        };
        entries.push((Swatch::band(color), format!("{label} ({share})")));
        panel.layers.push(Layer::Cells {
            name,
            centres,
            size: [dx, dy],
            color,
        });
    }
    let mut curve_entries = Vec::new();
    let mut drawn: Vec<&str> = Vec::new();
    if let Some(c) = curves {
        for ((name, values), (dash, text)) in c.named().into_iter().zip([
            (Dash::Dotted, "$\u{3b1}$ birth of (1, 1)"),
            (Dash::Solid, "$\u{3b1}_{PD}$ of (1, 1)"),
            (Dash::Dashed, "border collision of (2, 2)"),
        ]) {
            let mut lines: Vec<Vec<[f64; 2]>> = vec![Vec::new()];
            for (&other, a) in c.values.iter().zip(values) {
                match a {
                    Some(a) => {
                        let p = if c.alpha_on_x {
                            [*a, other]
                        } else {
                            [other, *a]
                        };
                        lines.last_mut().unwrap().push(p);
                    }
                    None => lines.push(Vec::new()),
                }
            }
            lines.retain(|l| l.len() > 1);
            // Only curves that pass through the picture are drawn and named.
            let (xa, ya) = (&panel.x, &panel.y);
            let inside =
                |p: &[f64; 2]| (xa.lo..=xa.hi).contains(&p[0]) && (ya.lo..=ya.hi).contains(&p[1]);
            if !lines.iter().flatten().any(inside) {
                continue;
            }
            curve_points.extend(lines.iter().flatten().filter(|p| inside(p)).copied());
            panel.layers.push(Layer::Lines {
                name: name.to_string(),
                lines,
                color: Color::BLACK,
                dash,
                width: 0.9,
            });
            curve_entries.push((Swatch::line(Color::BLACK, dash), text.to_string()));
            drawn.push(text);
        }
    }
    if let Some(c) = &continued {
        let alpha_on_x = spec.x.param == SweepParam::Alpha;
        let (layers, entries) = super::curves::layers(c.curves, alpha_on_x, Some(Color::BLACK));
        for q in c.curves.curves.iter().flat_map(|cv| cv.points.iter()) {
            curve_points.push(if alpha_on_x {
                [q.alpha, q.p]
            } else {
                [q.p, q.alpha]
            });
        }
        panel.layers.extend(layers);
        curve_entries.extend(entries);
    }
    // The classes' legend beside the frame (inside, any corner would hide a large
    // stretch of the map); the curves' inside, where it hides least.
    if !entries.is_empty() {
        panel.beside.push(Legend {
            corner: Corner::TopRight,
            entries,
        });
    }
    let (nx, ny) = (spec.x.n.max(1), spec.y.n.max(1));
    let fractions = |p: &[f64; 2]| [panel.x.fraction(p[0]), panel.y.fraction(p[1])];
    let placed: Vec<([f64; 2], usize)> = placed.iter().map(|(p, k)| (fractions(p), *k)).collect();
    let curve_points: Vec<[f64; 2]> = curve_points.iter().map(fractions).collect();
    if !curve_entries.is_empty() {
        let size = legend_size(&curve_entries);
        let corner = place(&[size], &placed, &curve_points, nx.max(ny))[0];
        panel.legends.push(Legend {
            corner,
            entries: curve_entries,
        });
    }
    // A family's parameter on an axis is left free in the title and the caption.
    let free = [spec.x.param, spec.y.param]
        .into_iter()
        .find(SweepParam::is_table)
        .unwrap_or(SweepParam::Alpha);
    panel.title = Some(crate::labels::family_title(&spec.table, free));
    // The table and what is fixed, as the diagram's caption begins.
    let mut head = vec![crate::labels::free_name(&spec.table, free)];
    for p in [SweepParam::Alpha, SweepParam::R] {
        if p != spec.x.param && p != spec.y.param {
            head.push(match p {
                SweepParam::Alpha => format!("\u{3b1} = {}", shortest(spec.alpha)),
                _ => format!("r = {}", shortest(spec.r)),
            });
        }
    }
    let start = match spec.start {
        bouncemap_engine::plane::PlaneStart::NearFixedPoint => {
            "next to the (1, 1) solution (cold where it does not exist)"
        }
        bouncemap_engine::plane::PlaneStart::Cold => "from the cold start",
    };
    let mut caption = format!(
        "{}: {}\u{d7}{} pixels, each an orbit started {start} and followed for up to {} table periods (early stop on cycles), coloured by what it settles on; chaotic: not settled with largest Lyapunov exponent above 10\u{207b}\u{00b3}.",
        head.join(", "),
        spec.x.n,
        spec.y.n,
        fmt_count(spec.transient),
    );
    if !drawn.is_empty() {
        caption.push_str(&format!(" Lines (analytic): {}.", drawn.join("; ")));
    }
    if let Some(c) = &continued {
        caption.push_str(&format!(
            " Black lines over the pixels: the two-parameter curves of the cycles up to period {} (solid: period doubling, dash-dotted: fold, dashed: border collision, dotted: grazing; circles: codimension-two points), as the curves command gives them; the (1, 1) period doubling among them is the analytic $\u{3b1}_{{PD}}$.",
            c.max_period
        ));
    }
    Figure {
        name: "plane".into(),
        panels: vec![panel],
        columns: 1,
        caption: vec![caption],
        size: (6.6, 3.4),
    }
}

/// The plot of the default figure (5.0 × 3.4 in, a caption of about four lines) in
/// points: a legend's share of it, for choosing where it goes.
const FRAME_PT: [f64; 2] = [319.0, 180.0];

/// A legend's width and height as fractions of the plot, with its inset (as the SVG
/// layer draws it: a 14 pt swatch, 1.35 lines per entry).
fn legend_size(entries: &[(Swatch, String)]) -> [f64; 2] {
    let widest = entries
        .iter()
        .map(|(_, t)| text::width(t, LEGEND_FONT))
        .fold(0.0, f64::max);
    let w = 3.5 + 23.5 + widest;
    let h = 3.5 + 3.0 + 1.35 * LEGEND_FONT * entries.len() as f64;
    [(w / FRAME_PT[0]).min(1.0), (h / FRAME_PT[1]).min(1.0)]
}

/// The corners of legends of `sizes` (fractions of the plot), each in the free corner
/// where it hides least, in order: the fewest pixels (`placed`: where, of which class)
/// unlike most of those beneath it, a hidden curve point weighing as `line` pixels (a
/// line of them: the curves have a point per row or column). Ties go to the bottom
/// right, top left, top right, bottom left in that order.
fn place(
    sizes: &[[f64; 2]],
    placed: &[([f64; 2], usize)],
    curve_points: &[[f64; 2]],
    line: usize,
) -> Vec<Corner> {
    let classes = placed.iter().map(|(_, k)| k + 1).max().unwrap_or(0);
    let hidden = |corner: Corner, size: [f64; 2]| {
        let under = |p: &[f64; 2]| covers(corner, size, p);
        let mut count = vec![0usize; classes];
        for (p, k) in placed {
            if under(p) {
                count[*k] += 1;
            }
        }
        let n: usize = count.iter().sum();
        let unlike = n - count.iter().max().copied().unwrap_or(0);
        unlike + curve_points.iter().filter(|p| under(p)).count() * line
    };
    let mut free = vec![
        Corner::BottomRight,
        Corner::TopLeft,
        Corner::TopRight,
        Corner::BottomLeft,
    ];
    sizes
        .iter()
        .map(|&size| {
            let best = (0..free.len())
                .min_by_key(|&i| hidden(free[i], size))
                .expect("a free corner for each legend");
            free.remove(best)
        })
        .collect()
}

/// Whether a legend of `size` in `corner` covers the point `p` (fractions of the plot).
fn covers(corner: Corner, size: [f64; 2], p: &[f64; 2]) -> bool {
    let x = match corner {
        Corner::TopLeft | Corner::BottomLeft => p[0] <= size[0],
        Corner::TopRight | Corner::BottomRight => p[0] >= 1.0 - size[0],
    };
    let y = match corner {
        Corner::BottomLeft | Corner::BottomRight => p[1] <= size[1],
        Corner::TopLeft | Corner::TopRight => p[1] >= 1.0 - size[1],
    };
    x && y
}

/// A class in words for the legend.
fn describe(c: Class) -> String {
    match c {
        Class::Period1 => "period 1".into(),
        Class::Period2 => "period 2".into(),
        Class::Period4 => "period 4".into(),
        Class::Period8 => "period 8".into(),
        Class::Periodic => "other periods".into(),
        Class::Sticking => "sticking".into(),
        Class::StickingUnresolved => "sticking, length beyond f64".into(),
        Class::Chaotic => "chaotic".into(),
        Class::Unresolved => "unresolved".into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use bouncemap_engine::jobs::grid::Axis as GridAxis;

    /// The classes' legend sits beside the frame (it would hide part of the map in any
    /// corner); given the continued curves, the analytic ones they hold are not drawn
    /// a second time (one line per curve, never two alike).
    #[test]
    fn the_map_keeps_its_legend_beside_and_draws_each_curve_once() {
        let axis = |param, lo, hi, n| GridAxis { param, lo, hi, n };
        let spec = PlaneSpec::new(
            bouncemap_engine::Table::fd(0.0).unwrap(),
            axis(SweepParam::Alpha, 0.45, 0.6, 12),
            axis(SweepParam::D, 0.0, 1.0, 6),
            0.45,
            0.8,
        );
        let pixels = vec![None; spec.len()];
        let analytic = bouncemap_engine::plane::curves(&spec).expect("an α axis");
        let lines = |f: &Figure| {
            f.panels[0]
                .layers
                .iter()
                .filter(|l| matches!(l, Layer::Lines { .. }))
                .count()
        };
        let alone = plane_figure(&spec, &pixels, Some(&analytic), None);
        assert!(lines(&alone) >= 1, "the analytic curves");
        assert_eq!(alone.panels[0].beside.len(), 1, "the classes beside");
        assert!(alone.panels[0]
            .legends
            .iter()
            .all(|l| l.entries.iter().all(|(s, _)| !s.band)));
        let none = bouncemap_engine::orbits::curves::Curves {
            curves: Vec::new(),
            codim2: Vec::new(),
            skipped: Vec::new(),
            unseeded: Vec::new(),
            seeding: Default::default(),
        };
        let with = plane_figure(
            &spec,
            &pixels,
            Some(&analytic),
            Some(Continued {
                curves: &none,
                max_period: 8,
            }),
        );
        assert_eq!(
            lines(&with),
            0,
            "no analytic line beside the continued ones"
        );
        assert!(with.caption[0].contains("up to period 8"));
    }

    /// A 20 × 10 plot of class 0 but for the cells `other` gives class 1.
    fn grid(other: impl Fn(f64, f64) -> bool) -> Vec<([f64; 2], usize)> {
        let mut out = Vec::new();
        for j in 0..10 {
            for i in 0..20 {
                let p = [(i as f64 + 0.5) / 20.0, (j as f64 + 0.5) / 10.0];
                out.push((p, usize::from(other(p[0], p[1]))));
            }
        }
        out
    }

    #[test]
    fn a_legend_goes_where_the_pixels_are_uniform() {
        // Mixed on the right half and at the top left: only the bottom left is uniform.
        let placed = grid(|x, y| {
            (x > 0.5 && ((x * 20.0) as usize).is_multiple_of(2)) || (x < 0.5 && y > 0.5 && x < 0.1)
        });
        assert_eq!(
            place(&[[0.3, 0.4]], &placed, &[], 20),
            vec![Corner::BottomLeft]
        );
        // Uniform everywhere: the first corner.
        let uniform = grid(|_, _| false);
        assert_eq!(
            place(&[[0.3, 0.4]], &uniform, &[], 20),
            vec![Corner::BottomRight]
        );
    }

    #[test]
    fn the_second_legend_avoids_the_first_and_the_curves() {
        let uniform = grid(|_, _| false);
        // A curve up the left edge: the top left and bottom left each hide some of it.
        let curve: Vec<[f64; 2]> = (0..10).map(|j| [0.05, (j as f64 + 0.5) / 10.0]).collect();
        assert_eq!(
            place(&[[0.3, 0.4], [0.2, 0.1]], &uniform, &curve, 20),
            vec![Corner::BottomRight, Corner::TopRight]
        );
    }

    #[test]
    fn a_legend_covers_its_corner_only() {
        let size = [0.3, 0.4];
        assert!(covers(Corner::TopLeft, size, &[0.1, 0.9]));
        assert!(!covers(Corner::TopLeft, size, &[0.1, 0.5]));
        assert!(covers(Corner::BottomRight, size, &[0.8, 0.2]));
        assert!(!covers(Corner::BottomRight, size, &[0.6, 0.2]));
        assert!(covers(Corner::TopRight, size, &[0.75, 0.65]));
        assert!(covers(Corner::BottomLeft, size, &[0.0, 0.0]));
    }
}
