//! `e`: write the current diagram under a typed name (default `bouncemap-diagram-N` in
//! the working directory, the first N free): `NAME.csv`, a sweep file in the format of
//! `bouncemap sweep` (the run's specification and provenance, the same rows with
//! period, status and exponent; its values are those the diagram holds so far), and
//! `NAME.txt`, the diagram as `sweep --format braille` draws it (title with the
//! window, axes, labels). Both written atomically; an existing file is never replaced.

use super::app::App;
use crate::output::diagram::BrailleDiagram;
use crate::output::records::SweepHeader;
use crate::output::sink::AtomicFile;
use crate::output::sweep_file::{Layout, SweepWriter};
use std::io::Write;
use std::path::{Path, PathBuf};

/// The first `bouncemap-diagram-N` in `dir` with neither file taken.
pub fn free_name(dir: &Path) -> String {
    crate::output::sink::free_stem(dir, "bouncemap-diagram", &[".csv", ".txt"])
}

/// `stem.csv` and `stem.txt`.
fn paths(stem: &Path) -> (PathBuf, PathBuf) {
    let with = |ext: &str| {
        let mut s = stem.as_os_str().to_owned();
        s.push(ext);
        PathBuf::from(s)
    };
    (with(".csv"), with(".txt"))
}

/// Write `stem.csv` and `stem.txt` (relative to the working directory). Returns the
/// two paths.
pub fn export(app: &App, stem: &Path) -> Result<(PathBuf, PathBuf), String> {
    let d = &app.diagram;
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
    let spec = d.running.clone().unwrap_or_else(|| d.sweep_spec(app));
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
