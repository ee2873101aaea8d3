//! The stability panel: κ_c for the current r; f''(t̂*) of each (1, k) solution on a
//! labelled number line against the stable band κ_c < f'' < 0; the eigenvalues' moduli
//! as numbers and the eigenvalues against the unit circle on scaled axes; and the
//! stable region of the (1, k) solution in the (α, r) plane between its birth curve (B)
//! and α_PD (P), on labelled axes with the current parameters (◎).
//! It owns the orbit analysis (which the diagram and the phase plot also mark), run on
//! a thread of its own so it answers within milliseconds whatever a sweep is doing.

use super::{panel, Component, Effect, Registered, Shared, Workers};
use crate::tui::analysis::{orbit_info, FixedPoint, OrbitInfo};
use crate::tui::params::{fmt_num, ParamId, Touch};
use crate::tui::plot::canvas_marker;
use bouncemap_engine::kappa_c;
use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::canvas::{Canvas, Circle, Line as CanvasLine, Points};
use ratatui::widgets::{Paragraph, Widget, Wrap};

/// The stability panel; it runs the orbit analysis, whose result it puts in
/// [`Shared::orbits`] for every panel.
#[derive(Default)]
pub struct Stability {
    pub gen: u64,
    pending: bool,
}

impl Stability {
    /// A new analysis started under generation `gen`.
    pub fn started(&mut self, gen: u64, shared: &mut Shared) {
        self.gen = gen;
        self.pending = true;
        shared.orbits = None;
    }
}

impl Component for Stability {
    type Msg = Result<OrbitInfo, String>;

    fn changed(&mut self, id: ParamId, shared: &mut Shared) {
        if id.touches() == Touch::System {
            shared.effect(Effect::Start(Self::TARGET));
        }
    }

    fn start(&mut self, shared: &mut Shared, workers: &Workers) {
        let (sys, k) = (shared.system(), shared.params.k);
        // Not paused with the rest: a few milliseconds, and the panels need it.
        let gen = workers.spawn(Self::ADDRESS, "orbit-analysis", move |t| {
            if !t.stale() {
                t.send(orbit_info(&sys, k));
            }
        });
        self.started(gen, shared);
    }

    fn receive(&mut self, gen: u64, msg: Self::Msg, shared: &mut Shared) {
        if gen != self.gen {
            return;
        }
        shared.orbits = Some(msg);
        self.pending = false;
        shared.dirty = true;
    }

    fn busy(&self) -> bool {
        self.pending
    }

    fn computing(&self, shared: &Shared) -> Option<String> {
        shared.orbits.is_none().then(|| "orbits".to_string())
    }

    fn draw(&self, app: &Shared, area: Rect, buf: &mut Buffer) {
        render(app, area, buf);
    }
}

