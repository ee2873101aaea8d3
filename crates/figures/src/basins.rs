//! `figure basins`: the basins of attraction of one system, each start (t̂0, w0) a
//! cell coloured by the attractor it ends on (1 = the largest basin), with a legend
//! naming each attractor's kind, period, largest exponent and share of the starts, and
//! each periodic attractor's point (t̂, w) marked on the picture. Also the one place for
//! how pictures number and name attractors ([`numbers`], [`describe`], [`exponent`]),
//! which the text pictures and the terminal application share.

use crate::format::significant;
use crate::model::{Axis, Color, Corner, Figure, Layer, Legend, Marker, Panel, Swatch};
use bouncemap_engine::attractors::basins::{BasinSpec, Basins};
use bouncemap_engine::attractors::{Attractor, Kind, Registry};
use bouncemap_engine::fmt_value as shortest;

/// The numbering of a registry's attractors: `number[id]` (1-based, largest basin
/// first, see [`Registry::ranked`]).
pub fn numbers(reg: &Registry) -> Vec<usize> {
    let mut number = vec![0; reg.attractors().len()];
    for (rank, id) in reg.ranked().into_iter().enumerate() {
        number[id] = rank + 1;
    }
    number
}

/// "periodic (1, 1)", "sticking (3, 2)", "chaotic", and "sticking (length
/// unresolved)" for a cycle whose length double precision cannot decide.
pub fn describe(a: &Attractor) -> String {
    kind_text(a.kind, a.period(), a.unresolved())
}

/// An attractor's kind for people: with its (n, k) where double precision decides it,
/// "(length unresolved)" where it does not.
pub fn kind_text(kind: Kind, period: Option<(usize, i64)>, unresolved: bool) -> String {
    match period {
        Some((n, k)) => format!("{} ({n}, {k})", kind.as_str()),
        None if unresolved => format!("{} (length unresolved)", kind.as_str()),
        None => kind.as_str().to_string(),
    }
}

/// A largest exponent for people: `-inf` (superstable), `—` where none.
pub fn exponent(l: Option<f64>) -> String {
    match l {
        Some(x) if x == f64::NEG_INFINITY => "-inf".into(),
        Some(x) => significant(x, 4),
        None => "—".into(),
    }
}

/// Whether attractors of this kind are drawn in a colour of their own (resting and
/// escaping are drawn dim).
pub fn is_attractor(kind: Kind) -> bool {
    !matches!(kind, Kind::Resting | Kind::Escaping)
}

/// The figure of a complete basin picture.
pub fn basins_figure(spec: &BasinSpec, basins: &Basins) -> Figure {
    let reg = basins.registry();
    let number = numbers(reg);
    let size = [1.0 / spec.nx as f64, spec.w_max / spec.ny as f64];
    let mut cells: Vec<Vec<[f64; 2]>> = vec![Vec::new(); reg.attractors().len()];
    for (k, l) in basins.labels().iter().enumerate() {
        if let Some(id) = l {
            let (t0, w0) = spec.start(k);
            cells[*id as usize].push([t0, w0]);
        }
    }
    let mut panel = Panel::new(
        Axis::new("$t\u{302}_0$", 0.0, 1.0),
        Axis::new("$w_0$", 0.0, spec.w_max),
    );
    let mut entries = Vec::new();
    let mut marks = Vec::new();
    for id in reg.ranked() {
        let a = &reg.attractors()[id];
        let n = number[id];
        let color = if is_attractor(a.kind) {
            crate::classes::attractor_colour(n)
        } else {
            crate::classes::REST
        };
        panel.layers.push(Layer::Cells {
            name: format!("attractor {n}: {}", describe(a)),
            centres: std::mem::take(&mut cells[id]),
            size,
            color,
        });
        // A periodic attractor's point after an impact, (t̂, w = v − f'(t̂)), is a start
        // on the attractor itself: it lies in its own basin.
        if let Some((t, v)) = a.point {
            let w = v - spec.sys.df(t);
            if (0.0..=spec.w_max).contains(&w) {
                marks.push([t, w]);
            }
        }
        entries.push((
            Swatch::band(color),
            format!(
                "{n}: {}, $\u{3bb}$ {}, {:.1}%",
                describe(a),
                exponent(a.lyapunov),
                100.0 * reg.fraction(id)
            ),
        ));
    }
    if !marks.is_empty() {
        panel.layers.push(Layer::Markers {
            name: "attractor points".into(),
            points: marks,
            marker: Marker::Circle,
            color: Color::BLACK,
        });
        entries.push((
            Swatch::marker(Color::BLACK, Marker::Circle),
            "a point of a periodic attractor".into(),
        ));
    }
    panel.title = Some(format!(
        "{}, $\u{3b1}$ = {}, $r$ = {}",
        crate::labels::table_title(spec.sys.table()),
        shortest(spec.sys.alpha()),
        shortest(spec.sys.r())
    ));
    // Beside the frame: a basin picture is full to every corner.
    panel.beside.push(Legend {
        corner: Corner::TopRight,
        entries,
    });
    Figure {
        name: "basins".into(),
        panels: vec![panel],
        columns: 1,
        caption: vec![format!(
            "Basins of attraction: each of {}\u{d7}{} starts leaves the table at phase $t\u{302}_0$ with relative velocity $w_0$ and is followed for up to {} table periods (early stop on cycles); its cell is coloured by the attractor it ends on, numbered from the largest basin down. Grey: starts that come to rest on the table or do not land. Circles: a point (after an impact) of each periodic attractor, itself a start in its basin.",
            spec.nx, spec.ny, spec.settle.transient
        )],
        size: (BASINS_WIDTH, 3.2),
    }
}

/// The width of a basins figure: a column's plot and the legend beside it.
const BASINS_WIDTH: f64 = 5.6;
