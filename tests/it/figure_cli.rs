//! `bouncemap figure` as a user runs it: valid PNG and SVG files of the asked size, text
//! drawn without any system font, Fig. 5's points equal to `bouncemap scaling`'s,
//! the analytic lines and the diagrams against closed forms, and bad input refused
//! with one line and nothing written. Diagrams run at `--quick` fidelity.

pub(crate) use crate::scratch::s;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub(crate) fn bouncemap(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_bouncemap"))
        .args(args)
        .output()
        .expect("the binary runs")
}

pub(crate) fn ok(o: &Output) {
    assert!(
        o.status.success(),
        "failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

pub(crate) fn dir(name: &str) -> PathBuf {
    crate::scratch::dir("figure", name)
}

/// A decoded PNG: width, height, pixels per metre, RGB rows.
pub(crate) struct Image {
    pub(crate) width: u32,
    height: u32,
    per_metre: Option<u32>,
    rgb: Vec<u8>,
}

impl Image {
    pub(crate) fn read(path: &Path) -> Image {
        let bytes = std::fs::read(path).unwrap();
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "the PNG signature");
        let mut reader = png::Decoder::new(std::io::Cursor::new(bytes))
            .read_info()
            .unwrap();
        let per_metre = reader.info().pixel_dims.map(|d| {
            assert_eq!(d.unit, png::Unit::Meter);
            assert_eq!(d.xppu, d.yppu);
            d.xppu
        });
        let mut buf = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut buf).unwrap();
        assert_eq!(info.color_type, png::ColorType::Rgb);
        buf.truncate(info.buffer_size());
        Image {
            width: info.width,
            height: info.height,
            per_metre,
            rgb: buf,
        }
    }

    /// Pixels darker than mid-grey in the box [x0, x1) × [y0, y1).
    fn ink(&self, x0: u32, x1: u32, y0: u32, y1: u32) -> usize {
        let mut n = 0;
        for y in y0..y1.min(self.height) {
            for x in x0..x1.min(self.width) {
                let i = 3 * (y * self.width + x) as usize;
                let lum =
                    (self.rgb[i] as u32 + self.rgb[i + 1] as u32 + self.rgb[i + 2] as u32) / 3;
                if lum < 128 {
                    n += 1;
                }
            }
        }
        n
    }
}