fn render(app: &Shared, area: Rect, buf: &mut Buffer) {
    let block = panel(app, format!(" Stability of (1, {}) ", app.params.k), false);
    let inner = block.inner(area);
    block.render(area, buf);
    if inner.height < 3 {
        return;
    }
    let kc = kappa_c(app.params.r);
    let fixed = match &app.orbits {
        Some(Ok(i)) => Some(&i.fixed[..]),
        _ => None,
    };
    // A short panel keeps its essentials: the f'' band (κ_c is on its ticks), one line
    // per solution, and room for the drawings; the words go.
    let short = inner.height < 14;
    let mut lines = Vec::new();
    if !short {
        lines.push(Line::from(vec![
            Span::raw("κ_c = "),
            Span::styled(format!("{kc:.4}"), app.theme.focus()),
            Span::raw(format!("  (r = {})", fmt_num(app.params.r))),
        ]));
    }
    let (band, ticks) = band_lines(app, kc, fixed.unwrap_or(&[]), inner.width as usize);
    lines.push(band);
    lines.push(ticks);
    match &app.orbits {
        None => lines.push(Line::styled("solving (1, k)…", app.theme.dim())),
        Some(Err(e)) => lines.push(Line::styled(
            format!("(1, k) analysis {e}"),
            app.theme.dim(),
        )),
        Some(Ok(i)) if i.fixed.is_empty() => lines.push(Line::styled(
            format!("no (1, {}) solution at this α", app.params.k),
            app.theme.dim(),
        )),
        Some(Ok(i)) => {
            // Narrow panels drop the words: ◆ is stable, ◇ unstable (see the legend).
            let wide = inner.width >= 34 && !short;
            for f in &i.fixed {
                let head = match (f.stable, wide) {
                    (true, true) => "◆ stable  ",
                    (false, true) => "◇ unstable",
                    (true, false) => "◆",
                    (false, false) => "◇",
                };
                let [a, b] = f.eig.map(|(re, im)| re.hypot(im));
                if short {
                    lines.push(Line::from(vec![
                        Span::styled(head, app.theme.mark()),
                        Span::raw(format!(
                            " t̂* {:.3} f'' {:.3} |λ| {:.2},{:.2}",
                            f.phase, f.f2, a, b
                        )),
                    ]));
                    continue;
                }
                lines.push(Line::from(vec![
                    Span::styled(head, app.theme.mark()),
                    Span::raw(format!(" t̂* {:.4}  f'' {:.4}", f.phase, f.f2)),
                ]));
                lines.push(Line::from(format!("  |λ| {}, {}", modulus(a), modulus(b))));
            }
        }
    }
    // The diagram's value at the cursor, with the evidence for its cycle (where there
    // is room for the drawings too).
    if let Some(at) = app.at_cursor.as_ref().filter(|_| !short) {
        for l in wrap_words(at, inner.width as usize) {
            lines.push(Line::styled(l, app.theme.mark2()));
        }
    }
    // The continued branch under the diagram's cursor (while the diagram has the focus).
    if let (Some((i, p)), Some(Ok(sk)), false) = (&app.under_cursor, &app.branches, short) {
        let b = &sk.branches[*i];
        lines.push(Line::from(vec![
            Span::styled(format!("branch ({}, {})", b.n, b.k), app.theme.mark2()),
            Span::raw(format!(
                " at α {}: {}",
                fmt_num(p.alpha),
                if p.stable { "stable" } else { "unstable" }
            )),
        ]));
        lines.push(Line::from(format!(
            "  μ {}",
            multipliers(&p.multipliers.map(|c| (c.re, c.im)))
        )));
    }
    // Proofs (`V`): the verdicts of the cycle asked about, even on a short panel.
    if app.show_proofs {
        match &app.proof {
            None => lines.push(Line::styled(
                "proving (interval arithmetic)…",
                app.theme.dim(),
            )),
            Some(Err(e)) => lines.push(Line::styled(format!("proof: {e}"), app.theme.error())),
            Some(Ok(v)) => {
                if !short {
                    for l in wrap_words(&format!("proofs of {}:", v.what), inner.width as usize) {
                        lines.push(Line::styled(l, app.theme.focus()));
                    }
                }
                for l in &v.lines {
                    let (mark, style) = if l.contains("not proved") {
                        ("✗", app.theme.error())
                    } else {
                        ("✓", app.theme.stable())
                    };
                    for w in wrap_words(&format!("{mark} {l}"), inner.width as usize) {
                        lines.push(Line::styled(w, style));
                    }
                }
            }
        }
    }
    let text_h = (lines.len() as u16).min(inner.height);
    let [text, plots] =
        Layout::vertical([Constraint::Length(text_h), Constraint::Min(0)]).areas(inner);
    Paragraph::new(lines).render(text, buf);
    if plots.height < 4 {
        return;
    }
    let circle_w = (plots.height * 2 + 2).min(plots.width / 2);
    let [circ, region] = Layout::horizontal([Constraint::Length(circle_w), Constraint::Min(0)])
        .spacing(1)
        .areas(plots);
    eigen_circle(app, fixed, circ, buf);
    region_plot(app, region, buf);
}

