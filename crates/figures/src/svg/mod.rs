//! The shared drawing layer: a [`Figure`] laid out on a page of the asked size and
//! written as SVG. Units are points (1/72 inch); the SVG's width and height are the
//! page's size in points, so it prints at the size it was made for.
//!
//! The look is a physics journal's: a closed frame per panel with ticks pointing in on
//! all four sides (major and minor), tick labels outside, the axis label under the x
//! axis and along the y axis, the panel letter above the frame's left, legends in a
//! corner box (or beside the frame, where every corner would hide data), and a caption in small type below the panels. Dense point clouds are
//! drawn as small dots whose opacities add up: a cell hit n times is as dark as n
//! overlaid dots, 1 − (1 − a)ⁿ.

use super::text::{self, Level};
use crate::model::{Axis, Color, Corner, Dash, Figure, Legend, Marker, Panel, Scale, Swatch};
use std::fmt::Write;

mod layers;
use layers::layer;

/// Font sizes, in points.
pub const TICK_FONT: f64 = 7.0;
pub const LABEL_FONT: f64 = 8.0;
pub const LETTER_FONT: f64 = 8.5;
pub const TITLE_FONT: f64 = 7.5;
pub const LEGEND_FONT: f64 = 6.3;
pub const CAPTION_FONT: f64 = 6.5;
/// Line widths and lengths, in points.
const FRAME_WIDTH: f64 = 0.6;
const TICK_WIDTH: f64 = 0.5;
const MAJOR_TICK: f64 = 3.0;
const MINOR_TICK: f64 = 1.6;
const PAD: f64 = 3.0;
/// Gap between a frame and its tick labels.
const GAP: f64 = 2.5;
/// Side of the cells dense points are counted in, radius and opacity of one dot.
const DOT_CELL: f64 = 0.3;
const DOT_RADIUS: f64 = 0.32;
const DOT_ALPHA: f64 = 0.2;
/// Opacity steps of the dots (one path each).
const DOT_LEVELS: u32 = 16;
const DISC_RADIUS: f64 = 1.7;
const CIRCLE_RADIUS: f64 = 2.3;

