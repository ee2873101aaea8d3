//! `bouncemap figure NAME`: the paper's figures, and any sweep, as SVG or PNG.
//!
//! Everything the user gave is checked before any computing (the name and the numbers
//! by clap, the sweep of `diagram`, the output's format and path). Then the figure's
//! data are computed on all cores (sweeps on the engine's executor, the scaling rows
//! of Fig. 4 and 5 on threads of their own) with a progress bar on a terminal, the
//! figure is drawn by [`bouncemap_figures`], and the file is written atomically. A
//! sweep's values are drawn into its [`Diagram`] as they complete and dropped: memory
//! is the picture's, whatever the number of values and kept events.

use super::drive::drive_job;
use super::progress::Progress;
use crate::config::flags::{FigureArgs, FigureName};
use crate::config::presets::preset;
use crate::config::{self, InputError};
use crate::output::sink::AtomicFile;
use bouncemap_engine::attractors::basins::BasinSpec;
use bouncemap_engine::attractors::global::GlobalSpec;
use bouncemap_engine::attractors::separation::{baseline, separation};
use bouncemap_engine::attractors::Registry;
use bouncemap_engine::jobs::grid::Shard;
use bouncemap_engine::jobs::{Control, Executor, Progress as JobProgress};
use bouncemap_engine::orbits::curves::curves;
use bouncemap_engine::orbits::manifold::{Kind, Manifold};
use bouncemap_engine::orbits::scaling::{log_spaced, scaling_row, ScalingRow};
use bouncemap_engine::plane::PlaneSpec;
use bouncemap_engine::sweep::{self, SweepSpec};
use bouncemap_figures::diagram::{self, Diagram, GRID_BINS, HELD_POINTS};
use bouncemap_figures::scaling::{self as scaling_fig, FIG5_D};
use bouncemap_figures::text::plain;
use bouncemap_figures::{self as figure, shapes, Figure, ImageFormat, Layer, DEFAULT_DPI};
use std::io::Write;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// `--quick`: values per diagram at most, and the transient, in table periods.
pub const QUICK_STEPS: usize = 200;
pub const QUICK_TRANSIENT: u64 = 20_000;
/// `--quick` for `basins`: the grid at most, and each start's transient.
pub const QUICK_GRID: (usize, usize) = (80, 40);
pub const QUICK_BASIN_TRANSIENT: u64 = 1000;
/// `--quick` for `attractors`: α values, the grid at each, the transient (at most).
pub const QUICK_ATTRACTORS: (usize, usize, u64) = (40, 30, 1000);
/// `--quick` for `plane`: the pixels at most (its transient as a diagram's).
pub const QUICK_PLANE: (usize, usize) = (100, 50);
/// r and k of the paper's Fig. 4 and 5.
const PAPER_R: f64 = 0.8;
const PAPER_K: u32 = 1;
/// The D values of Fig. 4.
const FIG4_D: [f64; 3] = [0.001, 0.01, 0.1];