/// `text` in lines of at most `width` characters, broken between words.
fn wrap_words(text: &str, width: usize) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for w in text.split(' ') {
        match out.last_mut() {
            Some(l) if l.chars().count() + 1 + w.chars().count() <= width.max(1) => {
                l.push(' ');
                l.push_str(w);
            }
            _ => out.push(w.to_string()),
        }
    }
    out
}

/// A pair of multipliers: two reals, or a complex pair as re ± im i.
fn multipliers(m: &[(f64, f64); 2]) -> String {
    let [(a, ai), (b, _)] = *m;
    if ai.abs() > 1e-12 * (1.0 + a.abs()) {
        format!("{:.4} ± {:.4}i", a, ai.abs())
    } else {
        format!("{}, {}", modulus_signed(a), modulus_signed(b))
    }
}

/// A real multiplier: four decimals, or the shortest form when huge or tiny.
fn modulus_signed(x: f64) -> String {
    if x.is_finite() && (1e-3..1e4).contains(&x.abs()) {
        format!("{x:.4}")
    } else {
        bouncemap_engine::fmt_value(x)
    }
}

/// An eigenvalue modulus: four decimals, or the shortest form when huge or tiny.
fn modulus(x: f64) -> String {
    if x.is_finite() && (1e-3..1e4).contains(&x) {
        format!("{x:.4}")
    } else {
        bouncemap_engine::fmt_value(x)
    }
}

/// The f'' number line from 1.5 κ_c to a little above 0 with the stable band
/// κ_c < f'' < 0 and each solution's f'' (an arrow at the end for values beyond it),
/// and below it the labelled ticks: both ends, κ_c and 0.
fn band_lines<'a>(
    app: &Shared,
    kc: f64,
    fixed: &[FixedPoint],
    width: usize,
) -> (Line<'a>, Line<'a>) {
    const LABEL: &str = "f'' ";
    let w = width.saturating_sub(LABEL.len()).max(12);
    let lo = 1.5 * kc;
    let hi = -0.25 * kc;
    let col = |x: f64| {
        (((x - lo) / (hi - lo)) * (w as f64 - 1.0))
            .round()
            .clamp(0.0, w as f64 - 1.0) as usize
    };
    let mut cells: Vec<(&str, Style)> = vec![("─", app.theme.dim()); w];
    let (a, b) = (col(kc), col(0.0));
    for c in cells.iter_mut().take(b + 1).skip(a) {
        *c = ("═", app.theme.stable());
    }
    cells[a] = ("[", app.theme.stable());
    cells[b] = ("]", app.theme.stable());
    for f in fixed {
        if f.f2.is_finite() {
            let glyph = match (f.f2 < lo, f.f2 > hi, f.stable) {
                (true, _, _) => "◂",
                (_, true, _) => "▸",
                (_, _, true) => "◆",
                _ => "◇",
            };
            cells[col(f.f2)] = (glyph, app.theme.mark());
        }
    }
    let mut spans = vec![Span::styled(LABEL, app.theme.dim())];
    spans.extend(cells.into_iter().map(|(s, st)| Span::styled(s, st)));
    let ticks = tick_text(
        w,
        &[
            (a, "κ_c".to_string()),
            (b, "0".to_string()),
            (0, format!("{lo:.2}")),
            (w - 1, format!("{hi:.2}")),
        ],
    );
    let ticks = Line::from(vec![
        Span::raw(" ".repeat(LABEL.len())),
        Span::styled(ticks, app.theme.dim()),
    ]);
    (Line::from(spans), ticks)
}