/// A number for the SVG: at most two decimals, no trailing zeros.
fn n(v: f64) -> String {
    let s = format!("{v:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" || s.is_empty() {
        "0".into()
    } else {
        s.to_string()
    }
}

/// A length given in hundredths of a point, as short as SVG allows: 5 → ".05",
/// −150 → "-1.5".
fn hundredths(v: i64) -> String {
    let (int, frac) = (v.abs() / 100, v.abs() % 100);
    let mut s = String::from(if v < 0 { "-" } else { "" });
    if int != 0 {
        s.push_str(&int.to_string());
    }
    if frac != 0 {
        if frac % 10 == 0 {
            let _ = write!(s, ".{}", frac / 10);
        } else {
            let _ = write!(s, ".{frac:02}");
        }
    }
    if v == 0 {
        s.push('0');
    }
    s
}

fn esc(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            c if (c as u32) < 0x20 && c != '\t' => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

/// Horizontal anchoring of a text.
#[derive(Clone, Copy, PartialEq)]
enum Anchor {
    Start,
    Middle,
    End,
}

/// A `<text>` element for a label in markup, its baseline at (x, y); `rotate` turns it
/// to read upwards about that point.
fn text_el(markup: &str, x: f64, y: f64, size: f64, anchor: Anchor, rotate: bool) -> String {
    let mut s = format!(
        "<text x=\"{}\" y=\"{}\" font-size=\"{}\" xml:space=\"preserve\"",
        n(x),
        n(y),
        n(size)
    );
    match anchor {
        Anchor::Start => {}
        Anchor::Middle => s.push_str(" text-anchor=\"middle\""),
        Anchor::End => s.push_str(" text-anchor=\"end\""),
    }
    if rotate {
        let _ = write!(s, " transform=\"rotate(-90 {} {})\"", n(x), n(y));
    }
    s.push('>');
    let mut shift = 0.0;
    for run in text::parse(markup) {
        let target = run.level.shift() * size;
        let plain = !run.italic && run.level == Level::Base && target == shift;
        if plain {
            s.push_str(&esc(&run.text));
            continue;
        }
        s.push_str("<tspan");
        if run.italic {
            s.push_str(" font-style=\"italic\"");
        }
        if run.level != Level::Base {
            let _ = write!(s, " font-size=\"{}\"", n(size * run.level.scale()));
        }
        if target != shift {
            let _ = write!(s, " dy=\"{}\"", n(target - shift));
            shift = target;
        }
        let _ = write!(s, ">{}</tspan>", esc(&run.text));
    }
    s.push_str("</text>\n");
    s
}

/// Major ticks (value, label) and minor ticks of an axis.
#[derive(Debug, Default)]
struct Ticks {
    major: Vec<(f64, String)>,
    minor: Vec<f64>,
}

/// Decimals a tick step needs.
fn decimals(step: f64) -> usize {
    let e = step.log10().floor();
    let mant = step / 10f64.powf(e);
    let d = (-e).max(0.0) as usize;
    if (mant - 2.5).abs() < 1e-9 {
        d + 1
    } else {
        d
    }
}

/// Ticks of a linear axis of `length` points: the finest "nice" step (1, 2 or 5 times
/// a power of ten) whose labels do not crowd.
fn linear_ticks(lo: f64, hi: f64, length: f64, horizontal: bool) -> Ticks {
    let span = hi - lo;
    if span.is_nan() || span <= 0.0 || !span.is_finite() {
        return Ticks::default();
    }
    let e0 = span.log10().floor() as i32;
    let mut best = None;
    'search: for e in (e0 - 4)..=(e0 + 1) {
        for m in [1.0, 2.0, 5.0] {
            let step = m * 10f64.powi(e);
            let first = (lo / step - 1e-9).ceil() as i64;
            let last = (hi / step + 1e-9).floor() as i64;
            let count = last - first + 1;
            if !(2..=12).contains(&count) {
                continue;
            }
            let dec = decimals(step);
            let major: Vec<(f64, String)> = (first..=last)
                .map(|k| {
                    let v = k as f64 * step;
                    (v, crate::format::fmt_fixed(v, dec))
                })
                .collect();
            let gap = length * step / span;
            let need = if horizontal {
                (major
                    .iter()
                    .map(|(_, l)| text::width(l, TICK_FONT))
                    .fold(0.0, f64::max)
                    + 6.0)
                    .max(28.0)
            } else {
                (TICK_FONT * 1.8).max(18.0)
            };
            if gap >= need {
                let sub = if m == 2.0 { 4.0 } else { 5.0 };
                let mstep = step / sub;
                let minor = if length * mstep / span >= 2.5 {
                    let f = (lo / mstep - 1e-9).ceil() as i64;
                    let l = (hi / mstep + 1e-9).floor() as i64;
                    (f..=l)
                        .filter(|k| k % sub as i64 != 0)
                        .map(|k| k as f64 * mstep)
                        .collect()
                } else {
                    Vec::new()
                };
                best = Some(Ticks { major, minor });
                break 'search;
            }
        }
    }
    best.unwrap_or_else(|| Ticks {
        major: vec![
            (lo, crate::format::fmt_fixed(lo, decimals(span / 2.0) + 1)),
            (hi, crate::format::fmt_fixed(hi, decimals(span / 2.0) + 1)),
        ],
        minor: Vec::new(),
    })
}

/// Ticks of a logarithmic axis: decades labelled 10^k, minor ticks at 2…9 × 10^k.
fn log_ticks(lo: f64, hi: f64) -> Ticks {
    let (a, b) = (lo.log10(), hi.log10());
    let mut t = Ticks::default();
    for k in (a.floor() as i32)..=(b.ceil() as i32) {
        let v = 10f64.powi(k);
        if v >= lo * (1.0 - 1e-9) && v <= hi * (1.0 + 1e-9) {
            let label = if k == 0 {
                "1".to_string()
            } else {
                format!("10$^{{{}}}$", crate::format::fmt_fixed(k as f64, 0))
            };
            t.major.push((v, label));
        }
        for m in 2..10 {
            let w = m as f64 * v;
            if w >= lo && w <= hi {
                t.minor.push(w);
            }
        }
    }
    t
}

fn ticks(axis: &Axis, length: f64, horizontal: bool) -> Ticks {
    match axis.scale {
        Scale::Linear => linear_ticks(axis.lo, axis.hi, length, horizontal),
        Scale::Log => log_ticks(axis.lo, axis.hi),
    }
}

/// A panel's frame on the page.
#[derive(Clone, Copy, Debug)]
struct Frame {
    x0: f64,
    y0: f64,
    x1: f64,
    y1: f64,
}

impl Frame {
    fn px(&self, a: &Axis, v: f64) -> f64 {
        self.x0 + a.fraction(v) * (self.x1 - self.x0)
    }
    fn py(&self, a: &Axis, v: f64) -> f64 {
        self.y1 - a.fraction(v) * (self.y1 - self.y0)
    }
}

fn dasharray(d: Dash) -> &'static str {
    match d {
        Dash::Solid => "",
        Dash::Dashed => " stroke-dasharray=\"3.2 1.8\"",
        Dash::Dotted => " stroke-dasharray=\"0.1 1.5\" stroke-linecap=\"round\"",
        Dash::DashDot => " stroke-dasharray=\"3.2 1.4 0.1 1.4\" stroke-linecap=\"round\"",
    }
}

