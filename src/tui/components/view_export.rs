//! `E` with the plane view or the basins shown: their figures at the export's own
//! resolution (the config file's `[export]` sizes, by default those of `bouncemap plane`
//! and `bouncemap basins`), not the screen's. The picture is computed again at that size
//! in the background, as the panel's own is, with what the screen shows over it (the
//! plane's two-parameter curves while `C` has them on), and its SVG and PNG are written
//! together when it is complete; the status line says how far it is and, at the end,
//! every file written. A new export of the same view replaces one still computing.
//!
//! One generic panel without a slot, [`PictureExport`], registered once per picture
//! ([`Exported`]: what the figure is drawn from and what its files are called).

use super::grid_picture::{ChunkOf, GridPicture};
use super::{Address, Component, JobMsg, Shared, Workers};
use crate::output::sink::AtomicFile;
use bouncemap_engine::attractors::basins::{BasinSpec, Basins};
use bouncemap_engine::jobs::picture::Filled;
use bouncemap_engine::orbits::curves::Curves as TwoParameterCurves;
use bouncemap_engine::plane::{Plane, PlaneSpec};
use bouncemap_figures::{render, Figure, ImageFormat, DEFAULT_DPI};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use std::io::Write;
use std::path::{Path, PathBuf};

/// A picture the view export draws: its name in file names and messages, what is drawn
/// over it, and its figure.
pub trait Exported: Filled {
    /// `plane` or `basins`: the files are `NAME-plane.svg/.png`.
    const WHAT: &'static str;
    /// What is drawn over the picture besides what it holds.
    type Over;

    /// The figure of the complete picture.
    fn figure(spec: &Self::Spec, picture: &Self, over: &Self::Over) -> Figure;

    /// The picture's size in its own units ("400×200 pixels").
    fn size_text(spec: &Self::Spec) -> String;
}

impl Exported for Plane {
    const WHAT: &'static str = "plane";
    /// The two-parameter curves shown by `C`, and the period they were followed to.
    type Over = Option<(TwoParameterCurves, usize)>;

    fn figure(spec: &PlaneSpec, picture: &Plane, over: &Self::Over) -> Figure {
        let analytic = bouncemap_engine::plane::curves(spec);
        bouncemap_figures::plane::plane_figure(
            spec,
            picture.pixels(),
            analytic.as_ref(),
            over.as_ref()
                .map(|(c, p)| bouncemap_figures::plane::Continued {
                    curves: c,
                    max_period: *p,
                }),
        )
    }

    fn size_text(spec: &PlaneSpec) -> String {
        format!("{}×{} pixels", spec.x.n, spec.y.n)
    }
}

impl Exported for Basins {
    const WHAT: &'static str = "basins";
    type Over = ();

    fn figure(spec: &BasinSpec, picture: &Basins, _: &()) -> Figure {
        bouncemap_figures::basins::basins_figure(spec, picture)
    }

    fn size_text(spec: &BasinSpec) -> String {
        format!("{}×{} starts", spec.nx, spec.ny)
    }
}

/// An export asked for: where, of what, with what over it.
pub struct Request<P: Exported> {
    /// The export's name: the files are `STEM-WHAT.svg` and `.png`.
    pub stem: PathBuf,
    pub spec: P::Spec,
    pub over: P::Over,
}

/// The view export of one kind of picture.
pub struct PictureExport<P: Exported> {
    /// The picture being computed (shown: an export is running).
    pub job: GridPicture<P>,
    /// The export it is for.
    pub request: Option<Request<P>>,
    /// Where its work reports.
    at: Address<JobMsg<ChunkOf<P>>>,
}

impl<P: Exported> PictureExport<P> {
    pub fn new(at: Address<JobMsg<ChunkOf<P>>>) -> Self {
        PictureExport {
            job: GridPicture::default(),
            request: None,
            at,
        }
    }

    /// The two files of an export named `stem`.
    pub fn paths(stem: &Path) -> [PathBuf; 2] {
        ["svg", "png"].map(|ext| {
            let mut s = stem.as_os_str().to_owned();
            s.push(format!("-{}.{ext}", P::WHAT));
            PathBuf::from(s)
        })
    }

    /// Ask for the export `request` (started by the runtime: `Effect::Start` of this
    /// panel's target).
    pub fn ask(&mut self, request: Request<P>) {
        self.request = Some(request);
        self.job.shown = true;
        self.job.done = false;
    }

    /// Draw and write the finished picture; the message names the files.
    fn write(&mut self, shared: &mut Shared) {
        let (Some(req), Some(spec), Some(pic)) =
            (self.request.take(), &self.job.spec, &self.job.picture)
        else {
            return;
        };
        self.job.shown = false;
        let fig = P::figure(spec, pic, &req.over);
        let paths = Self::paths(&req.stem);
        let written = (|| -> Result<(), String> {
            let mut files = Vec::new();
            for (path, format) in paths.iter().zip([ImageFormat::Svg, ImageFormat::Png]) {
                let bytes = render(&fig, format, None, DEFAULT_DPI).map_err(|e| e.to_string())?;
                let mut f = AtomicFile::create(path)?;
                f.write_all(&bytes)
                    .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
                files.push(f);
            }
            AtomicFile::commit_all(files).map_err(|e| e.to_string())
        })();
        match written {
            Ok(()) => shared.say(
                format!(
                    "export: wrote {} and {} ({})",
                    paths[0].display(),
                    paths[1].display(),
                    P::size_text(spec)
                ),
                false,
            ),
            Err(e) => shared.say(format!("export {}: {e}", P::WHAT), true),
        }
    }
}

impl<P: Exported> Component for PictureExport<P> {
    type Msg = JobMsg<ChunkOf<P>>;

    fn start(&mut self, shared: &mut Shared, workers: &Workers) {
        let Some(req) = &self.request else {
            workers.cancel(self.at.to);
            return;
        };
        let spec = req.spec.clone();
        if !self.job.run(spec, self.at, workers) {
            let why = self.job.error.clone().unwrap_or_default();
            self.request = None;
            self.job.shown = false;
            shared.say(format!("export {}: {why}", P::WHAT), true);
        }
    }

    fn receive(&mut self, gen: u64, msg: Self::Msg, shared: &mut Shared) {
        self.job.receive(gen, msg, shared);
        if self.job.done && self.job.picture.as_ref().is_some_and(P::complete) {
            self.write(shared);
        }
    }

    fn busy(&self) -> bool {
        self.request.is_some() && !self.job.done
    }

    fn computing(&self, _shared: &Shared) -> Option<String> {
        let (Some(_), Some(pic)) = (&self.request, &self.job.picture) else {
            return None;
        };
        let (nx, ny) = pic.size();
        let frac = pic.covered() as f64 / (nx * ny).max(1) as f64;
        Some(format!("export {} {:.0}%", P::WHAT, (100.0 * frac).floor()))
    }

    fn draw(&self, _shared: &Shared, _area: Rect, _buf: &mut Buffer) {}
}
