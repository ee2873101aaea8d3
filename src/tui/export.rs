//! `e`: write the current diagram under a typed name (default `bouncemap-diagram-N` in
//! the working directory, the first N free: [`free_name`]): `NAME.csv`, a sweep file in
//! the format of `bouncemap sweep` (the run's specification and provenance, the same
//! rows with period, status and exponent; its values are those the diagram holds so
//! far), and `NAME.txt`, the diagram as `sweep --format braille` draws it (title with
//! the window and the starts, axes, labels).
//!
//! `E` writes the same two files and the current view as figures beside them (default
//! name `bouncemap-view-N`): `NAME-diagram.svg/.png` (the diagram over its zoom window,
//! coloured as the screen colours it, the parameters and the starts in the caption)
//! and `NAME-phase.svg/.png` (the phase plot); with the attractors along α shown,
//! `NAME-attractors.svg/.png` (`figure attractors` of the values done so far, written
//! at once with the others); with the plane view or the basins shown,
//! `NAME-plane.svg/.png` or `NAME-basins.svg/.png` at the export's own resolution
//! (computed in the background by [`super::components::view_export`], with the
//! two-parameter curves `C` shows). The files written at once are written together
//! (all or none); an existing file is never replaced. The files are named here once,
//! for the default names, the prompt and writing.

use super::components::plane_curves::MAX_PERIOD;
use super::components::view_export::{PictureExport, Request};
use super::components::{Effect, Panels, Registered, Shared};
use crate::output::diagram::BrailleDiagram;
use crate::output::records::SweepHeader;
use crate::output::sink::{free_stem, AtomicFile};
use crate::output::sweep_file::{Layout, SweepWriter};
use bouncemap_engine::attractors::basins::Basins;
use bouncemap_engine::plane::Plane;
use std::io::Write;
use std::path::{Path, PathBuf};

/// The resolution of `E`'s plane and basins figures, computed for the export.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ExportSizes {
    /// Pixels along α and along the other axis.
    pub plane: (usize, usize),
    /// Starts along t̂0 and along w0.
    pub basins: (usize, usize),
}

impl Default for ExportSizes {
    /// The commands' defaults (`plane --size`, `basins --grid`).
    fn default() -> Self {
        use crate::config::flags::{parse_grid, parse_plane_size};
        use crate::config::rules::{BASINS_GRID, PLANE_SIZE};
        ExportSizes {
            plane: parse_plane_size(PLANE_SIZE).expect("the default plane size parses"),
            basins: parse_grid(BASINS_GRID).expect("the default basins grid parses"),
        }
    }
}

/// The ends of the files `e` writes.
const FILES: [&str; 2] = [".csv", ".txt"];
/// The ends of the figures `E` writes besides them, always (the diagram, the phase plot).
const VIEW: [&str; 4] = ["-diagram.svg", "-diagram.png", "-phase.svg", "-phase.png"];
/// The ends of the figures of the views that may be shown.
const PLANE: [&str; 2] = ["-plane.svg", "-plane.png"];
const BASINS: [&str; 2] = ["-basins.svg", "-basins.png"];
const ATTRACTORS: [&str; 2] = ["-attractors.svg", "-attractors.png"];

/// The default name of an export in `dir`: the first `bouncemap-diagram-N` (`e`) or,
/// with `view`, `bouncemap-view-N` (`E`) with none of its files taken.
pub fn free_name(dir: &Path, view: bool) -> String {
    if view {
        let ends: Vec<&str> = FILES
            .iter()
            .chain(&VIEW)
            .chain(&PLANE)
            .chain(&BASINS)
            .chain(&ATTRACTORS)
            .copied()
            .collect();
        free_stem(dir, "bouncemap-view", &ends)
    } else {
        free_stem(dir, "bouncemap-diagram", &FILES)
    }
}

/// What the export being named will write, for the prompt: the ends added to the name.
pub fn prompt_note(view: bool, panels: &Panels) -> String {
    if !view {
        return ".csv and .txt are added".into();
    }
    let mut ends = vec![".csv", ".txt", "-diagram.svg/.png", "-phase.svg/.png"];
    if along_alpha(panels) {
        ends.push("-attractors.svg/.png");
    }
    if panels.plane.view.shown {
        ends.push("-plane.svg/.png");
    }
    if panels.basins.view.shown {
        ends.push("-basins.svg/.png");
    }
    format!("{} are added", ends.join(", "))
}