fn marker_el(out: &mut String, m: Marker, c: Color, x: f64, y: f64) {
    match m {
        Marker::Disc => {
            let _ = writeln!(
                out,
                "<circle cx=\"{}\" cy=\"{}\" r=\"{DISC_RADIUS}\" fill=\"{}\"/>",
                n(x),
                n(y),
                c.hex()
            );
        }
        Marker::Circle => {
            let _ = writeln!(
                out,
                "<circle cx=\"{}\" cy=\"{}\" r=\"{CIRCLE_RADIUS}\" fill=\"none\" stroke=\"{}\" stroke-width=\"0.6\"/>",
                n(x),
                n(y),
                c.hex()
            );
        }
    }
}

fn swatch(out: &mut String, s: &Swatch, x: f64, y: f64) {
    if s.band {
        let _ = writeln!(
            out,
            "<rect x=\"{}\" y=\"{}\" width=\"12\" height=\"5\" fill=\"{}\"/>",
            n(x + 1.0),
            n(y - 2.5),
            s.color.hex()
        );
    }
    if let Some(d) = s.line {
        let _ = writeln!(
            out,
            "<path d=\"M{} {}H{}\" stroke=\"{}\" stroke-width=\"1\"{}/>",
            n(x),
            n(y),
            n(x + 14.0),
            s.color.hex(),
            dasharray(d)
        );
    }
    if let Some(m) = s.marker {
        marker_el(out, m, s.color, x + 7.0, y);
    }
}

/// The widest entry text of a legend, at [`LEGEND_FONT`].
fn widest_entry(l: &Legend) -> f64 {
    l.entries
        .iter()
        .map(|(_, t)| text::width(t, LEGEND_FONT))
        .fold(0.0, f64::max)
}

/// A legend box's width at [`LEGEND_FONT`], in points.
fn legend_width(l: &Legend) -> f64 {
    3.0 + 14.0 + 3.0 + widest_entry(l) + 3.5
}

/// Room between a frame and the legends beside it.
const BESIDE_GAP: f64 = 6.0;

/// The room the legends beside a panel's frame take on its right.
fn beside_width(p: &Panel) -> f64 {
    p.beside
        .iter()
        .map(legend_width)
        .fold(0.0, f64::max)
        .max(0.0)
        + if p.beside.is_empty() { 0.0 } else { BESIDE_GAP }
}

fn legend(out: &mut String, f: &Frame, l: &Legend) {
    let inset = 3.5;
    // A legend wider than its frame gets smaller type (not below 5 pt).
    let room = (f.x1 - f.x0) - 2.0 * inset - 23.5;
    let (x, y) = match l.corner {
        Corner::TopLeft => (f.x0 + inset, f.y0 + inset),
        Corner::TopRight => (f.x1 - inset, f.y0 + inset),
        Corner::BottomLeft => (f.x0 + inset, f.y1 - inset),
        Corner::BottomRight => (f.x1 - inset, f.y1 - inset),
    };
    let right = matches!(l.corner, Corner::TopRight | Corner::BottomRight);
    let bottom = matches!(l.corner, Corner::BottomLeft | Corner::BottomRight);
    legend_box(out, l, (x, y), (right, bottom), room);
}

