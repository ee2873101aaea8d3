//! The `l` overlay: what every mark, line and colour on the screen means, panel by
//! panel. One meaning per symbol across the panels; the period colours are drawn in
//! their own styles so the legend shows them as the diagram does.

use super::Shared;
use crate::output::basin_map::textures;
use crate::output::classes::Class;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};

/// (symbol, meaning) rows under a panel's heading.
pub const SECTIONS: &[(&str, &[(&str, &str)])] = &[
    (
        "Bifurcation diagram",
        &[
            (
                "⣿ dots",
                "recorded events (phase t̂ or velocity v) of each value's orbit",
            ),
            ("│", "the current value of the swept parameter (α, r or D)"),
            (
                "┆ ┄",
                "the cursor (diagram focused); its readout is top right",
            ),
            (
                "┃ ━",
                "first corner of a window being marked (m twice zooms)",
            ),
            (
                "B  P",
                "on the axis: birth, α_PD of (1,k) (PD when branches show)",
            ),
            (
                "⠉ lines",
                "periodic branches (α sweeps): stable solid, unstable dotted",
            ),
            ("red ⠉", "with proofs on (V): stretches not proved"),
            (
                "PD F BC",
                "on the axis: period doubling, fold, border collision",
            ),
            (
                "λ strip",
                "largest Lyapunov exponent per impact; ┄ 0; ▁ −∞ (sticks)",
            ),
        ],
    ),
    (
        "Phase plot",
        &[
            ("⣿ dots", "every event (t̂, v) of the orbit from t̂0, v0"),
            ("bright", "the latest 40 events"),
            ("◆ ◇", "the (1,k) solution: stable, unstable"),
            ("✕", "the two points of the (2,2k) solution"),
            ("▣", "the state stepped to in the bounce panel"),
        ],
    ),
    (
        "Stability panel",
        &[
            (
                "[═══]",
                "the stable band κ_c < f'' < 0 on the labelled f'' line",
            ),
            (
                "◆ ◇",
                "the (1,k) solution (stable, unstable): f'', eigenvalues",
            ),
            ("◂ ▸", "an f'' beyond the ends of the line"),
            (
                "circle",
                "|λ| = 1; beyond it a log radius, dotted ring |λ| = 10",
            ),
            (
                "B  P",
                "(α, r) plane: birth and α_PD curves of (1,k) (E: other end)",
            ),
            ("◎", "the current (α, r)"),
            (
                "✓ ✗",
                "proofs (V): proved (with the stability) or not, and why",
            ),
        ],
    ),
    (
        "Bounce panel",
        &[
            ("⠤ line", "the table f(t), t in periods"),
            (
                "•",
                "the ball's path z(t); dim at the start: the next flight",
            ),
            ("▾", "an impact"),
            ("▪", "a stick or a release"),
            ("●", "the ball now"),
        ],
    ),
    (
        "Plane (M)",
        &[
            (
                "colours",
                "each pixel's class in the period colours (two per cell)",
            ),
            (
                "· : + * #",
                "no colour: period 1 2 4 8 other; ▒ sticks █ chaos ? unsettled",
            ),
            (
                "x",
                "no colour: no landing or at rest (left blank in colour)",
            ),
            (
                "B P C",
                "curves: birth and α_PD of (1,1), border collision of (2,2)",
            ),
            ("╋", "the cursor: the application's α and D (or r)"),
        ],
    ),
    (
        "Basins (B)",
        &[
            (
                "▀ halves",
                "one start (t̂0, w0) per half cell, coloured by its attractor",
            ),
            ("grey", "starts that come to rest or do not land"),
            (
                "no colour",
                "each cell shows its attractor's texture (legend lines)",
            ),
        ],
    ),
    (
        "Attractors along α (A)",
        &[
            (
                "∙ dots",
                "each attractor's points (t̂ up) at every α, coloured by its number",
            ),
            (
                "█ strip",
                "basin fractions stacked from the bottom, in the same colours",
            ),
            ("░", "starts not run to an attractor"),
            ("◦  grey", "resting balls and escapes"),
            ("▲", "the cursor's α (the basins panel shows its picture)"),
            ("no colour", "each attractor in its number's texture"),
        ],
    ),
];

/// The legend's lines.
pub fn lines(app: &Shared) -> Vec<Line<'static>> {
    let mut out = Vec::new();
    out.push(Line::styled(
        " Period colours (diagram, c switches)",
        app.theme.focus(),
    ));
    // Two lines: the cycles, then the rest.
    for part in [&Class::ALL[..5], &Class::ALL[5..]] {
        let mut spans = vec![Span::raw("   ")];
        for &c in part {
            spans.push(Span::styled(c.label().to_string(), app.theme.class(c)));
            spans.push(Span::raw(format!(" {}  ", short(c))));
        }
        out.push(Line::from(spans));
    }
    let mut density = vec![Span::raw("   density (c): ")];
    for (l, t) in ["sparse", "·", "·", "dense"].into_iter().enumerate() {
        density.push(Span::styled(t, app.theme.density(l)));
        density.push(Span::raw(" "));
    }
    out.push(Line::from(density));
    for (heading, rows) in SECTIONS {
        out.push(Line::styled(format!(" {heading}"), app.theme.focus()));
        for (sym, meaning) in rows.iter() {
            let sym = app.marker.samples(sym);
            out.push(Line::from(vec![
                Span::styled(format!("   {sym:<9} "), app.theme.mark2()),
                Span::raw(meaning.to_string()),
            ]));
        }
    }
    let t: String = textures(app.marker).iter().take(4).collect();
    out.push(Line::styled(
        format!(" basins textures without colour: {t} … = attractors 1, 2, 3, 4 …"),
        app.theme.dim(),
    ));
    out
}

fn short(c: Class) -> &'static str {
    match c {
        Class::Period1 => "period 1",
        Class::Period2 => "2",
        Class::Period4 => "4",
        Class::Period8 => "8",
        Class::Periodic => "other",
        Class::Sticking => "sticks",
        Class::StickingUnresolved => "length beyond f64",
        Class::Chaotic => "λ>0",
        Class::Unresolved => "unsettled (λ≈0)",
    }
}

/// Draw the legend overlay, scrolled by `scroll` lines if it does not fit.
pub fn draw(app: &Shared, scroll: usize, area: Rect, buf: &mut Buffer) {
    let all = lines(app);
    super::help::scrolled(app, "Legend (l or Esc closes)", all, scroll, area, buf);
}
