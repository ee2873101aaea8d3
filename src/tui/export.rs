//! `e`: write the current diagram as csv (one row per point: alpha, phase, v, complete,
//! sticking) and as the braille text of the plot, next to each other in a directory.

use super::app::App;
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
    let fail = |p: &Path, e: std::io::Error| format!("export: cannot write {}: {e}", p.display());
    let mut out = std::io::BufWriter::new(std::fs::File::create(&csv).map_err(|e| fail(&csv, e))?);
    let p = &app.params;
    let mut body = format!(
        "# table={} r={} k={} window=[{}, {}] transient={} keep={}\nalpha,phase,v,complete,sticking\n",
        p.table_label(),
        p.r,
        p.k,
        p.lo,
        p.hi,
        p.transient,
        p.keep
    );
    let mut slots: Vec<_> = d.slots.iter().flatten().collect();
    slots.sort_by(|a, b| a.value.total_cmp(&b.value));
    for s in slots {
        for (t, v) in &s.points {
            body.push_str(&format!(
                "{},{},{},{},{}\n",
                s.value, t, v, s.complete, s.sticking
            ));
        }
    }
    out.write_all(body.as_bytes())
        .and_then(|_| out.flush())
        .map_err(|e| fail(&csv, e))?;
    let mut text = d.grid.to_text().join("\n");
    text.push('\n');
    std::fs::write(&txt, text).map_err(|e| fail(&txt, e))?;
    Ok((csv, txt))
}