/// The legends beside frame `f`, on its right, one under the other.
fn legends_beside(out: &mut String, f: &Frame, p: &Panel) {
    let mut y = f.y0;
    for l in &p.beside {
        y += legend_box(
            out,
            l,
            (f.x1 + BESIDE_GAP, y),
            (false, false),
            f64::INFINITY,
        ) + 4.0;
    }
}

/// A legend's box with its corner at `at`: the box extends left of it where `anchor.0`
/// (right-aligned), up where `anchor.1` (bottom-aligned); the type shrinks (not below
/// 5 pt) to fit `room` points of text. Returns the box's height.
fn legend_box(
    out: &mut String,
    l: &Legend,
    at: (f64, f64),
    anchor: (bool, bool),
    room: f64,
) -> f64 {
    if l.entries.is_empty() {
        return 0.0;
    }
    let widest = widest_entry(l);
    let size = if widest > room && widest > 0.0 {
        (LEGEND_FONT * room / widest).max(5.0)
    } else {
        LEGEND_FONT
    };
    let text_w = widest * size / LEGEND_FONT;
    let row = size * 1.35;
    let w = 3.0 + 14.0 + 3.0 + text_w + 3.5;
    let h = 2.0 + row * l.entries.len() as f64 + 1.0;
    let x = if anchor.0 { at.0 - w } else { at.0 };
    let y = if anchor.1 { at.1 - h } else { at.1 };
    let _ = writeln!(
        out,
        "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"#ffffff\" fill-opacity=\"0.88\" stroke=\"#a0a0a0\" stroke-width=\"0.4\"/>",
        n(x),
        n(y),
        n(w),
        n(h)
    );
    for (i, (s, t)) in l.entries.iter().enumerate() {
        let cy = y + 2.0 + row * (i as f64 + 0.5);
        swatch(out, s, x + 3.0, cy);
        out.push_str(&text_el(
            t,
            x + 20.0,
            cy + 0.36 * size,
            size,
            Anchor::Start,
            false,
        ));
    }
    h
}

/// The axes: frame, inward ticks on four sides, tick labels, axis labels.
fn axes(out: &mut String, f: &Frame, p: &Panel, xt: &Ticks, yt: &Ticks, ylabel_x: f64) {
    let mut d = String::new();
    for (v, _) in &xt.major {
        let x = f.px(&p.x, *v);
        let _ = write!(
            d,
            "M{x} {}v-{MAJOR_TICK}M{x} {}v{MAJOR_TICK}",
            n(f.y1),
            n(f.y0),
            x = n(x)
        );
    }
    for v in &xt.minor {
        let x = f.px(&p.x, *v);
        let _ = write!(
            d,
            "M{x} {}v-{MINOR_TICK}M{x} {}v{MINOR_TICK}",
            n(f.y1),
            n(f.y0),
            x = n(x)
        );
    }
    for (v, _) in &yt.major {
        let y = f.py(&p.y, *v);
        let _ = write!(
            d,
            "M{} {y}h{MAJOR_TICK}M{} {y}h-{MAJOR_TICK}",
            n(f.x0),
            n(f.x1),
            y = n(y)
        );
    }
    for v in &yt.minor {
        let y = f.py(&p.y, *v);
        let _ = write!(
            d,
            "M{} {y}h{MINOR_TICK}M{} {y}h-{MINOR_TICK}",
            n(f.x0),
            n(f.x1),
            y = n(y)
        );
    }
    let _ = writeln!(
        out,
        "<path d=\"{d}\" stroke=\"#000000\" stroke-width=\"{TICK_WIDTH}\" fill=\"none\"/>"
    );
    let _ = writeln!(
        out,
        "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#000000\" stroke-width=\"{FRAME_WIDTH}\"/>",
        n(f.x0),
        n(f.y0),
        n(f.x1 - f.x0),
        n(f.y1 - f.y0)
    );
    let xbase = f.y1 + GAP + 0.76 * TICK_FONT;
    for (v, l) in &xt.major {
        out.push_str(&text_el(
            l,
            f.px(&p.x, *v),
            xbase,
            TICK_FONT,
            Anchor::Middle,
            false,
        ));
    }
    for (v, l) in &yt.major {
        out.push_str(&text_el(
            l,
            f.x0 - GAP,
            f.py(&p.y, *v) + 0.36 * TICK_FONT,
            TICK_FONT,
            Anchor::End,
            false,
        ));
    }
    out.push_str(&text_el(
        &p.x.label,
        0.5 * (f.x0 + f.x1),
        xbase + 0.3 * TICK_FONT + 2.0 + 0.8 * LABEL_FONT,
        LABEL_FONT,
        Anchor::Middle,
        false,
    ));
    out.push_str(&text_el(
        &p.y.label,
        ylabel_x,
        0.5 * (f.y0 + f.y1),
        LABEL_FONT,
        Anchor::Middle,
        true,
    ));
}

