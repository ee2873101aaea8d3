//! `e`: write the current diagram under a typed name (default `bouncemap-diagram-N` in
//! the working directory, the first N free: [`free_name`]): `NAME.csv`, a sweep file in
//! the format of `bouncemap sweep` (the run's specification and provenance, the same
//! rows with period, status and exponent; its values are those the diagram holds so
//! far), and `NAME.txt`, the diagram as `sweep --format braille` draws it (title with
//! the window, axes, labels). Both written atomically; an existing file is never
//! replaced.
//!
//! `E` writes the same two files and the current view as figures beside them (default
//! name `bouncemap-view-N`): `NAME-diagram.svg/.png` (the diagram over its zoom window,
//! the parameters in the caption) and `NAME-phase.svg/.png` (the phase plot), and with
//! the basins panel or the plane view shown and complete `NAME-basins.svg/.png` or
//! `NAME-plane.svg/.png`, drawn by [`bouncemap_figures`] and written by
//! [`crate::output::figure_file`]. The files are named here once, for the default names
//! and for writing.

use super::components::{Panels, Shared};
use crate::output::diagram::BrailleDiagram;
use crate::output::records::SweepHeader;
use crate::output::sink::{free_stem, AtomicFile};
use crate::output::sweep_file::{Layout, SweepWriter};
use std::io::Write;
use std::path::{Path, PathBuf};

/// The ends of the files `e` writes.
const FILES: [&str; 2] = [".csv", ".txt"];
/// The ends of the figures `E` writes besides them, always (the diagram, the phase plot).
const VIEW: [&str; 4] = ["-diagram.svg", "-diagram.png", "-phase.svg", "-phase.png"];

/// The default name of an export in `dir`: the first `bouncemap-diagram-N` (`e`) or,
/// with `view`, `bouncemap-view-N` (`E`) with none of its files taken.
pub fn free_name(dir: &Path, view: bool) -> String {
    if view {
        let ends: Vec<&str> = FILES.iter().chain(&VIEW).copied().collect();
        free_stem(dir, "bouncemap-view", &ends)
    } else {
        free_stem(dir, "bouncemap-diagram", &FILES)
    }
}

/// `stem` with `ext` appended (the stem may hold dots).
fn with(stem: &Path, ext: &str) -> PathBuf {
    let mut s = stem.as_os_str().to_owned();
    s.push(ext);
    PathBuf::from(s)
}

/// `stem.csv` and `stem.txt`.
fn paths(stem: &Path) -> (PathBuf, PathBuf) {
    (with(stem, FILES[0]), with(stem, FILES[1]))
}

/// The files `E` writes for `stem`, besides the csv and the text: the diagram, the
/// phase plot, and the basins and the plane when they are shown with a complete
/// picture.
pub fn view_paths(stem: &Path, basins: bool, plane: bool) -> Vec<PathBuf> {
    let mut ends = VIEW.to_vec();
    if basins {
        ends.extend(["-basins.svg", "-basins.png"]);
    }
    if plane {
        ends.extend(["-plane.svg", "-plane.png"]);
    }
    ends.iter().map(|e| with(stem, e)).collect()
}

