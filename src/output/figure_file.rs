//! A figure in a file: drawn by `bouncemap_figures` (SVG text or PNG bytes), written
//! here atomically through [`super::sink`] (a temporary beside the file, renamed into
//! place when complete), for `figure` and the terminal application's exports.

use super::sink::AtomicFile;
use bouncemap_figures::{render, Figure, ImageFormat};
use std::io::Write;
use std::path::Path;

/// Write `figure` to `path` as `format` at `size` inches (its own size if None) and
/// `dpi` (PNG). Errors name the file.
pub fn write(
    figure: &Figure,
    path: &Path,
    format: ImageFormat,
    size: Option<(f64, f64)>,
    dpi: u32,
) -> anyhow::Result<()> {
    let bytes = render(figure, format, size, dpi)?;
    let mut f = AtomicFile::create(path).map_err(anyhow::Error::msg)?;
    f.write_all(&bytes)
        .map_err(|e| anyhow::anyhow!("cannot write {}: {e}", path.display()))?;
    f.commit()
}

#[cfg(test)]
mod tests {
    use super::*;
    use bouncemap_figures::{diagram_view, phase_view, DiagramAxis, DEFAULT_DPI};

    #[test]
    fn the_terminal_views_export_as_svg_and_png() {
        use bouncemap_engine::jobs::grid::SweepParam;
        use bouncemap_engine::run::Outcome;
        use bouncemap_engine::run::Point as SweepPoint;
        use bouncemap_engine::sweep::{SweepSpec, ValueResult};
        use bouncemap_engine::EventKind;
        let spec = SweepSpec::new(
            bouncemap_engine::Table::fd(0.1).unwrap(),
            0.45,
            0.8,
            SweepParam::Alpha,
            0.45,
            0.6,
            3,
        );
        let values: Vec<ValueResult> = (0..3)
            .map(|i| ValueResult {
                index: i,
                value: spec.value(i),
                complete: true,
                points: vec![SweepPoint {
                    phase: 0.2,
                    v: 0.5,
                    kind: EventKind::Impact,
                }],
                outcome: Outcome::Unsettled,
                sticking: i == 2,
                events: 1,
                lyapunov: None,
                attractors: Vec::new(),
                precision: None,
                cycle: None,
            })
            .collect();
        let dir = std::env::temp_dir().join(format!("bouncemap-export-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let fig = diagram_view(
            &spec,
            &values,
            Some((0.5, 0.6)),
            DiagramAxis::Velocity,
            bouncemap_figures::diagram::Colouring::Class,
            "fd:0.1  r = 0.8  zoom 0.5..0.6",
        );
        assert_eq!(fig.panels[0].x.lo, 0.5);
        let (svg, png) = (dir.join("d.svg"), dir.join("d.png"));
        write(&fig, &svg, ImageFormat::Svg, None, DEFAULT_DPI).unwrap();
        write(&fig, &png, ImageFormat::Png, None, DEFAULT_DPI).unwrap();
        assert!(std::fs::read_to_string(&svg)
            .unwrap()
            .contains("zoom 0.5..0.6"));
        assert_eq!(&std::fs::read(&png).unwrap()[..4], b"\x89PNG");
        let phase = phase_view(&[(0.1, 0.4), (0.7, -0.2)], "orbit");
        write(
            &phase,
            &dir.join("p.svg"),
            ImageFormat::Svg,
            Some((4.0, 3.0)),
            100,
        )
        .unwrap();
        let text = std::fs::read_to_string(dir.join("p.svg")).unwrap();
        assert!(
            text.contains("width=\"288pt\" height=\"216pt\""),
            "4 × 3 inches"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
