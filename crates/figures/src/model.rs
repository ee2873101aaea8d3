//! The figures' data model: a [`Figure`] is panels with axes, layers of points, lines,
//! bands and cells, legends and a caption, described as data before anything is laid
//! out; [`Figure::data`] gives the numbers behind every layer. Everything else in the
//! crate builds these values ([`crate::diagram`], [`crate::plane`], ...) or draws them
//! ([`crate::svg`], [`crate::raster`]).

use serde::Serialize;
use std::path::Path;

/// A colour, sRGB.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Color(pub u8, pub u8, pub u8);

impl Color {
    pub const BLACK: Color = Color(0, 0, 0);
    pub const GREY: Color = Color(110, 110, 110);
    /// The paper's ΔT and b_T.
    pub const BLUE: Color = Color(31, 89, 180);
    /// The paper's Δt and b_t.
    pub const RED: Color = Color(204, 37, 41);
    pub const ORANGE: Color = Color(230, 120, 20);
    pub const GREEN: Color = Color(44, 150, 44);
    /// The band of values whose orbit sticks.
    pub const STICKING: Color = Color(190, 215, 245);

    /// The colour mixed with white, `f` of the way (0: itself, 1: white).
    pub fn tint(self, f: f64) -> Color {
        let m = |c: u8| (c as f64 + (255.0 - c as f64) * f).round() as u8;
        Color(m(self.0), m(self.1), m(self.2))
    }

    /// `#rrggbb`.
    pub fn hex(self) -> String {
        format!("#{:02x}{:02x}{:02x}", self.0, self.1, self.2)
    }
}

/// A point marker.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Marker {
    /// A filled disc.
    Disc,
    /// An open circle.
    Circle,
}

/// A line's pattern.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dash {
    Solid,
    Dashed,
    Dotted,
    /// Dash and dot alternating.
    DashDot,
}

/// One series of a panel.
#[derive(Clone, Debug, PartialEq)]
pub enum Layer {
    /// Points as small alpha-blended dots: where many fall, the picture is dark.
    Density {
        name: String,
        points: Vec<[f64; 2]>,
        color: Color,
    },
    /// Points already counted on a fine grid ([`DensityGrid`]), drawn as
    /// [`Layer::Density`] draws points: for more points than are worth holding.
    Grid {
        name: String,
        grid: DensityGrid,
        color: Color,
    },
    /// Points with a marker each.
    Markers {
        name: String,
        points: Vec<[f64; 2]>,
        marker: Marker,
        color: Color,
    },
    /// Polylines (each one unbroken).
    Lines {
        name: String,
        lines: Vec<Vec<[f64; 2]>>,
        color: Color,
        dash: Dash,
        /// Stroke width in points.
        width: f64,
    },
    /// Shaded stretches [x0, x1] of the x axis, over the whole height.
    Bands {
        name: String,
        spans: Vec<[f64; 2]>,
        color: Color,
    },
    /// Filled rectangles of one size centred on `centres` (a picture over a grid,
    /// e.g. one attractor's basin); neighbouring cells of a row are drawn as one.
    Cells {
        name: String,
        centres: Vec<[f64; 2]>,
        /// Width and height of a cell in axis units.
        size: [f64; 2],
        color: Color,
    },
    /// The region between two lines over the same x values (`lower` and `upper`, in
    /// order of x), filled: a band of a stacked plot.
    Area {
        name: String,
        lower: Vec<[f64; 2]>,
        upper: Vec<[f64; 2]>,
        color: Color,
    },
    /// A horizontal line across the panel.
    HLine { y: f64, color: Color, dash: Dash },
    /// A vertical line across the panel.
    VLine { x: f64, color: Color, dash: Dash },
}

/// Points counted on a grid over [x0, x1] × [y0, y1] as they come, so a picture of any
/// number of points holds only its counts (4 bytes per bin). Along x the bins are
/// centred on `nx` evenly spaced values from x0 to x1 (a sweep of at most `nx` values
/// keeps every value's own column), along y they split [y0, y1] in `ny`. Points outside
/// are not counted.
#[derive(Clone, Debug, PartialEq)]
pub struct DensityGrid {
    pub x: (f64, f64),
    pub y: (f64, f64),
    pub nx: usize,
    pub ny: usize,
    counts: Vec<u32>,
}