pub fn run(args: &FigureArgs) -> anyhow::Result<()> {
    let name = args.name.as_str();
    let out = args.out.clone().unwrap_or_else(|| format!("{name}.png"));
    let path = Path::new(&out);
    let format = args
        .format
        .map(ImageFormat::from)
        .or_else(|| ImageFormat::from_path(path))
        .ok_or_else(|| {
            InputError(format!(
                "--out {}: the file name does not say the format: valid a name ending in .svg or .png, or --format svg|png",
                crate::output::text::quoted(&out)
            ))
        })?;
    let dpi = args.dpi.unwrap_or(DEFAULT_DPI);
    let diagram_spec = match &args.name {
        FigureName::Diagram(a) => Some(quick(
            config::sweep::sweep_spec_from(a, Shard::WHOLE)?,
            args.quick,
        )),
        FigureName::Lyapunov(a) => {
            let mut spec = quick(config::sweep::sweep_spec_from(a, Shard::WHOLE)?, args.quick);
            spec.lyapunov = true;
            Some(spec)
        }
        _ => None,
    };
    let plane_spec = match &args.name {
        FigureName::Plane(a) => {
            let mut spec = config::plane::plane_spec_from(&a.spec, a.pixels, Shard::WHOLE)?;
            if args.quick {
                spec.x.n = spec.x.n.min(QUICK_PLANE.0);
                spec.y.n = spec.y.n.min(QUICK_PLANE.1);
                spec.transient = spec.transient.min(QUICK_TRANSIENT);
                spec.validate().map_err(InputError::from)?;
            }
            Some(spec)
        }
        _ => None,
    };
    let basin_spec = match &args.name {
        FigureName::Basins(a) => {
            let most = figure::manifold::OVERLAY_SADDLES;
            if a.manifolds.len() > most {
                return Err(InputError(format!(
                    "--manifolds is given {} times; valid: up to {most} saddles drawn over the basins",
                    a.manifolds.len()
                ))
                .into());
            }
            if let Some((i, _)) = a
                .manifolds
                .iter()
                .enumerate()
                .find(|(i, c)| a.manifolds[..*i].contains(c))
            {
                return Err(InputError(format!(
                    "--manifolds: value {} names a saddle already named; valid: up to {most} different saddles",
                    i + 1
                ))
                .into());
            }
            let mut spec = config::basin_spec(&a.spec)?;
            if args.quick {
                spec.nx = spec.nx.min(QUICK_GRID.0);
                spec.ny = spec.ny.min(QUICK_GRID.1);
                spec.settle.transient = spec.settle.transient.min(QUICK_BASIN_TRANSIENT);
            }
            Some(spec)
        }
        _ => None,
    };
    if let Some(spec) = &diagram_spec {
        // Drawn as values complete: the points up to HELD_POINTS (and their copy in the
        // figure), then a grid of counts; a byte and an exponent per value.
        let points = (spec.steps as u64 * spec.keep as u64).min(HELD_POINTS as u64);
        config::check_memory(
            points * 32 + (GRID_BINS * GRID_BINS * 4) as u64 + spec.steps as u64 * 9,
            "this diagram",
        )?;
    }
    let attractors_spec = match &args.name {
        FigureName::Attractors(a) => {
            let mut spec = config::attractors_spec(&a.spec)?;
            if args.quick {
                let (steps, side, transient) = QUICK_ATTRACTORS;
                spec.steps = spec.steps.min(steps);
                spec.nx = spec.nx.min(side);
                spec.ny = spec.ny.min(side);
                spec.settle.transient = spec.settle.transient.min(transient);
            }
            Some(spec)
        }
        _ => None,
    };
    // The two-parameter curves: of `figure curves`, or over a plane (`--curves P`).
    let curves_task = match &args.name {
        FigureName::Curves(a) => Some(config::plane::curves_plane(a)?),
        FigureName::Plane(a) => match (a.curves, &plane_spec) {
            (Some(p), Some(spec)) => Some(config::plane::plane_curves(spec, 1, p, None)?),
            _ => None,
        },
        _ => None,
    };
    let threads = config::threads(args.threads)?;
    // The files are created now: a path that cannot be written is refused before any
    // computing, and nothing is put in place until the figure is complete.
    let mut file = AtomicFile::create(path).map_err(|e| InputError(format!("--out: {e}")))?;
    let data = match &args.data {
        Some(d) => {
            Some(AtomicFile::create(Path::new(d)).map_err(|e| InputError(format!("--data: {e}")))?)
        }
        None => None,
    };
    let executor = Executor::new(threads)?;
    let fig = build(
        &args.name,
        Specs {
            diagram: diagram_spec,
            basins: basin_spec,
            plane: plane_spec,
            curves: curves_task,
            attractors: attractors_spec,
        },
        args.quick,
        &executor,
        threads,
    )?;
    let bytes = figure::render(&fig, format, args.size, dpi)?;
    let shown = file.path().display().to_string();
    file.write_all(&bytes)
        .map_err(|e| anyhow::anyhow!("cannot write {shown}: {e}"))?;
    let mut files = vec![file];
    if let Some(mut d) = data {
        let shown = d.path().display().to_string();
        serde_json::to_writer(&mut d, &fig.data())
            .map_err(|e| anyhow::anyhow!("cannot write {shown}: {e}"))?;
        writeln!(d).map_err(|e| anyhow::anyhow!("cannot write {shown}: {e}"))?;
        files.push(d);
    }
    // The picture and its data together, or neither.
    AtomicFile::commit_all(files)
}

