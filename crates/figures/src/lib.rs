//! Publication figures of the bouncing ball impact map: the paper's Fig. 2–5, any sweep
//! as a bifurcation diagram, basins of attraction, two-parameter maps and the terminal
//! application's views, as SVG (vector, text as text) and PNG. The crate draws; it
//! writes no file (the caller puts the bytes where they belong) and reads none: its text
//! is set in the fonts compiled into it ([`text`]), never in a system font.
//!
//! A figure is first described as data ([`Figure`]: panels with axes, layers of points
//! and lines, legends, a caption), then laid out and written as SVG by [`svg`]; the PNG
//! is that SVG rendered by resvg ([`raster`]), so both formats show the same picture.
//! [`Figure::data`] gives the numbers behind every layer (`figure --data`).
//!
//! One module per family of figures builds its [`Figure`]s from engine results:
//! [`shapes`] (Fig. 2), [`diagram`] (Fig. 3, Fig. 4's upper row, any sweep and the
//! terminal's diagram view), [`scaling`] (Fig. 4's lower row, Fig. 5), [`phase`] (the
//! terminal's phase plot), [`lyapunov`] (a diagram over its largest exponent),
//! [`basins`] (basins of attraction; how attractors are numbered and named in pictures),
//! [`plane`] (two-parameter maps). [`classes`] says what an orbit is as the pictures
//! colour it (period 1, 2, 4, 8, sticking, chaotic …). A new kind of picture is one more
//! function returning a [`Figure`].
//!
//! # Drawing a figure as a library user
//!
//! ```
//! use bouncemap_engine::jobs::Executor;
//! use bouncemap_engine::jobs::grid::SweepParam;
//! use bouncemap_engine::sweep::{collect, SweepSpec};
//! use bouncemap_engine::Table;
//! use bouncemap_figures::{diagram, render, ImageFormat, DEFAULT_DPI};
//!
//! // A small bifurcation diagram of F_0.1 at r = 0.8, α from 0.45 to 0.6.
//! let mut spec = SweepSpec::new(Table::fd(0.1)?, 0.45, 0.8, SweepParam::Alpha, 0.45, 0.6, 40);
//! spec.transient = 2000;
//! spec.keep = 20;
//! let values = collect(&spec, &Executor::new(1)?)?;
//! let figure = diagram::diagram_figure("diagram", diagram::Diagram::of(&spec, &values));
//!
//! // The SVG as text, at the figure's own size; the PNG as bytes, 5 × 3.5 inches.
//! let svg = bouncemap_figures::svg::to_svg(&figure, figure.size);
//! assert!(svg.contains("<svg"));
//! let png = render(&figure, ImageFormat::Png, Some((5.0, 3.5)), DEFAULT_DPI)?;
//! assert_eq!(&png[..4], b"\x89PNG");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#![forbid(unsafe_code)]

pub mod basins;
pub mod classes;
pub mod curves;
pub mod diagram;
pub mod global;
pub mod lyapunov;
pub mod manifold;
pub mod phase;
pub mod plane;
pub mod raster;
pub mod scaling;
pub mod shapes;
pub mod svg;
pub mod terminal;
pub mod text;

pub mod format;
pub mod labels;
pub mod model;

pub use diagram::{diagram_view, DiagramAxis};
pub use format::{fmt_count, fmt_fixed, significant};
pub use model::*;
pub use phase::phase_view;

/// The file's bytes: `figure` at `size` inches (its own size if None), as SVG or as
/// PNG at `dpi`.
pub fn render(
    figure: &Figure,
    format: ImageFormat,
    size: Option<(f64, f64)>,
    dpi: u32,
) -> Result<Vec<u8>, FigureError> {
    let size = size.unwrap_or(figure.size);
    let svg = svg::to_svg(figure, size);
    match format {
        ImageFormat::Svg => Ok(svg.into_bytes()),
        ImageFormat::Png => raster::png(&svg, size, dpi),
    }
}