#[test]
fn fig2_is_a_png_of_the_asked_size_and_resolution() {
    let d = dir("fig2");
    let out = d.join("f.png");
    ok(&bouncemap(&["figure", "fig2", "--out", s(&out)]));
    let img = Image::read(&out);
    // The default: the page width of a two-column paper, 7 × 2.4 inches at 300 dpi.
    assert_eq!((img.width, img.height), (2100, 720));
    assert_eq!(
        img.per_metre,
        Some(11811),
        "300 dpi = 11811 pixels per metre"
    );
    let len = std::fs::metadata(&out).unwrap().len();
    assert!((20_000..5_000_000).contains(&len), "{len} bytes");
    // --size and --dpi.
    let small = d.join("s.png");
    ok(&bouncemap(&[
        "figure",
        "fig2",
        "--out",
        s(&small),
        "--size",
        "4x2",
        "--dpi",
        "100",
    ]));
    let img = Image::read(&small);
    assert_eq!(
        (img.width, img.height, img.per_metre),
        (400, 200, Some(3937))
    );
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn text_is_drawn_without_any_system_font() {
    let d = dir("nofonts");
    let empty = d.join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    let out = d.join("f.png");
    let o = Command::new(env!("CARGO_BIN_EXE_bouncemap"))
        .args(["figure", "fig2", "--dpi", "100", "--out", s(&out)])
        .env_clear()
        .env("FONTCONFIG_FILE", "/dev/null")
        .env("FONTCONFIG_PATH", &empty)
        .env("HOME", &empty)
        .env("XDG_DATA_HOME", &empty)
        .env("XDG_DATA_DIRS", &empty)
        .env("XDG_CONFIG_HOME", &empty)
        .output()
        .unwrap();
    ok(&o);
    let img = Image::read(&out);
    let (w, h) = (img.width, img.height);
    // The bottom tenth holds only the caption's text; the left strip below the panel
    // letter only the rotated y label.
    let caption = img.ink(0, w, h - h / 10, h);
    let ylabel = img.ink(0, 12, h / 5, h - h / 4);
    assert!(caption > 200, "caption ink: {caption} pixels");
    assert!(ylabel > 15, "y label ink: {ylabel} pixels");
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn a_figure_of_one_label_has_ink_where_the_label_is_and_nowhere_else() {
    use bouncemap_figures::{render, Figure, ImageFormat};
    let fig = Figure {
        name: "label".into(),
        panels: Vec::new(),
        columns: 1,
        caption: vec!["$t\u{302}$ \u{3b1} \u{394}\u{3ba} D".into()],
        size: (3.0, 1.0),
    };
    let bytes = render(&fig, ImageFormat::Png, None, 200).unwrap();
    let d = dir("label");
    let p = d.join("l.png");
    std::fs::write(&p, bytes).unwrap();
    let img = Image::read(&p);
    assert_eq!((img.width, img.height), (600, 200));
    let all = img.ink(0, 600, 0, 200);
    // The caption sits in the bottom line, at the left.
    let label = img.ink(0, 300, 150, 200);
    assert!(label > 100, "label ink: {label}");
    assert_eq!(all, label, "no ink outside the label's box");
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn fig3_quick_is_valid_svg_with_six_panels_and_text_as_text() {
    let d = dir("fig3");
    let out = d.join("f3.svg");
    ok(&bouncemap(&["figure", "fig3", "--quick", "--out", s(&out)]));
    let text = std::fs::read_to_string(&out).unwrap();
    let doc = roxmltree::Document::parse(&text).expect("the SVG parses as XML");
    let root = doc.root_element();
    assert_eq!(root.tag_name().name(), "svg");
    assert_eq!(root.attribute("width"), Some("504pt"), "7 inches");
    let clips = doc
        .descendants()
        .filter(|n| n.tag_name().name() == "clipPath")
        .count();
    assert_eq!(clips, 6, "six panels");
    let texts: Vec<String> = doc
        .descendants()
        .filter(|n| n.tag_name().name() == "text")
        .map(|n| {
            n.descendants()
                .filter(|c| c.is_text())
                .filter_map(|c| c.text())
                .collect()
        })
        .collect();
    for letter in ["(a)", "(b)", "(c)", "(d)", "(e)", "(f)"] {
        assert!(texts.iter().any(|t| t == letter), "{letter} in {texts:?}");
    }
    assert!(texts.iter().any(|t| t == "\u{3b1}"), "the α axis label");
    assert!(texts.iter().any(|t| t == "t\u{302}"), "the t̂ axis label");
    assert!(texts.iter().any(|t| t.contains("sticks")), "the caption");
    std::fs::remove_dir_all(&d).unwrap();
}

pub(crate) fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The points of the series called `name` in a figure's data.
pub(crate) fn series<'a>(data: &'a serde_json::Value, name: &str) -> &'a Vec<serde_json::Value> {
    data["panels"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|p| p["series"].as_array().unwrap())
        .find(|s| s["name"] == name)
        .unwrap_or_else(|| panic!("no series {name}"))["points"]
        .as_array()
        .unwrap()
}

#[test]
fn fig5_points_are_what_scaling_computes_and_its_printed_lines_are_the_paper_formula() {
    let d = dir("fig5");
    let (out, data) = (d.join("f5.svg"), d.join("f5.json"));
    ok(&bouncemap(&[
        "figure",
        "fig5",
        "--out",
        s(&out),
        "--data",
        s(&data),
    ]));
    roxmltree::Document::parse(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let fig = json(&data);
    let o = bouncemap(&["scaling", "--d", "0.001..1:13", "--format", "json"]);
    ok(&o);
    let scaling: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let rows = scaling["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 13);
    for (series_name, source, field) in [
        ("exact b_T", "exact", "b_T"),
        ("exact b_t", "exact", "b_t"),
        ("simulated b_T", "simulated", "b_T"),
        ("simulated b_t", "simulated", "b_t"),
    ] {
        let pts = series(&fig, series_name);
        assert_eq!(pts.len(), rows.len(), "{series_name}");
        for (p, row) in pts.iter().zip(rows) {
            assert_eq!(p[0], row["d"], "{series_name}: D");
            assert_eq!(
                p[1], row[source][field],
                "{series_name} at D = {}",
                row["d"]
            );
        }
    }
    // The printed Eqs. (bT), (bt), from the paper's text: c = f'(t̂*) = (1 − r)/(2(1 + r)),
    // κ_c = −2(1 + r²)/(1 + r)², k = 1, decimal logarithms.
    let r: f64 = 0.8;
    let c = (1.0 - r) / (2.0 * (1.0 + r));
    let kc = -2.0 * (1.0 + r * r) / ((1.0 + r) * (1.0 + r));
    let bt =
        |d: f64| -d.log10() - (-3.0 * kc * (1.0 - 4.0 * c * c / 3.0 * kc / (1.0 + kc))).log10();
    let bs = |d: f64| {
        -0.5 * d.log10() - 0.5 * (-3.0 * kc * ((1.0 + kc) / (4.0 * c * kc) - c / 3.0)).log10()
    };
    for (name, f) in [
        ("printed b_T", &bt as &dyn Fn(f64) -> f64),
        ("printed b_t", &bs),
    ] {
        let line = &fig["panels"][0]["series"]
            .as_array()
            .unwrap()
            .iter()
            .find(|s| s["name"] == name)
            .unwrap()["lines"][0];
        let pts = line.as_array().unwrap();
        assert!(pts.len() > 20, "{name}");
        for p in pts {
            let (x, y) = (p[0].as_f64().unwrap(), p[1].as_f64().unwrap());
            assert!(
                (y - f(x)).abs() < 1e-12,
                "{name} at D = {x}: {y} vs {}",
                f(x)
            );
        }
    }
    // The README's table: the printed b_T at D = 0.1 is 0.6963, the corrected 0.9122.
    assert!((bt(0.1) - 0.6963).abs() < 5e-5);
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn fig4_quick_is_a_png_with_the_paper_fits_beside_the_exact_ones() {
    let d = dir("fig4");
    let (out, data) = (d.join("f4.png"), d.join("f4.json"));
    ok(&bouncemap(&[
        "figure",
        "fig4",
        "--quick",
        "--dpi",
        "100",
        "--out",
        s(&out),
        "--data",
        s(&data),
    ]));
    let img = Image::read(&out);
    assert_eq!((img.width, img.height), (700, 540));
    let fig = json(&data);
    let panels = fig["panels"].as_array().unwrap();
    assert_eq!(panels.len(), 6);
    // The paper's fit for D = 0.001 (its Fig. 4 caption): log ΔT = 1.007 log Δκ + 3.031.
    let line = &panels[3]["series"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["name"] == "paper's fit log10 \u{394}T")
        .unwrap()["lines"][0];
    for p in line.as_array().unwrap() {
        let (x, y) = (p[0].as_f64().unwrap(), p[1].as_f64().unwrap());
        assert!((y - (1.007 * x + 3.031)).abs() < 1e-12);
    }
    // The exact points lie on ΔT ∝ Δκ: slope 1 between any two within 1e-3.
    let pts = series(&fig, "exact log10 \u{394}T");
    assert!(pts.len() >= 5);
    let xy = |p: &serde_json::Value| (p[0].as_f64().unwrap(), p[1].as_f64().unwrap());
    let ((x0, y0), (x1, y1)) = (xy(&pts[0]), xy(pts.last().unwrap()));
    assert!(((y1 - y0) / (x1 - x0) - 1.0).abs() < 1e-3);
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn a_diagram_takes_the_sweep_flags_and_sits_on_the_closed_form_fixed_point() {
    let d = dir("diagram");
    let (out, data) = (d.join("d.svg"), d.join("d.json"));
    ok(&bouncemap(&[
        "figure",
        "diagram",
        "--table",
        "fd:0.1",
        "--alpha",
        "0.45..0.47",
        "--steps",
        "5",
        "--transient",
        "20000",
        "--keep",
        "10",
        "--out",
        s(&out),
        "--data",
        s(&data),
    ]));
    let fig = json(&data);
    let pts = series(&fig, "phase");
    assert_eq!(pts.len(), 5 * 10);
    // On the stable (1, 1) branch: f'(t̂*) = ½(1 − r)/(1 + r) on the first piece of F_0.1,
    // α(3D t̂² − (2 + D) t̂ + ½) = 1/18, the smaller root.
    for p in pts {
        let (a, t) = (p[0].as_f64().unwrap(), p[1].as_f64().unwrap());
        let dd = 0.1;
        let (qa, qb, qc) = (3.0 * dd * a, -(2.0 + dd) * a, 0.5 * a - 1.0 / 18.0);
        let star = (-qb - (qb * qb - 4.0 * qa * qc).sqrt()) / (2.0 * qa);
        assert!((t - star).abs() < 1e-8, "α = {a}: t̂ = {t}, t̂* = {star}");
    }
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn bad_input_is_one_line_with_status_2_and_writes_nothing() {
    let d = dir("bad");
    let out = d.join("f.png");
    for (args, needle) in [
        (vec!["figure", "fig9"], "valid fig2, fig3"),
        (vec!["figure"], "valid fig2, fig3"),
        (vec!["figure", "fig2", "--dpi", "10"], "[50, 600]"),
        (vec!["figure", "fig2", "--dpi", "2.5"], "whole number"),
        (vec!["figure", "fig2", "--size", "0.5x2"], "[1, 12]"),
        (vec!["figure", "fig2", "--size", "3x40"], "[1, 12]"),
        (vec!["figure", "fig2", "--size", "big"], "WxH"),
        (vec!["figure", "fig2", "--alpha", "0.5"], "--alpha"),
        (vec!["figure", "diagram", "--alpha", "0.5"], "window"),
    ] {
        let mut a = args.clone();
        a.extend(["--out", s(&out)]);
        let o = bouncemap(&a);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!out.exists(), "{args:?} wrote a file");
    }
    // A file name without a format, and a directory that does not exist.
    for target in [d.join("f.pdf"), d.join("missing").join("f.png")] {
        let o = bouncemap(&["figure", "fig2", "--out", s(&target)]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains(s(&target)), "{err}");
        assert!(!target.exists());
    }
    assert_eq!(
        std::fs::read_dir(&d).unwrap().count(),
        0,
        "nothing left behind"
    );
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn a_failed_write_names_the_file_and_leaves_the_old_one() {
    let o = bouncemap(&["figure", "fig2", "--out", "/dev/full", "--format", "png"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("cannot write /dev/full"), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    // A run refused after the file was named leaves what was there before.
    let d = dir("keep");
    let out = d.join("f.png");
    std::fs::write(&out, b"old").unwrap();
    let o = bouncemap(&["figure", "diagram", "--preset", "nope", "--out", s(&out)]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(std::fs::read(&out).unwrap(), b"old");
    assert_eq!(
        std::fs::read_dir(&d).unwrap().count(),
        1,
        "no temporary left"
    );
    std::fs::remove_dir_all(&d).unwrap();
}

/// `figure basins` on the cubic table at α = 0.47, r = 0.8, where the stable (1, 1)
/// solution coexists with a sticking cycle: every start is a cell of some attractor,
/// and the periodic attractor's marked point is the closed-form (1, 1) point.
#[test]
fn basins_cover_the_grid_and_mark_the_closed_form_fixed_point() {
    let d = dir("basins");
    let (out, data) = (d.join("b.svg"), d.join("b.json"));
    ok(&bouncemap(&[
        "figure",
        "basins",
        "--table",
        "cubic",
        "--alpha",
        "0.47",
        "--r",
        "0.8",
        "--grid",
        "40x20",
        "--out",
        s(&out),
        "--data",
        s(&data),
    ]));
    let fig = json(&data);
    let cells: usize = fig["panels"][0]["series"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|s| s["kind"] == "cells")
        .map(|s| s["points"].as_array().unwrap().len())
        .sum();
    assert_eq!(cells, 40 * 20);
    // (1, 1) on the first piece of F_1 (α(3t̂² − 3t̂ + ½) = ½(1 − r)/(1 + r) = 1/18, the
    // smaller root); after the impact v = ½, so w = ½ − α F'(t̂*) = ½ − 1/18.
    let a: f64 = 0.47;
    let (qa, qb, qc) = (3.0 * a, -3.0 * a, 0.5 * a - 1.0 / 18.0);
    let star = (-qb - (qb * qb - 4.0 * qa * qc).sqrt()) / (2.0 * qa);
    let pts = series(&fig, "attractor points");
    assert!(
        pts.iter().any(|p| {
            (p[0].as_f64().unwrap() - star).abs() < 1e-8
                && (p[1].as_f64().unwrap() - (0.5 - 1.0 / 18.0)).abs() < 1e-8
        }),
        "{pts:?} vs t̂* = {star}"
    );
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(
        svg.contains("periodic (1, 1)"),
        "legend names the attractor"
    );
    std::fs::remove_dir_all(&d).unwrap();
}

/// `figure lyapunov` over the stable (1, 1) branch of fd:0.1: the stable point's
/// eigenvalues are complex with |λ|² = det J = r², so every exponent is ln r.
#[test]
fn the_lyapunov_figure_shows_ln_r_on_the_stable_branch() {
    let d = dir("lyapunov");
    let (out, data) = (d.join("l.png"), d.join("l.json"));
    ok(&bouncemap(&[
        "figure",
        "lyapunov",
        "--table",
        "fd:0.1",
        "--alpha",
        "0.45..0.47",
        "--steps",
        "6",
        "--transient",
        "20000",
        "--near-fixed-point",
        "--out",
        s(&out),
        "--data",
        s(&data),
    ]));
    let fig = json(&data);
    let lines = fig["panels"][1]["series"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["name"] == "lyapunov")
        .unwrap()["lines"]
        .as_array()
        .unwrap()
        .clone();
    let pts: Vec<&serde_json::Value> = lines.iter().flat_map(|l| l.as_array().unwrap()).collect();
    assert_eq!(pts.len(), 6);
    for p in pts {
        let l = p[1].as_f64().unwrap();
        assert!((l - 0.8f64.ln()).abs() < 1e-9, "{p}");
    }
    assert!(std::fs::metadata(&out).unwrap().len() > 1000);
    std::fs::remove_dir_all(&d).unwrap();
}

/// `figure plane` over (α, D): every pixel is a cell of exactly one class, and on the
/// row D = 0 (F_0, f'' = −2α on the stable solution's piece) the α_PD curve and the
/// end of the period-1 cells sit at the closed form α_PD = −κ_c/2 = (1 + r²)/(1 + r)².
#[test]
fn the_plane_figure_covers_every_pixel_and_puts_alpha_pd_at_its_closed_form() {
    let d = dir("plane");
    let (out, data) = (d.join("p.svg"), d.join("p.json"));
    ok(&bouncemap(&[
        "figure",
        "plane",
        "--table",
        "fd",
        "--x",
        "alpha:0.45..0.6",
        "--y",
        "d:0..1",
        "--r",
        "0.8",
        "--pixels",
        "60x11",
        "--out",
        s(&out),
        "--data",
        s(&data),
    ]));
    let fig = json(&data);
    let all = fig["panels"][0]["series"].as_array().unwrap();
    let cells: usize = all
        .iter()
        .filter(|s| s["kind"] == "cells")
        .map(|s| s["points"].as_array().unwrap().len())
        .sum();
    assert_eq!(cells, 60 * 11);
    let r: f64 = 0.8;
    let pd0 = (1.0 + r * r) / ((1.0 + r) * (1.0 + r));
    let line = all.iter().find(|s| s["name"] == "alpha_pd").unwrap()["lines"][0][0].clone();
    assert_eq!(line[1].as_f64().unwrap(), 0.0);
    assert!(
        (line[0].as_f64().unwrap() - pd0).abs() < 1e-10,
        "{line} vs {pd0}"
    );
    let dx = 0.15 / 59.0;
    let period1 = series(&fig, "period-1");
    let last = period1
        .iter()
        .filter(|p| p[1].as_f64().unwrap() == 0.0)
        .map(|p| p[0].as_f64().unwrap())
        .fold(f64::NEG_INFINITY, f64::max);
    assert!(
        (last - pd0).abs() <= dx,
        "last period-1 pixel {last}, α_PD {pd0}"
    );
    // The caption says the table, what is fixed and the size, and names the curves drawn.
    let caption = fig["caption"][0].as_str().unwrap();
    assert!(
        caption.starts_with("fd:D, r = 0.8: 60\u{d7}11 pixels"),
        "{caption}"
    );
    assert!(caption.contains("border collision of (2, 2)."), "{caption}");
    // The figure's own --size is inches; the plane's pixels are --pixels.
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(svg.contains("border collision of (2, 2)"));
    std::fs::remove_dir_all(&d).unwrap();
}

/// `figure plane --quick` caps the pixels at 100×50 and the transient at 2·10⁴; an
/// (α, r) plane fixes nothing, and its caption says only the table.
#[test]
fn the_quick_plane_figure_is_at_most_100_by_50_pixels_and_2e4_periods() {
    let d = dir("plane-quick");
    let (out, data) = (d.join("q.svg"), d.join("q.json"));
    ok(&bouncemap(&[
        "figure",
        "plane",
        "--quick",
        "--table",
        "sine",
        "--x",
        "alpha:0.02..0.025",
        "--y",
        "r:0.6..0.9",
        "--pixels",
        "400x200",
        "--transient",
        "50000",
        "--out",
        s(&out),
        "--data",
        s(&data),
    ]));
    let fig = json(&data);
    let cells: usize = fig["panels"][0]["series"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|s| s["kind"] == "cells")
        .map(|s| s["points"].as_array().unwrap().len())
        .sum();
    assert_eq!(cells, 100 * 50);
    let caption = fig["caption"][0].as_str().unwrap();
    assert!(
        caption.starts_with("sine: 100\u{d7}50 pixels, each an orbit"),
        "{caption}"
    );
    assert!(
        caption.contains("up to 2\u{b7}10\u{2074} table periods"),
        "{caption}"
    );
    std::fs::remove_dir_all(&d).unwrap();
}

/// `figure attractors` on the cubic table across the (1, 1) solution's period doubling
/// (α_PD = 0.48383449168, `fixed`): the stacked fractions fill [0, 1] at every α, and
/// the (1, 1) attractor's points are the closed-form phase below α_PD and two phases
/// (the (2, 2) cycle) above it.
#[test]
fn the_attractors_figure_stacks_fractions_to_one_and_doubles_at_alpha_pd() {
    let d = dir("attractors");
    let (out, data, svg) = (d.join("a.png"), d.join("a.json"), d.join("a.svg"));
    let draw = |more: &[&str]| {
        let mut args = vec![
            "figure",
            "attractors",
            "--table",
            "cubic",
            "--r",
            "0.8",
            "--alpha",
            "0.475..0.495",
            "--steps",
            "5",
            "--grid",
            "20x20",
        ];
        args.extend_from_slice(more);
        ok(&bouncemap(&args));
    };
    draw(&["--out", s(&out), "--data", s(&data)]);
    let fig = json(&data);
    let areas: Vec<&serde_json::Value> = fig["panels"][1]["series"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|s| s["kind"] == "area")
        .collect();
    assert!(areas.len() >= 2, "{areas:?}");
    // The top of the last band at each α is 1 (nothing is not settled here).
    let top = &areas.last().unwrap()["lines"][1];
    for p in top.as_array().unwrap() {
        assert!((p[1].as_f64().unwrap() - 1.0).abs() < 1e-12, "{p}");
    }
    // The attractor that holds the (1, 1) solution at α = 0.475.
    let a: f64 = 0.475;
    let (qa, qb, qc) = (3.0 * a, -3.0 * a, 0.5 * a - 1.0 / 18.0);
    let star = (-qb - (qb * qb - 4.0 * qa * qc).sqrt()) / (2.0 * qa);
    let series = fig["panels"][0]["series"].as_array().unwrap();
    let p11 = series
        .iter()
        .find(|s| {
            s["points"].as_array().unwrap().iter().any(|p| {
                p[0].as_f64().unwrap() == 0.475 && (p[1].as_f64().unwrap() - star).abs() < 1e-9
            })
        })
        .unwrap_or_else(|| panic!("t̂* = {star} not among {series:?}"));
    let at = |alpha: f64| -> usize {
        p11["points"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|p| (p[0].as_f64().unwrap() - alpha).abs() < 1e-12)
            .count()
    };
    assert_eq!((at(0.475), at(0.48)), (1, 1));
    assert_eq!((at(0.49), at(0.495)), (2, 2));
    assert!(std::fs::metadata(&out).unwrap().len() > 1000);
    // The legend names it by what it is first and last: the (1, 1) cycle, then past
    // α_PD the (2, 2) (the SVG keeps its text as text).
    draw(&["--out", s(&svg)]);
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(
        text.contains("periodic (1, 1) \u{2192} periodic (2, 2), 0.4750\u{2013}0.4950"),
        "{text}"
    );
    std::fs::remove_dir_all(&d).unwrap();
}
