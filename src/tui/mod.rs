//! The terminal application: `bouncemap` without a subcommand.
//!
//! * [`app`]: state and what each action does (pure, tested directly);
//!   [`params`]: the editable values and their ranges; [`keymap`]: keys → actions, and
//!   the help overlay generated from the same table; [`config`]: the TOML config file.
//! * [`views`]: one file per panel; [`plot`]: the braille hit-count grid; [`theme`]:
//!   colour modes.
//! * [`runtime`]: the event loop; [`workers`]: background jobs, latest-wins;
//!   [`terminal`]: setup and restore on every way out.
//!
//! Invariants: the UI thread never waits on a computation (sweeps, the phase plot and
//! the orbit analysis run on other threads and report over a channel); a parameter
//! change bumps a generation that stops stale work; the screen is redrawn only when
//! something changed, never faster than the frame cap.

pub mod analysis;
pub mod app;
pub mod config;
pub mod export;
pub mod keymap;
pub mod params;
pub mod plot;
pub mod runtime;
pub mod terminal;
pub mod theme;
pub mod views;
pub mod workers;

use crate::input::InputError;
use app::{App, Preset};
use config::Config;
use params::{ParamId, Params, TableKind};
use plot::Marker;
use std::io::IsTerminal;
use std::path::PathBuf;
use std::sync::Arc;
use theme::{ColorChoice, Theme};

/// Start-up options from the command line (None: config file, then built-in default).
#[derive(Clone, Debug, Default)]
pub struct Options {
    pub table: Option<String>,
    pub alpha: Option<f64>,
    pub r: Option<f64>,
    pub fps: Option<u32>,
    pub color: Option<ColorChoice>,
    pub marker: Option<Marker>,
    pub mouse: bool,
    pub config: Option<PathBuf>,
}

impl From<&crate::cli::TuiArgs> for Options {
    fn from(a: &crate::cli::TuiArgs) -> Options {
        Options {
            table: a.tui_table.clone(),
            alpha: a.tui_alpha,
            r: a.tui_r,
            fps: a.fps,
            color: a.color,
            marker: a.marker,
            mouse: a.mouse,
            config: a.config.clone(),
        }
    }
}

/// Build the application state from options and config (no terminal needed).
pub fn build_app(opts: &Options, config: &Config) -> Result<App, InputError> {
    let mut p = Params::default();
    config.apply_defaults(&mut p).map_err(|e| {
        let file = config
            .path
            .as_ref()
            .map_or(String::new(), |p| format!("config {}: ", p.display()));
        InputError(format!("{file}{e}"))
    })?;
    if let Some(spec) = &opts.table {
        let table = crate::input::load_table(spec)?;
        match (table.d(), spec.ends_with(".toml")) {
            (_, true) => {
                p.file = Some((spec.clone(), table.clone()));
                p.table = TableKind::File(spec.clone(), table);
            }
            (Some(d), false) => {
                p.table = TableKind::Fd;
                p.d = d;
            }
            (None, false) => p.table = TableKind::Sine,
        }
        if let Some(w) = default_window(spec) {
            p.lo = w.0;
            p.hi = w.1;
        }
    }
    if let Some(a) = opts.alpha {
        p.set_text(ParamId::Alpha, &a.to_string())
            .map_err(|e| InputError(format!("--alpha: {e}")))?;
    }
    if let Some(r) = opts.r {
        p.set_text(ParamId::R, &r.to_string())
            .map_err(|e| InputError(format!("--r: {e}")))?;
    }
    // The start must be valid for the table chosen.
    let sys = p.system();
    p.initial(&sys)
        .map_err(|e| InputError(format!("initial state: {e}")))?;
    let color = opts.color.or(config.color).unwrap_or_default();
    let mode = color.resolve(std::env::var("NO_COLOR").ok().as_deref());
    let marker = opts.marker.or(config.marker).unwrap_or_default();
    let fps = opts.fps.or(config.fps).unwrap_or(15);
    let mut app = App::new(p, config.keymap.clone(), Theme::new(mode), marker, fps);
    app.mouse = opts.mouse || config.mouse.unwrap_or(false);
    app.presets = paper_presets();
    Ok(app)
}

/// A sweep window that shows the interesting range of a built-in table.
fn default_window(spec: &str) -> Option<(f64, f64)> {
    match spec {
        "sine" => Some((0.005, 0.05)),
        _ => None,
    }
}

/// The paper's figures (r = 0.8, k = 1): Fig. 3's panels from the preset files shipped
/// in `assets/presets/` (the same ones `bouncemap sweep --preset` uses), then enlarged
/// windows around α_PD in the manner of Fig. 4.
pub fn paper_presets() -> Vec<Preset> {
    let mut presets: Vec<Preset> = crate::commands::sweep::PRESETS
        .iter()
        .filter_map(|(name, _)| {
            let p = crate::commands::sweep::preset(name).ok()?;
            (p.param == "alpha").then(|| Preset {
                name: name.to_string(),
                description: shorten(&p.description, 48),
                table: p.table,
                r: p.r.unwrap_or(0.8),
                k: 1,
                lo: p.window[0],
                hi: p.window[1],
            })
        })
        .collect();
    let p = |name: &str, description: &str, table: &str, lo, hi| Preset {
        name: name.into(),
        description: description.into(),
        table: table.into(),
        r: 0.8,
        k: 1,
        lo,
        hi,
    };
    presets.extend([
        p("fig4a", "D = 0.001 near α_PD", "fd:0.001", 0.46, 0.56),
        p("fig4b", "D = 0.01 near α_PD", "fd:0.01", 0.46, 0.56),
        p("fig4c", "D = 0.1 near α_PD", "fd:0.1", 0.44, 0.54),
    ]);
    presets
}

/// `text` cut to at most `max` characters, with an ellipsis where it was cut.
fn shorten(text: &str, max: usize) -> String {
    if text.chars().count() <= max {
        return text.to_string();
    }
    let cut: String = text.chars().take(max.saturating_sub(1)).collect();
    format!("{}…", cut.trim_end())
}

/// Open the terminal application. Bad options or config: [`InputError`] (status 2).
pub fn run(opts: Options, analysis: Arc<dyn workers::Analysis>) -> anyhow::Result<()> {
    if !(std::io::stdin().is_terminal() && std::io::stdout().is_terminal()) {
        return Err(InputError(
            "the terminal application needs a terminal on stdin and stdout; for scripts use the headless commands (bouncemap orbit --help, bouncemap --help)".into(),
        )
        .into());
    }
    let config = match Config::locate(opts.config.as_deref()) {
        Some(path) => Config::load(&path).map_err(InputError)?,
        None => Config::default(),
    };
    let mut app = build_app(&opts, &config)?;
    let stop = terminal::signal_flag()?;
    terminal::spawn_watchdog(stop.clone());
    let workers = workers::Workers::new(analysis);
    let mut term = terminal::setup(app.mouse)?;
    let result = runtime::run(&mut term, &mut app, &workers, &stop);
    terminal::restore();
    workers.cancel_all();
    if let Some(status) = terminal::signal_status(stop.load(std::sync::atomic::Ordering::SeqCst)) {
        // Stopped by a signal: say so in the exit status, as a shell expects.
        std::process::exit(status);
    }
    result
}