impl DensityGrid {
    /// An empty grid of `nx` × `ny` bins (each at least 1).
    pub fn new(x: (f64, f64), y: (f64, f64), nx: usize, ny: usize) -> DensityGrid {
        let (nx, ny) = (nx.max(1), ny.max(1));
        DensityGrid {
            x,
            y,
            nx,
            ny,
            counts: vec![0; nx * ny],
        }
    }

    /// Count one point.
    pub fn add(&mut self, p: [f64; 2]) {
        let (fx, fy) = (
            if self.x.1 > self.x.0 {
                (p[0] - self.x.0) / (self.x.1 - self.x.0)
            } else {
                0.0
            },
            (p[1] - self.y.0) / (self.y.1 - self.y.0),
        );
        if !(0.0..=1.0).contains(&fx) || !(0.0..=1.0).contains(&fy) {
            return;
        }
        let i = (fx * (self.nx - 1) as f64).round() as usize;
        let j = ((fy * self.ny as f64) as usize).min(self.ny - 1);
        let c = &mut self.counts[i * self.ny + j];
        *c = c.saturating_add(1);
    }

    /// The centre of each bin holding points, and its count.
    pub fn bins(&self) -> impl Iterator<Item = ([f64; 2], u32)> + '_ {
        let dx = if self.nx > 1 {
            (self.x.1 - self.x.0) / (self.nx - 1) as f64
        } else {
            0.0
        };
        let dy = (self.y.1 - self.y.0) / self.ny as f64;
        self.counts
            .iter()
            .enumerate()
            .filter(|(_, c)| **c > 0)
            .map(move |(k, c)| {
                let (i, j) = (k / self.ny, k % self.ny);
                (
                    [self.x.0 + i as f64 * dx, self.y.0 + (j as f64 + 0.5) * dy],
                    *c,
                )
            })
    }
}

/// Linear or decimal-logarithmic axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scale {
    Linear,
    Log,
}

/// One axis of a panel.
#[derive(Clone, Debug, PartialEq)]
pub struct Axis {
    /// The label, in [`crate::text`]'s markup.
    pub label: String,
    pub lo: f64,
    pub hi: f64,
    pub scale: Scale,
}

impl Axis {
    /// A linear axis over [lo, hi].
    pub fn new(label: &str, lo: f64, hi: f64) -> Axis {
        let (lo, hi) = if hi > lo {
            (lo, hi)
        } else {
            // An empty range (one value) is widened so the points show.
            let pad = if lo == 0.0 { 1.0 } else { 0.05 * lo.abs() };
            (lo - pad, hi + pad)
        };
        Axis {
            label: label.into(),
            lo,
            hi,
            scale: Scale::Linear,
        }
    }

    /// A linear axis around `values`, with `pad` of the range added on each side.
    pub fn around(label: &str, values: impl IntoIterator<Item = f64>, pad: f64) -> Axis {
        let (lo, hi) = values
            .into_iter()
            .filter(|v| v.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(v), b.max(v))
            });
        if !lo.is_finite() {
            return Axis::new(label, 0.0, 1.0);
        }
        let p = pad * (hi - lo);
        Axis::new(label, lo - p, hi + p)
    }

    /// A decimal-logarithmic axis over [lo, hi] (both > 0).
    pub fn log(label: &str, lo: f64, hi: f64) -> Axis {
        Axis {
            label: label.into(),
            lo,
            hi,
            scale: Scale::Log,
        }
    }

    /// Where `v` lies along the axis, 0 at lo and 1 at hi.
    pub fn fraction(&self, v: f64) -> f64 {
        match self.scale {
            Scale::Linear => (v - self.lo) / (self.hi - self.lo),
            Scale::Log => (v.log10() - self.lo.log10()) / (self.hi.log10() - self.lo.log10()),
        }
    }
}