/// `w` columns with each label centred on its column (kept inside the line), later
/// labels skipped where they would touch an earlier one. The labels are placed in the
/// order given, so the first ones win.
pub fn tick_text(w: usize, labels: &[(usize, String)]) -> String {
    let mut cells = vec![' '; w];
    let mut taken = vec![false; w];
    for (c, text) in labels {
        let chars: Vec<char> = text.chars().collect();
        let n = chars.len();
        if n > w {
            continue;
        }
        let start = c.saturating_sub(n / 2).min(w - n);
        let (from, to) = (start.saturating_sub(1), (start + n + 1).min(w));
        if taken[from..to].iter().any(|&t| t) {
            continue;
        }
        for (i, ch) in chars.into_iter().enumerate() {
            cells[start + i] = ch;
            taken[start + i] = true;
        }
    }
    cells.into_iter().collect()
}

/// The radial scale of the eigenvalue plot: linear inside the unit circle, then
/// logarithmic (half a radius per decade), so an eigenvalue of any size is drawn at its
/// place: |λ| = 10 on the ring at 1.5, 100 on the ring at 2.
pub fn radial(m: f64) -> f64 {
    if m <= 1.0 {
        m
    } else {
        1.0 + 0.5 * m.log10()
    }
}

/// The eigenvalues of each (1, k) solution (◆ stable, ◇ unstable) against the unit
/// circle; outside it the radius is logarithmic (see [`radial`]), with a dotted ring
/// and a tick at |λ| = 10 when some eigenvalue lies beyond the circle.
fn eigen_circle(app: &Shared, fixed: Option<&[FixedPoint]>, area: Rect, buf: &mut Buffer) {
    let fixed = fixed.unwrap_or(&[]);
    let place = |(re, im): (f64, f64)| {
        let m = re.hypot(im);
        if !m.is_finite() || m == 0.0 {
            return (0.0, 0.0);
        }
        let s = radial(m.min(1e6)) / m;
        (re * s, im * s)
    };
    let marks: Vec<(f64, f64, &str)> = fixed
        .iter()
        .flat_map(|f| {
            let g = if f.stable { "◆" } else { "◇" };
            f.eig.map(|e| {
                let (x, y) = place(e);
                (x, y, g)
            })
        })
        .collect();
    let outside = marks.iter().any(|&(x, y, _)| x.hypot(y) > 1.0);
    let bound = marks
        .iter()
        .map(|&(x, y, _)| x.abs().max(y.abs()) + 0.15)
        .fold(1.5, f64::max);
    let theme = &app.theme;
    Canvas::default()
        .marker(canvas_marker(app.marker))
        .x_bounds([-bound, bound])
        .y_bounds([-bound, bound])
        .paint(|ctx| {
            let axis = theme.axis().fg.unwrap_or_default();
            ctx.draw(&CanvasLine::new(-bound, 0.0, bound, 0.0, axis));
            ctx.draw(&CanvasLine::new(0.0, -bound, 0.0, bound, axis));
            ctx.draw(&Circle {
                x: 0.0,
                y: 0.0,
                radius: 1.0,
                color: theme.stable().fg.unwrap_or_default(),
            });
            if outside {
                let ring: Vec<(f64, f64)> = (0..48)
                    .map(|i| {
                        let t = i as f64 * std::f64::consts::TAU / 48.0;
                        (1.5 * t.cos(), 1.5 * t.sin())
                    })
                    .collect();
                ctx.draw(&Points {
                    coords: &ring,
                    color: axis,
                });
            }
            ctx.layer();
            ctx.print(-bound, bound, Line::styled("λ", theme.dim()));
            // Radius ticks on the imaginary axis, where real eigenvalues never sit.
            ctx.print(0.1, 1.0, Line::styled("1", theme.dim()));
            if outside {
                ctx.print(0.1, 1.5, Line::styled("10", theme.dim()));
            }
            for &(x, y, g) in &marks {
                ctx.print(x, y, Line::styled(g, theme.mark()));
            }
        })
        .render(area, buf);
}

/// 1, 1.5, 2, 3, 5 times a power of ten, at or above `x`.
fn nice_ceil(x: f64) -> f64 {
    let p = 10f64.powf(x.log10().floor());
    [1.0, 1.5, 2.0, 3.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * p)
        .find(|&v| v >= x * (1.0 - 1e-12))
        .unwrap_or(10.0 * p)
}