/// Whether the attractors along α are shown with at least one value done (`E` then
/// draws them).
fn along_alpha(panels: &Panels) -> bool {
    panels.global.shown && !panels.global.steps.is_empty()
}

/// `figure attractors` of the values the attractors-along-α view has done so far.
fn attractors_figure(panels: &Panels) -> Result<bouncemap_figures::Figure, String> {
    use bouncemap_engine::attractors::global::Continuation;
    let g = &panels.global;
    let spec = g
        .spec
        .clone()
        .ok_or("export: no attractors along α to draw")?;
    let cont = Continuation::from_parts(
        spec,
        0..g.steps.len(),
        g.steps.clone(),
        g.changes.clone(),
        g.tracks.clone(),
    )
    .map_err(|e| format!("export: the attractors along α: {e}"))?;
    Ok(bouncemap_figures::global::attractors_figure(&cont))
}

/// `stem` with `ext` appended (the stem may hold dots).
fn with(stem: &Path, ext: &str) -> PathBuf {
    let mut s = stem.as_os_str().to_owned();
    s.push(ext);
    PathBuf::from(s)
}

/// Refuse an export whose files exist (each one is kept).
fn none_taken(paths: &[PathBuf]) -> Result<(), String> {
    match paths.iter().find(|p| p.exists()) {
        Some(p) => Err(format!(
            "export: {} exists and is kept; type another name",
            p.display()
        )),
        None => Ok(()),
    }
}