/// A corner of a panel's frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Corner {
    TopLeft,
    TopRight,
    BottomLeft,
    BottomRight,
}

/// What a legend entry shows before its text.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Swatch {
    pub color: Color,
    pub line: Option<Dash>,
    pub marker: Option<Marker>,
    /// A filled box (a band's colour).
    pub band: bool,
}

impl Swatch {
    pub fn line(color: Color, dash: Dash) -> Swatch {
        Swatch {
            color,
            line: Some(dash),
            marker: None,
            band: false,
        }
    }

    pub fn marker(color: Color, marker: Marker) -> Swatch {
        Swatch {
            color,
            line: None,
            marker: Some(marker),
            band: false,
        }
    }

    pub fn band(color: Color) -> Swatch {
        Swatch {
            color,
            line: None,
            marker: None,
            band: true,
        }
    }
}

/// A legend: entries in a box inside a corner of the frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Legend {
    pub corner: Corner,
    /// Swatch and text (markup).
    pub entries: Vec<(Swatch, String)>,
}

/// One panel: a frame with its axes, layers and legends.
#[derive(Clone, Debug, PartialEq)]
pub struct Panel {
    /// "(a)", above the frame's left.
    pub letter: Option<String>,
    /// Above the frame, centred (markup).
    pub title: Option<String>,
    pub x: Axis,
    pub y: Axis,
    pub layers: Vec<Layer>,
    /// Legends inside the frame, each in its corner.
    pub legends: Vec<Legend>,
    /// Legends beside the frame, on its right, top down (their corner is not used):
    /// for a legend that would hide data anywhere inside (a map's classes, the
    /// colours of a dense diagram). The frame narrows to make room.
    pub beside: Vec<Legend>,
}

impl Panel {
    pub fn new(x: Axis, y: Axis) -> Panel {
        Panel {
            letter: None,
            title: None,
            x,
            y,
            layers: Vec::new(),
            legends: Vec::new(),
            beside: Vec::new(),
        }
    }
}

/// A figure: panels on a grid, a caption below them.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    /// What it is (`fig2`, `diagram`, …): the SVG's description and the data's name.
    pub name: String,
    /// Panels, row by row.
    pub panels: Vec<Panel>,
    /// Panels per row.
    pub columns: usize,
    /// Lines of small text below the panels (markup), wrapped to the width.
    pub caption: Vec<String>,
    /// Width and height in inches when none is asked for.
    pub size: (f64, f64),
}

/// One column of a two-column paper, in inches.
pub const COLUMN: f64 = 3.4;
/// The full width of a two-column paper, in inches.
pub const FULL_WIDTH: f64 = 7.0;

/// Output format of a figure file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ImageFormat {
    /// Vector graphics, text as text.
    Svg,
    /// A bitmap at the given dpi.
    Png,
}

impl ImageFormat {
    /// The format a file name's extension names (.svg, .png; any case).
    pub fn from_path(path: &Path) -> Option<ImageFormat> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "svg" => Some(ImageFormat::Svg),
            "png" => Some(ImageFormat::Png),
            _ => None,
        }
    }

    pub fn extension(self) -> &'static str {
        match self {
            ImageFormat::Svg => "svg",
            ImageFormat::Png => "png",
        }
    }
}

/// Pixels per inch when none is asked for.
pub const DEFAULT_DPI: u32 = 300;

/// Why a figure could not be drawn: one line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FigureError(pub String);

impl std::fmt::Display for FigureError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for FigureError {}

/// The numbers behind a figure, for `figure --data`.
#[derive(Serialize, Debug)]
pub struct FigureData {
    pub figure: String,
    pub panels: Vec<PanelData>,
    pub caption: Vec<String>,
}

#[derive(Serialize, Debug)]
pub struct PanelData {
    pub letter: Option<String>,
    pub title: Option<String>,
    pub x: AxisData,
    pub y: AxisData,
    pub series: Vec<SeriesData>,
}

