//! `e`: write the current diagram next to each other in a directory: a sweep file (the
//! same format as `bouncemap sweep`, with the run's specification and provenance; its
//! values are those the diagram holds so far) and the braille text of the plot. Both
//! written atomically.

use super::app::App;
use crate::output::records::SweepHeader;
use crate::output::sink::AtomicFile;
use crate::output::sweep_file::{Layout, SweepWriter};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Write `bouncemap-diagram-N.csv` and `.txt` into `dir` (N the first free number).
/// Returns the two paths.
pub fn export(app: &App, dir: &Path) -> Result<(PathBuf, PathBuf), String> {
    let d = &app.diagram;
    if d.plotted == 0 {
        return Err("export: the diagram has no points yet".into());
    }
    let (csv, txt) = (1..10_000)
        .map(|n| {
            (
                dir.join(format!("bouncemap-diagram-{n}.csv")),
                dir.join(format!("bouncemap-diagram-{n}.txt")),
            )
        })
        .find(|(c, t)| !c.exists() && !t.exists())
        .ok_or("export: no free file name")?;
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
    let mut t = AtomicFile::create(&txt).map_err(|e| format!("export: {e}"))?;
    let mut text = d.grid.to_text().join("\n");
    text.push('\n');
    t.write_all(text.as_bytes())
        .map_err(|e| format!("export: cannot write {}: {e}", txt.display()))?;
    t.commit().map_err(|e| format!("export: {e}"))?;
    Ok((csv, txt))
}