/// A sweep at the lower fidelity of `--quick`.
fn quick(mut spec: SweepSpec, quick: bool) -> SweepSpec {
    if quick {
        spec.steps = spec.steps.min(QUICK_STEPS);
        spec.transient = spec.transient.min(QUICK_TRANSIENT);
    }
    spec
}

/// A preset's sweep (at `--quick`'s fidelity if asked).
fn preset_spec(name: &str, q: bool) -> anyhow::Result<SweepSpec> {
    Ok(quick(preset(name)?.sweep_spec()?, q))
}

/// Run a whole sweep on `executor`, with a progress bar labelled `what`, drawing its
/// diagram as values complete (each value is dropped once drawn: memory for the picture
/// only, see [`Diagram`]).
fn run_sweep(spec: &SweepSpec, executor: &Executor, what: &str) -> anyhow::Result<Diagram> {
    let handle = sweep::start(spec.clone(), executor, &Control::new())?;
    let mut diagram = Diagram::new(spec);
    let mut done = 0usize;
    drive_job(handle, Progress::bar(what), |_, b| {
        if b.complete {
            diagram.add(&b.data);
            done += 1;
        }
        Ok(())
    })?;
    if done != spec.shard_values() {
        anyhow::bail!(
            "{what}: the sweep stopped after {done} of {} values",
            spec.shard_values()
        );
    }
    Ok(diagram)
}

/// The Fig. 4/5 rows for `ds` (r = 0.8, k = 1), computed on `threads` threads.
fn scaling_rows(ds: &[f64], threads: usize, what: &str) -> anyhow::Result<Vec<ScalingRow>> {
    let next = AtomicUsize::new(0);
    let done = AtomicUsize::new(0);
    let results: Mutex<Vec<Option<Result<ScalingRow, String>>>> = Mutex::new(vec![None; ds.len()]);
    let start = Instant::now();
    let mut progress = Progress::bar(what);
    std::thread::scope(|s| {
        for _ in 0..threads.min(ds.len()).max(1) {
            s.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                let Some(&d) = ds.get(i) else { break };
                let row = scaling_row(d, PAPER_R, PAPER_K).map_err(|e| e.to_string());
                results.lock().unwrap_or_else(|e| e.into_inner())[i] = Some(row);
                done.fetch_add(1, Ordering::Relaxed);
            });
        }
        while done.load(Ordering::Relaxed) < ds.len() {
            progress.update(&JobProgress {
                done: done.load(Ordering::Relaxed),
                total: ds.len(),
                events: 0,
                elapsed: start.elapsed(),
            });
            std::thread::sleep(Duration::from_millis(100));
        }
    });
    progress.finish(&JobProgress {
        done: ds.len(),
        total: ds.len(),
        events: 0,
        elapsed: start.elapsed(),
    });
    results
        .into_inner()
        .unwrap_or_else(|e| e.into_inner())
        .into_iter()
        .map(|r| match r {
            Some(Ok(row)) => Ok(row),
            Some(Err(e)) => Err(anyhow::anyhow!("{what}: {e}")),
            None => Err(anyhow::anyhow!("{what}: a row was not computed")),
        })
        .collect()
}