#[derive(Serialize, Debug)]
pub struct AxisData {
    pub label: String,
    pub lo: f64,
    pub hi: f64,
    pub log: bool,
}

/// One layer's numbers: points (x, y), or for lines one list per polyline, or for
/// bands the spans [x0, x1]; for points counted on a grid, the grid.
#[derive(Serialize, Debug)]
pub struct SeriesData {
    pub name: String,
    pub kind: &'static str,
    pub points: Vec<[f64; 2]>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub lines: Vec<Vec<[f64; 2]>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub grid: Option<GridData>,
}

/// A [`DensityGrid`]'s numbers: the bins along x are centred on `nx` evenly spaced
/// values from `x[0]` to `x[1]`, along y they split `[y[0], y[1]]` in `ny`; `counts` holds
/// the points per bin, x-major (bin (i, j) at i·ny + j).
#[derive(Serialize, Debug)]
pub struct GridData {
    pub x: [f64; 2],
    pub y: [f64; 2],
    pub nx: usize,
    pub ny: usize,
    pub counts: Vec<u32>,
}

impl Figure {
    /// Every named layer's numbers.
    pub fn data(&self) -> FigureData {
        let axis = |a: &Axis| AxisData {
            label: a.label.clone(),
            lo: a.lo,
            hi: a.hi,
            log: a.scale == Scale::Log,
        };
        FigureData {
            figure: self.name.clone(),
            caption: self.caption.clone(),
            panels: self
                .panels
                .iter()
                .map(|p| PanelData {
                    letter: p.letter.clone(),
                    title: p.title.clone(),
                    x: axis(&p.x),
                    y: axis(&p.y),
                    series: p
                        .layers
                        .iter()
                        .filter_map(|l| {
                            let s = |name: &str, kind, points: &[[f64; 2]]| SeriesData {
                                name: name.into(),
                                kind,
                                points: points.to_vec(),
                                lines: Vec::new(),
                                grid: None,
                            };
                            match l {
                                Layer::Density { name, points, .. } => {
                                    Some(s(name, "density", points))
                                }
                                Layer::Markers { name, points, .. } => {
                                    Some(s(name, "markers", points))
                                }
                                Layer::Bands { name, spans, .. } => Some(s(name, "bands", spans)),
                                Layer::Cells { name, centres, .. } => {
                                    Some(s(name, "cells", centres))
                                }
                                Layer::Lines { name, lines, .. } => Some(SeriesData {
                                    name: name.clone(),
                                    kind: "lines",
                                    points: Vec::new(),
                                    lines: lines.clone(),
                                    grid: None,
                                }),
                                Layer::Grid { name, grid, .. } => Some(SeriesData {
                                    name: name.clone(),
                                    kind: "density_grid",
                                    points: Vec::new(),
                                    lines: Vec::new(),
                                    grid: Some(GridData {
                                        x: [grid.x.0, grid.x.1],
                                        y: [grid.y.0, grid.y.1],
                                        nx: grid.nx,
                                        ny: grid.ny,
                                        counts: grid.counts.clone(),
                                    }),
                                }),
                                Layer::Area {
                                    name, lower, upper, ..
                                } => Some(SeriesData {
                                    name: name.clone(),
                                    kind: "area",
                                    points: Vec::new(),
                                    lines: vec![lower.clone(), upper.clone()],
                                    grid: None,
                                }),
                                Layer::HLine { .. } | Layer::VLine { .. } => None,
                            }
                        })
                        .collect(),
                })
                .collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    #[test]
    fn formats_follow_the_extension() {
        assert_eq!(
            ImageFormat::from_path(Path::new("a/b.SVG")),
            Some(ImageFormat::Svg)
        );
        assert_eq!(
            ImageFormat::from_path(Path::new("f.png")),
            Some(ImageFormat::Png)
        );
        assert_eq!(ImageFormat::from_path(Path::new("f.pdf")), None);
        assert_eq!(ImageFormat::from_path(Path::new("/dev/full")), None);
    }
}