/// Room above the frame, below it and on its right, in points.
fn top_margin(fig: &Figure) -> f64 {
    let header = fig
        .panels
        .iter()
        .any(|p| p.letter.is_some() || p.title.is_some());
    if header {
        PAD + LETTER_FONT * 1.25
    } else {
        PAD + 3.0
    }
}
const BOTTOM_MARGIN: f64 = GAP + 1.06 * TICK_FONT + 2.0 + 1.05 * LABEL_FONT + PAD;
/// Least room right of a frame.
const RIGHT_MARGIN: f64 = 6.0;

/// The figure as an SVG document, `size` inches.
pub fn to_svg(fig: &Figure, size: (f64, f64)) -> String {
    let (w, h) = (size.0 * 72.0, size.1 * 72.0);
    let caption: Vec<String> = fig
        .caption
        .iter()
        .flat_map(|c| text::wrap(c, CAPTION_FONT, w - 2.0 * PAD))
        .collect();
    let caption_h = if caption.is_empty() {
        0.0
    } else {
        caption.len() as f64 * CAPTION_FONT * 1.3 + PAD
    };
    let cols = fig.columns.max(1);
    let rows = fig.panels.len().div_ceil(cols).max(1);
    let (cell_w, cell_h) = (w / cols as f64, (h - caption_h) / rows as f64);
    let top = top_margin(fig);
    let frame_h = (cell_h - top - BOTTOM_MARGIN).max(10.0);
    // One left margin for all panels, from the widest y tick label, so frames align.
    let yticks: Vec<Ticks> = fig
        .panels
        .iter()
        .map(|p| ticks(&p.y, frame_h, false))
        .collect();
    let widest = yticks
        .iter()
        .flat_map(|t| t.major.iter().map(|(_, l)| text::width(l, TICK_FONT)))
        .fold(0.0, f64::max);
    let left = PAD + 1.05 * LABEL_FONT + GAP + widest + GAP;
    // Room on the right for half of a tick label at the frame's right end.
    let right = |frame_w: f64| {
        fig.panels
            .iter()
            .filter_map(|p| {
                let t = ticks(&p.x, frame_w, true);
                let (v, l) = t.major.last()?;
                let from_end = (1.0 - p.x.fraction(*v)) * frame_w;
                Some(0.5 * text::width(l, TICK_FONT) + 1.5 - from_end)
            })
            .fold(RIGHT_MARGIN, f64::max)
    };
    // Legends beside the frames take their room from the frames' width.
    let beside = fig.panels.iter().map(beside_width).fold(0.0, f64::max);
    let frame_w = (cell_w - left - beside - right(cell_w - left - beside - RIGHT_MARGIN)).max(10.0);

    let mut out = String::new();
    let _ = writeln!(
        out,
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}pt\" height=\"{}pt\" viewBox=\"0 0 {} {}\" font-family=\"{}, Verdana, sans-serif\">",
        n(w),
        n(h),
        n(w),
        n(h),
        text::FAMILY
    );
    let _ = writeln!(
        out,
        "<desc>bouncemap {} figure {}</desc>",
        env!("CARGO_PKG_VERSION"),
        esc(&fig.name)
    );
    let _ = writeln!(
        out,
        "<rect x=\"0\" y=\"0\" width=\"{}\" height=\"{}\" fill=\"#ffffff\"/>",
        n(w),
        n(h)
    );
    for (i, (p, yt)) in fig.panels.iter().zip(&yticks).enumerate() {
        let (cx, cy) = ((i % cols) as f64 * cell_w, (i / cols) as f64 * cell_h);
        let f = Frame {
            x0: cx + left,
            y0: cy + top,
            x1: cx + left + frame_w,
            y1: cy + top + frame_h,
        };
        let xt = ticks(&p.x, frame_w, true);
        let _ = writeln!(
            out,
            "<clipPath id=\"frame{i}\"><rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/></clipPath>",
            n(f.x0),
            n(f.y0),
            n(frame_w),
            n(frame_h)
        );
        let _ = writeln!(out, "<g clip-path=\"url(#frame{i})\">");
        for l in &p.layers {
            layer(&mut out, &f, p, l);
        }
        out.push_str("</g>\n");
        axes(&mut out, &f, p, &xt, yt, cx + PAD + 0.8 * LABEL_FONT);
        for l in &p.legends {
            legend(&mut out, &f, l);
        }
        legends_beside(&mut out, &f, p);
        let head = f.y0 - 0.45 * LETTER_FONT;
        if let Some(letter) = &p.letter {
            out.push_str(&text_el(
                letter,
                cx + PAD,
                head,
                LETTER_FONT,
                Anchor::Start,
                false,
            ));
        }
        if let Some(title) = &p.title {
            out.push_str(&text_el(
                title,
                0.5 * (f.x0 + f.x1),
                head,
                TITLE_FONT,
                Anchor::Middle,
                false,
            ));
        }
    }
    let mut y = h - caption_h + PAD + 0.8 * CAPTION_FONT;
    for line in &caption {
        out.push_str(&text_el(line, PAD, y, CAPTION_FONT, Anchor::Start, false));
        y += CAPTION_FONT * 1.3;
    }
    out.push_str("</svg>\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hundredths_are_short_and_exact() {
        for (v, t) in [
            (5, ".05"),
            (50, ".5"),
            (150, "1.5"),
            (-30, "-.3"),
            (0, "0"),
            (1234, "12.34"),
            (-200, "-2"),
        ] {
            assert_eq!(hundredths(v), t);
            assert_eq!((t.parse::<f64>().unwrap() * 100.0).round() as i64, v);
        }
    }

    #[test]
    fn svg_numbers_are_short() {
        assert_eq!(n(1.0), "1");
        assert_eq!(n(1.234), "1.23");
        assert_eq!(n(-0.001), "0");
        assert_eq!(n(12.5), "12.5");
    }

    #[test]
    fn ticks_are_nice_numbers_inside_the_range() {
        let t = linear_ticks(0.45, 0.6, 200.0, true);
        let v: Vec<&str> = t.major.iter().map(|m| m.1.as_str()).collect();
        assert_eq!(v, ["0.45", "0.50", "0.55", "0.60"]);
        let t = linear_ticks(-0.05, 1.05, 150.0, false);
        let v: Vec<&str> = t.major.iter().map(|m| m.1.as_str()).collect();
        assert_eq!(v, ["0.0", "0.2", "0.4", "0.6", "0.8", "1.0"]);
        // A narrow window far from zero still gets readable, distinct labels.
        let t = linear_ticks(0.50621, 0.506235, 140.0, true);
        assert!(t.major.len() >= 2);
        let labels: std::collections::HashSet<&str> =
            t.major.iter().map(|m| m.1.as_str()).collect();
        assert_eq!(labels.len(), t.major.len());
        let t = log_ticks(1e-3, 1.0);
        let v: Vec<&str> = t.major.iter().map(|m| m.1.as_str()).collect();
        assert_eq!(
            v,
            [
                "10$^{\u{2212}3}$",
                "10$^{\u{2212}2}$",
                "10$^{\u{2212}1}$",
                "1"
            ]
        );
        assert_eq!(t.minor.len(), 8 * 3);
    }

    #[test]
    fn markup_becomes_tspans() {
        let s = text_el("$b_T$ x", 1.0, 2.0, 10.0, Anchor::Start, false);
        assert!(s.contains("<tspan font-style=\"italic\">b</tspan>"), "{s}");
        assert!(s.contains("font-size=\"7\" dy=\"2.2\">T</tspan>"), "{s}");
        assert!(s.contains("<tspan dy=\"-2.2\"> x</tspan>"), "{s}");
        let s = text_el("a<b & c", 0.0, 0.0, 10.0, Anchor::End, true);
        assert!(s.contains("a&lt;b &amp; c"), "{s}");
        assert!(s.contains("rotate(-90 0 0)"), "{s}");
    }
}
