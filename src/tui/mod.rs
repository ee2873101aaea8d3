//! The terminal application: `bouncemap` without a subcommand.
//!
//! * [`app`]: the shared state and the panels, the application's own overlays and
//!   prompts, and the routing of actions, changes and worker messages through the panel
//!   registry (pure, tested directly); [`components`]: the registry (the one list of
//!   panels, from which targets, messages, routing, focus and drawing come), what the
//!   panels share, and one file per panel, each owning its state, keys, background
//!   work and drawing; [`layout`]: the slots the panels take.
//! * [`params`]: the editable values (checked by the shared rules); [`keymap`]: keys →
//!   actions, and the help overlay generated from the same table; [`settings`]: the
//!   config file; [`line_edit`]: the typed line of the parameter editor and the export
//!   prompt.
//! * [`runtime`]: the event loop; [`input`]: keys, mouse and terminal signals, parsed
//!   here; [`workers`]: background work, latest-wins, on the engine's executor or
//!   threads of its own, its results typed; [`analysis`]: the orbit analysis the
//!   stability panel shows; [`skeleton`]: the continued branches of the α window;
//!   [`terminal`]: setup and restore on every way out, and around a stop.
//! * [`plot`]: drawing the shared hit-count grid; [`theme`]: styles; [`export`]: `e`
//!   and `E`.
//!
//! Invariants: the UI thread never waits on a computation (sweeps, the phase plot and
//! the orbit analysis run on other threads and report over a channel); a parameter
//! change bumps a generation that stops stale work; the screen is redrawn only when
//! something changed, never faster than the frame cap.

pub mod analysis;
pub mod app;
pub mod components;
pub mod export;
pub mod input;
pub mod keymap;
pub mod layout;
pub mod line_edit;
pub mod params;
pub mod plot;
pub mod runtime;
pub mod settings;
pub mod skeleton;
pub mod terminal;
pub mod theme;
pub mod workers;

use crate::config::display::ColorChoice;
use crate::config::rules;
use crate::config::table_spec::TableSpec;
use crate::config::InputError;
use crate::output::hitgrid::Marker;
use app::App;
use bouncemap_engine::jobs::Executor;
use params::{ParamId, Params};
use settings::Config;
use std::io::IsTerminal;
use std::path::PathBuf;
use theme::Theme;

/// Start-up options from the command line (None: config file, then built-in default).
#[derive(Clone, Debug, Default)]
pub struct Options {
    pub table: Option<TableSpec>,
    pub alpha: Option<f64>,
    pub r: Option<f64>,
    pub fps: Option<u32>,
    pub color: Option<ColorChoice>,
    pub marker: Option<Marker>,
    pub mouse: bool,
    pub config: Option<PathBuf>,
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
        // A table of another kind brings its own window, α placed in it (--alpha wins).
        let table = spec.load()?;
        p.change_table(spec.clone(), table);
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
    let fps = opts.fps.or(config.fps).unwrap_or(rules::FPS.default as u32);
    let mut app = App::new(p, config.keymap.clone(), Theme::new(mode), marker, fps);
    app.mouse = opts.mouse || config.mouse.unwrap_or(false);
    if let Some(s) = config.export_plane {
        app.export_sizes.plane = s;
    }
    if let Some(s) = config.export_basins {
        app.export_sizes.basins = s;
    }
    Ok(app)
}

/// Open the terminal application. Bad options or config: [`InputError`] (status 2).
pub fn run(opts: Options) -> anyhow::Result<()> {
    // Options and config first: bad ones are refused with or without a terminal.
    let config = match Config::locate(opts.config.as_deref()) {
        Some(path) => Config::load(&path).map_err(InputError)?,
        None => Config::default(),
    };
    let mut app = build_app(&opts, &config)?;
    if !(std::io::stdin().is_terminal() && std::io::stdout().is_terminal()) {
        return Err(InputError(
            "the terminal application needs a terminal on stdin and stdout; for scripts use the headless commands (bouncemap orbit --help, bouncemap --help)".into(),
        )
        .into());
    }
    let stop = terminal::signal_flag()?;
    terminal::spawn_watchdog(stop.clone());
    let workers = components::Workers::new(Executor::all_cores()?);
    let inputs = input::Inputs::start()?;
    let mut term = terminal::setup(app.mouse)?;
    let result = runtime::run(&mut term, &mut app, &workers, &inputs, &stop);
    terminal::restore();
    workers.cancel_all();
    if let Some(status) = terminal::signal_status(stop.load(std::sync::atomic::Ordering::SeqCst)) {
        // Stopped by a signal: say so in the exit status, as a shell expects.
        std::process::exit(status);
    }
    result
}