/// `E`: the csv and the text of [`export`], the diagram and the phase plot as SVG and
/// PNG, written together; and the plane's or the basins' figures asked of their
/// export panels (at `sizes`). Returns the message naming every file.
pub fn export_view(
    shared: &mut Shared,
    panels: &mut Panels,
    sizes: ExportSizes,
    stem: &Path,
) -> Result<String, String> {
    use bouncemap_figures::{self as figure, DiagramAxis, ImageFormat, DEFAULT_DPI};
    let plane = panels.plane.view.shown;
    let basins = panels.basins.view.shown;
    let views: Vec<PathBuf> = VIEW.iter().map(|e| with(stem, e)).collect();
    let attractors: Vec<PathBuf> = match along_alpha(panels) {
        true => ATTRACTORS.iter().map(|e| with(stem, e)).collect(),
        false => Vec::new(),
    };
    let mut later: Vec<PathBuf> = Vec::new();
    if plane {
        later.extend(PLANE.iter().map(|e| with(stem, e)));
    }
    if basins {
        later.extend(BASINS.iter().map(|e| with(stem, e)));
    }
    none_taken(&views)?;
    none_taken(&attractors)?;
    none_taken(&later)?;
    let mut files = diagram_files(shared, panels, stem)?;
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
    let axis = match d.axis {
        crate::tui::components::diagram::Axis::Phase => DiagramAxis::Phase,
        crate::tui::components::diagram::Axis::Velocity => DiagramAxis::Velocity,
    };
    let diagram = figure::diagram_view(
        &spec,
        d.slots.iter().flatten(),
        Some((p.lo, p.hi)),
        axis,
        d.color_by,
        &system,
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
    let along = match attractors.is_empty() {
        true => None,
        false => Some(attractors_figure(panels)?),
    };
    let mut figures = vec![(&diagram, &views[0..2]), (&phase, &views[2..4])];
    if let Some(f) = &along {
        figures.push((f, &attractors[..]));
    }
    for (fig, paths) in figures {
        for (path, format) in paths.iter().zip([ImageFormat::Svg, ImageFormat::Png]) {
            let bytes = figure::render(fig, format, None, DEFAULT_DPI)
                .map_err(|e| format!("export: {e}"))?;
            files.push(write_file(path, &bytes)?);
        }
    }
    let written: Vec<String> = files
        .iter()
        .map(|f| f.path().display().to_string())
        .collect();
    AtomicFile::commit_all(files).map_err(|e| format!("export: {e}"))?;
    let mut msg = format!("export: wrote {}", written.join(", "));
    // The views shown, at the export's resolution, in the background.
    if plane {
        msg.push_str(&ask_plane(shared, panels, sizes.plane, stem));
    }
    if basins {
        msg.push_str(&ask_basins(shared, panels, sizes.basins, stem));
    }
    Ok(msg)
}

/// Ask for the plane's figure at `size` pixels, with the curves `C` shows; the words
/// the message adds.
fn ask_plane(
    shared: &mut Shared,
    panels: &mut Panels,
    size: (usize, usize),
    stem: &Path,
) -> String {
    let Some(mut spec) = panels.plane.view.spec.clone() else {
        return "; no plane to export (it was refused)".into();
    };
    spec.x.n = size.0;
    spec.y.n = size.1;
    let (over, note) = match (&shared.plane_curves, shared.show_plane_curves) {
        (Some(Ok(c)), true) => (Some((c.clone(), MAX_PERIOD)), ", with the curves"),
        (None, true) => (None, ", without the curves (still computing)"),
        _ => (None, ""),
    };
    let [svg, png] = PictureExport::<Plane>::paths(stem);
    panels.plane_export.ask(Request {
        stem: stem.to_path_buf(),
        spec,
        over,
    });
    shared.effect(Effect::Start(<PictureExport<Plane> as Registered>::TARGET));
    format!(
        "; computing {} and {} at {}×{} pixels{note}",
        svg.display(),
        png.display(),
        size.0,
        size.1
    )
}

/// Ask for the basins' figure at `size` starts; the words the message adds.
fn ask_basins(
    shared: &mut Shared,
    panels: &mut Panels,
    size: (usize, usize),
    stem: &Path,
) -> String {
    let Some(mut spec) = panels.basins.view.spec.clone() else {
        return "; no basins to export (they were refused)".into();
    };
    spec.nx = size.0;
    spec.ny = size.1;
    let [svg, png] = PictureExport::<Basins>::paths(stem);
    panels.basins_export.ask(Request {
        stem: stem.to_path_buf(),
        spec,
        over: (),
    });
    shared.effect(Effect::Start(<PictureExport<Basins> as Registered>::TARGET));
    format!(
        "; computing {} and {} at {}×{} starts",
        svg.display(),
        png.display(),
        size.0,
        size.1
    )
}

/// `path` written with `bytes`, to be committed with the others.
fn write_file(path: &Path, bytes: &[u8]) -> Result<AtomicFile, String> {
    let mut f = AtomicFile::create(path).map_err(|e| format!("export: {e}"))?;
    f.write_all(bytes)
        .map_err(|e| format!("export: cannot write {}: {e}", path.display()))?;
    Ok(f)
}

/// `stem.csv` and `stem.txt`, written but not yet in place.
fn diagram_files(shared: &Shared, panels: &Panels, stem: &Path) -> Result<Vec<AtomicFile>, String> {
    let d = &panels.diagram;
    if d.plotted == 0 {
        return Err("export: the diagram has no points yet".into());
    }
    if stem.as_os_str().is_empty() {
        return Err("export: no file name given".into());
    }
    let (csv, txt) = (with(stem, FILES[0]), with(stem, FILES[1]));
    none_taken(&[csv.clone(), txt.clone()])?;
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
    // The text: as `sweep --format braille` draws it, at the diagram's size.
    let (w, h) = d.grid.size();
    let mut picture = BrailleDiagram::new(&spec, w.max(20) + 6, h.max(6) + 4);
    for r in &values {
        picture.add(r);
    }
    let mut text = picture.lines(&spec).join("\n");
    text.push('\n');
    let t = write_file(&txt, text.as_bytes())?;
    Ok(vec![f, t])
}

/// `e`: write `stem.csv` and `stem.txt` (relative to the working directory) together.
/// Returns the two paths.
pub fn export(shared: &Shared, panels: &Panels, stem: &Path) -> Result<(PathBuf, PathBuf), String> {
    let files = diagram_files(shared, panels, stem)?;
    let paths = (files[0].path().to_path_buf(), files[1].path().to_path_buf());
    AtomicFile::commit_all(files).map_err(|e| format!("export: {e}"))?;
    Ok(paths)
}