/// Where the (1, k) solution is stable in the (α, r) plane: its birth curve (B) and the
/// curve where its stability ends (P where that is period doubling), the current
/// parameters (◎), with labelled axes: α from 0 to a little beyond the larger of the
/// curves and the current α, r from 0 to 1.
fn region_plot(app: &Shared, area: Rect, buf: &mut Buffer) {
    let rows = match &app.orbits {
        Some(Ok(i)) if !i.region.is_empty() => &i.region,
        Some(Err(_)) => {
            Paragraph::new("(α, r) region not available")
                .style(app.theme.dim())
                .wrap(Wrap { trim: true })
                .render(area, buf);
            return;
        }
        _ => return,
    };
    if area.width < 10 || area.height < 4 {
        return;
    }
    let amax = nice_ceil(
        rows.iter()
            .flat_map(|r| r.intervals.iter().map(|iv| iv.1))
            .filter(|a| a.is_finite())
            .fold(app.params.alpha, f64::max)
            * 1.1,
    );
    let theme = &app.theme;
    // Axes: r labels in a margin of 4 columns, α labels in the bottom row.
    const MARGIN: u16 = 4;
    let plot = Rect {
        x: area.x + MARGIN,
        y: area.y,
        width: area.width - MARGIN,
        height: area.height - 1,
    };
    for dy in 0..plot.height {
        let label = match dy {
            0 => "1.0┤".to_string(),
            d if d == plot.height - 1 => "0.0┤".to_string(),
            d if d == plot.height / 2 => "  r│".to_string(),
            _ => "   │".to_string(),
        };
        buf.set_string(area.x, area.y + dy, label, theme.axis());
    }
    let w = plot.width as usize;
    let ticks = tick_text(
        w,
        &[
            (0, "0".to_string()),
            (w - 1, fmt_num(amax)),
            (w / 2, "α".to_string()),
        ],
    );
    let bottom = area.y + area.height - 1;
    buf.set_string(area.x + MARGIN - 1, bottom, "└", theme.axis());
    buf.set_string(plot.x, bottom, ticks, theme.axis());
    // The curves, joined between neighbouring rows of r.
    let mut births = Vec::new();
    let mut ends = Vec::new();
    for pair in rows.windows(2) {
        for (a, b) in pair[0].intervals.iter().zip(&pair[1].intervals) {
            births.push((a.0, pair[0].r, b.0, pair[1].r));
            ends.push((a.1, pair[0].r, b.1, pair[1].r));
        }
    }
    // Labels at the top of each curve (the highest r with an interval).
    let top = rows.iter().rev().find(|r| !r.intervals.is_empty());
    let here = (app.params.alpha.min(amax), app.params.r);
    Canvas::default()
        .marker(canvas_marker(app.marker))
        .x_bounds([0.0, amax])
        .y_bounds([0.0, 1.0])
        .paint(|ctx| {
            let birth = theme.stable().fg.unwrap_or_default();
            let end = theme.mark2().fg.unwrap_or_default();
            for &(x1, y1, x2, y2) in &births {
                ctx.draw(&CanvasLine::new(x1, y1, x2, y2, birth));
            }
            for &(x1, y1, x2, y2) in &ends {
                ctx.draw(&CanvasLine::new(x1, y1, x2, y2, end));
            }
            ctx.layer();
            if let Some(t) = top {
                for &(b, e, pd) in &t.intervals {
                    ctx.print(b, t.r, Line::styled("B", theme.stable()));
                    ctx.print(
                        e,
                        t.r,
                        Line::styled(if pd { "P" } else { "E" }, theme.mark2()),
                    );
                }
            }
            ctx.print(here.0, here.1, Line::styled("◎", theme.mark()));
        })
        .render(plot, buf);
}