/// `E`: the csv and the text of [`export`], and the diagram and the phase plot as
/// SVG and PNG. Returns every path written.
pub fn export_view(shared: &Shared, panels: &Panels, stem: &Path) -> Result<Vec<PathBuf>, String> {
    use crate::output::figure_file;
    use bouncemap_figures::{self as figure, DiagramAxis, ImageFormat, DEFAULT_DPI};
    let b = &panels.basins.view;
    let basins = match (b.shown, &b.spec, &b.picture) {
        (true, Some(spec), Some(pic)) if pic.complete() => {
            Some(figure::basins::basins_figure(spec, pic))
        }
        _ => None,
    };
    let pl = &panels.plane;
    let plane = match (pl.view.shown, &pl.view.spec, &pl.view.picture) {
        (true, Some(spec), Some(pic)) if pic.complete() => Some(figure::plane::plane_figure(
            spec,
            pic.pixels(),
            pl.curves.as_ref(),
        )),
        _ => None,
    };
    let views = view_paths(stem, basins.is_some(), plane.is_some());
    if let Some(p) = views.iter().find(|p| p.exists()) {
        return Err(format!(
            "export: {} exists and is kept; type another name",
            p.display()
        ));
    }
    let (csv, txt) = export(shared, panels, stem)?;
    let d = &panels.diagram;
    let spec = d.running.clone().unwrap_or_else(|| d.sweep_spec(shared));
    let p = &shared.params;
    let n = crate::output::text::shortest;
    let system = format!(
        "{}, α = {}, r = {}, k = {}",
        p.table_label(),
        n(p.alpha),
        n(p.r),
        p.k
    );
    let caption = format!("{system}, start {}", p.start.key());
    let axis = match d.axis {
        crate::tui::components::diagram::Axis::Phase => DiagramAxis::Phase,
        crate::tui::components::diagram::Axis::Velocity => DiagramAxis::Velocity,
    };
    let diagram = figure::diagram_view(
        &spec,
        d.slots.iter().flatten(),
        Some((p.lo, p.hi)),
        axis,
        &caption,
    );
    let v0 = p.v0.map_or("f'(t̂0) + 0.5".to_string(), n);
    let phase = figure::phase_view(
        &panels.phase.points,
        &format!(
            "{system}: every event of the orbit from t̂0 = {}, v0 = {v0} ({} events)",
            n(p.t0),
            panels.phase.points.len()
        ),
    );
    let mut written = vec![csv, txt];
    let mut figures = vec![
        (&diagram, &views[0], &views[1]),
        (&phase, &views[2], &views[3]),
    ];
    let mut next = 4;
    for f in [&basins, &plane].into_iter().flatten() {
        figures.push((f, &views[next], &views[next + 1]));
        next += 2;
    }
    for (fig, svg, png) in figures {
        figure_file::write(fig, svg, ImageFormat::Svg, None, DEFAULT_DPI)
            .and_then(|_| figure_file::write(fig, png, ImageFormat::Png, None, DEFAULT_DPI))
            .map_err(|e| format!("export: {e}"))?;
        written.push(svg.clone());
        written.push(png.clone());
    }
    Ok(written)
}

/// Write `stem.csv` and `stem.txt` (relative to the working directory). Returns the
/// two paths.
pub fn export(shared: &Shared, panels: &Panels, stem: &Path) -> Result<(PathBuf, PathBuf), String> {
    let d = &panels.diagram;
    if d.plotted == 0 {
        return Err("export: the diagram has no points yet".into());
    }
    if stem.as_os_str().is_empty() {
        return Err("export: no file name given".into());
    }
    let (csv, txt) = paths(stem);
    for p in [&csv, &txt] {
        if p.exists() {
            return Err(format!(
                "export: {} exists and is kept; type another name",
                p.display()
            ));
        }
    }
    // The sweep the stored values come from (the screen may have changed since).
    let spec = d.running.clone().unwrap_or_else(|| d.sweep_spec(shared));
    let values: Vec<_> = d.slots.iter().flatten().collect();
    let mut f = AtomicFile::create(&csv).map_err(|e| format!("export: {e}"))?;
    let written = (|| -> std::io::Result<()> {
        let mut w = SweepWriter::begin(
            &mut f,
            Layout::Csv,
            &SweepHeader::from(&spec),
            "1/1",
            values.len(),
        )?;
        for r in &values {
            w.value(r)?;
        }
        w.end()?;
        Ok(())
    })();
    written.map_err(|e| format!("export: cannot write {}: {e}", csv.display()))?;
    f.commit().map_err(|e| format!("export: {e}"))?;
    // The text: as `sweep --format braille` draws it, at the diagram's size.
    let (w, h) = d.grid.size();
    let mut picture = BrailleDiagram::new(&spec, w.max(20) + 6, h.max(6) + 4);
    for r in &values {
        picture.add(r);
    }
    let mut text = picture.lines(&spec).join("\n");
    text.push('\n');
    let mut t = AtomicFile::create(&txt).map_err(|e| format!("export: {e}"))?;
    t.write_all(text.as_bytes())
        .map_err(|e| format!("export: cannot write {}: {e}", txt.display()))?;
    t.commit().map_err(|e| format!("export: {e}"))?;
    Ok((csv, txt))
}
