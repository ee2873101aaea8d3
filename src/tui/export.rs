//! `e`: write the current diagram next to each other in a directory, as csv (the same
//! rows as `bouncemap sweep`, after a `#` line stating the run) and as the braille text
//! of the plot.

use super::app::App;
use crate::output::records::{csv_writer, SweepRow};
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
    let fail =
        |p: &Path, e: &dyn std::fmt::Display| format!("export: cannot write {}: {e}", p.display());
    let spec = d.sweep_spec(app);
    let p = &app.params;
    let mut body = format!(
        "# table={} r={} k={} window=[{}, {}] transient={} keep={}\n",
        p.table_label(),
        p.r,
        p.k,
        p.lo,
        p.hi,
        p.transient,
        p.keep
    )
    .into_bytes();
    {
        let mut w =
            csv_writer(&mut body, &SweepRow::header(spec.param)).map_err(|e| fail(&csv, &e))?;
        for r in d.slots.iter().flatten() {
            for row in SweepRow::rows(r) {
                w.serialize(row).map_err(|e| fail(&csv, &e))?;
            }
        }
        w.flush().map_err(|e| fail(&csv, &e))?;
    }
    let mut out = std::fs::File::create(&csv).map_err(|e| fail(&csv, &e))?;
    out.write_all(&body).map_err(|e| fail(&csv, &e))?;
    let mut text = d.grid.to_text().join("\n");
    text.push('\n');
    std::fs::write(&txt, text).map_err(|e| fail(&txt, &e))?;
    Ok((csv, txt))
}