/// The D values of Fig. 5 (the same as `scaling --d 0.001..1:13`).
pub fn fig5_d() -> Vec<f64> {
    log_spaced(FIG5_D.0, FIG5_D.1, FIG5_D.2)
}

/// What `figure curves` and `figure plane --curves` follow: the plane and the seeds.
type CurvesTask = (
    bouncemap_engine::orbits::curves::Plane,
    bouncemap_engine::orbits::curves::Seeds,
);

/// What the figure named computes, checked before any file is created: at most one is
/// set (both the plane and its curves for `plane --curves`).
struct Specs {
    diagram: Option<SweepSpec>,
    basins: Option<BasinSpec>,
    plane: Option<PlaneSpec>,
    curves: Option<CurvesTask>,
    attractors: Option<GlobalSpec>,
}

/// The figure `name` from its checked `specs`.
fn build(
    name: &FigureName,
    specs: Specs,
    q: bool,
    executor: &Executor,
    threads: usize,
) -> anyhow::Result<Figure> {
    let Specs {
        diagram: diagram_spec,
        basins: basin_spec,
        plane: plane_spec,
        curves: curves_task,
        attractors: attractors_spec,
    } = specs;
    let panel_name = |n: &FigureName| n.as_str().to_string();
    match name {
        FigureName::Fig2 => Ok(shapes::fig2()?),
        FigureName::Fig3 => {
            let mut panels = Vec::new();
            for letter in ['a', 'b', 'c', 'd', 'e', 'f'] {
                let spec = preset_spec(&format!("fig3{letter}"), q)?;
                panels.push(run_sweep(&spec, executor, &format!("fig3 ({letter})"))?);
            }
            Ok(diagram::fig3(panels))
        }
        FigureName::Fig3a
        | FigureName::Fig3b
        | FigureName::Fig3c
        | FigureName::Fig3d
        | FigureName::Fig3e
        | FigureName::Fig3f => {
            let n = panel_name(name);
            let spec = preset_spec(&n, q)?;
            Ok(diagram::diagram_figure(&n, run_sweep(&spec, executor, &n)?))
        }
        FigureName::Fig4 => {
            let mut upper = Vec::new();
            let mut caption = Vec::new();
            for (letter, d) in ['a', 'b', 'c'].into_iter().zip(FIG4_D) {
                let spec = preset_spec(&format!("fig4{letter}"), q)?;
                let mut p = run_sweep(&spec, executor, &format!("fig4 ({letter})"))?.into_panel();
                p.title = Some(format!("$D$ = {d}"));
                upper.push(p);
                if caption.is_empty() {
                    caption.push(plain(&format!(
                        "(a)\u{2013}(c): bifurcation diagrams enlarged near the period-doubling point, r = {}: the last {} events before t = {} for each of {} values of \u{3b1}.",
                        spec.r,
                        spec.keep,
                        figure::fmt_count(spec.transient),
                        spec.steps
                    )));
                }
            }
            let shaded = upper
                .iter()
                .any(|p| p.layers.iter().any(|l| matches!(l, Layer::Bands { .. })));
            caption.push(if shaded {
                diagram::STICKING_NOTE.to_string()
            } else {
                "Dashed: $t\u{302}$ = 0 and 1, the domain of $t\u{302}$.".to_string()
            });
            let rows = scaling_rows(&FIG4_D, threads, "fig4 (d)-(f)")?;
            Ok(scaling_fig::fig4(upper, &rows, caption))
        }
        FigureName::Fig5 => {
            let rows = scaling_rows(&fig5_d(), threads, "fig5")?;
            Ok(scaling_fig::fig5(&rows, PAPER_R, PAPER_K)?)
        }
        FigureName::Lyapunov(_) => {
            let spec = diagram_spec.expect("the diagram's sweep was checked first");
            let diagram = run_sweep(&spec, executor, "lyapunov")?;
            Ok(figure::lyapunov::lyapunov_figure(diagram))
        }
        FigureName::Plane(_) => {
            let spec = plane_spec.expect("the plane was checked first");
            let plane = super::plane::compute(&spec, executor)?;
            let analytic = bouncemap_engine::plane::curves(&spec);
            let found = match &curves_task {
                Some((cplane, seeds)) => Some((
                    curves(cplane, *seeds).map_err(InputError::from)?,
                    seeds.max_period(),
                )),
                None => None,
            };
            Ok(figure::plane::plane_figure(
                &spec,
                plane.pixels(),
                analytic.as_ref(),
                found.as_ref().map(|(c, p)| figure::plane::Continued {
                    curves: c,
                    max_period: *p,
                }),
            ))
        }
        FigureName::Attractors(a) => {
            let spec = attractors_spec.expect("the continuation was checked first");
            let cont = super::attractors::compute(&spec, 0..spec.steps, executor)?;
            let mut fig = figure::global::attractors_figure(&cont);
            if a.crises {
                let located = super::attractors::locate_crises(&cont);
                figure::global::mark_crises(&mut fig, &located);
            }
            Ok(fig)
        }
        FigureName::Manifolds(a) => {
            let (sys, saddle, ms) = super::manifolds::compute(a)?;
            Ok(figure::manifold::manifold_figure(&sys, &saddle, &ms))
        }
        FigureName::Basins(a) => {
            let spec = basin_spec.expect("the basins' grid was checked first");
            // The saddles and their manifolds first: a refusal before the picture's work.
            let mut overlays = Vec::new();
            for choice in &a.manifolds {
                let saddle = super::manifolds::saddle(&spec.sys, choice.k, choice.guess)?;
                let ms = super::manifolds::grow(
                    &spec.sys,
                    &saddle,
                    &[Kind::Unstable, Kind::Stable],
                    a.manifold_length,
                )?;
                overlays.push((saddle, ms));
            }
            let basins = super::basins::compute(&spec, executor)?;
            let mut fig = figure::basins::basins_figure(&spec, &basins);
            for (which, (saddle, ms)) in overlays.iter().enumerate() {
                let split = split_report(&spec, ms);
                figure::manifold::overlay_on_basins(
                    &mut fig,
                    &spec.sys,
                    spec.w_max,
                    (which, saddle),
                    ms,
                    split.as_ref(),
                );
            }
            Ok(fig)
        }
        FigureName::Curves(_) => {
            let (plane, seeds) = curves_task.expect("the curves' plane was checked first");
            let found = curves(&plane, seeds).map_err(InputError::from)?;
            Ok(figure::curves::curves_figure(
                &plane,
                &found,
                seeds.max_period(),
            ))
        }
        FigureName::Diagram(_) => {
            let spec = diagram_spec.expect("the diagram's sweep was checked first");
            let diagram = run_sweep(&spec, executor, "diagram")?;
            Ok(diagram::diagram_figure("diagram", diagram))
        }
    }
}

/// Pairs of starts across the stable manifold in `ms`, half a grid cell's diagonal on
/// either side, against as many pairs spread over the picture (see
/// [`bouncemap_engine::attractors::separation`]).
fn split_report(spec: &BasinSpec, ms: &[Manifold]) -> Option<figure::manifold::SplitReport> {
    let stable = ms.iter().find(|m| m.kind == Kind::Stable)?;
    let offset = 0.5 * (1.0 / spec.nx as f64).hypot(spec.w_max / spec.ny as f64);
    let mut reg = Registry::new();
    let never = &mut |_| false;
    let across = separation(&spec.sys, stable, offset, &spec.settle, &mut reg, never)?;
    let pairs = across.pairs.max(100);
    let base = baseline(
        &spec.sys,
        spec.w_max,
        pairs,
        offset,
        &spec.settle,
        &mut reg,
        never,
    )?;
    Some(figure::manifold::SplitReport {
        across,
        baseline: base,
    })
}
