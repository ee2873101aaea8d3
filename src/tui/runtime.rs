//! The event loop (after oha's monitor): carry out queued effects, drain the worker
//! channel, draw if something changed and the frame cap allows, then wait for input
//! until the next frame is due. Nothing here waits on a computation, and with nothing
//! changing it blocks on the input channel and writes nothing. Ctrl-C always quits;
//! a stop (Ctrl-Z, SIGTSTP) restores the terminal first and takes it back on `fg`.

use super::app::{App, Effect};
use super::components::diagram::alpha_at;
use super::components::Workers;
use super::export::{export, export_view};
use super::input::{Input, Inputs};
use super::layout::Slot;
use super::terminal::{self, Term};
use crossterm::event::{
    KeyCode, KeyEvent, KeyEventKind, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// Slowest frame rate while only background results change (a sweep adding points):
/// a few frames per second keep the byte rate low over ssh.
const DATA_FRAME: Duration = Duration::from_millis(250);
/// After a key press, frames follow at the full `--fps` cap for this long.
const INTERACTIVE: Duration = Duration::from_secs(2);
/// Messages taken per loop turn at most, so input stays responsive.
const DRAIN_MAX: usize = 4096;

/// Run until quit or a signal; the caller restores the terminal.
pub fn run(
    term: &mut Term,
    app: &mut App,
    workers: &Workers,
    inputs: &Inputs,
    stop: &AtomicUsize,
) -> anyhow::Result<()> {
    let frame = Duration::from_secs_f64(1.0 / app.fps.max(1) as f64);
    let mut last_draw: Option<Instant> = None;
    let mut last_input = Instant::now();
    // Start of a mouse drag on the diagram (column).
    let mut drag_from: Option<u16> = None;
    loop {
        if stop.load(Ordering::Relaxed) != 0 {
            break;
        }
        // Size the plot grids before sweeps ask for the diagram's width.
        let size = term.size()?;
        app.set_size(ratatui::layout::Rect::new(0, 0, size.width, size.height));
        for e in app.take_effects() {
            apply(e, app, workers, term)?;
        }
        for m in workers.rx.try_iter().take(DRAIN_MAX) {
            app.receive(m);
        }
        if app.quit {
            break;
        }
        let now = Instant::now();
        let cap = if now.duration_since(last_input) < INTERACTIVE {
            frame
        } else {
            frame.max(DATA_FRAME)
        };
        let due = last_draw.map_or(now, |t| t + cap);
        if app.shared.dirty && now >= due {
            terminal::draw_synced(term, |f| app.draw(f))?;
            app.shared.dirty = false;
            last_draw = Some(now);
        }
        let timeout = if app.shared.dirty {
            due.saturating_duration_since(Instant::now())
                .max(Duration::from_millis(1))
        } else if app.busy() {
            Duration::from_millis(40)
        } else {
            Duration::from_millis(500)
        };
        // Take every pending input before drawing again.
        let mut next = inputs.next(timeout);
        while let Some(ev) = next {
            match ev {
                Input::Key(k) => {
                    last_input = Instant::now();
                    handle_key(app, k);
                }
                Input::Mouse(m) => {
                    last_input = Instant::now();
                    handle_mouse(app, m, &mut drag_from);
                }
                Input::Resize => app.shared.dirty = true,
                Input::Suspend => suspend(app, term)?,
                // Continued after a stop we did not take (SIGSTOP): redraw everything.
                Input::Continue => {
                    terminal::redraw_all(term)?;
                    app.shared.dirty = true;
                }
                Input::Hangup => {
                    // The terminal is gone: stop as for SIGHUP.
                    stop.store(signal_hook::consts::SIGHUP as usize, Ordering::SeqCst);
                }
            }
            if app.quit || stop.load(Ordering::Relaxed) != 0 {
                break;
            }
            next = inputs.try_next();
        }
    }
    workers.cancel_all();
    Ok(())
}

/// Stop (Ctrl-Z, SIGTSTP) with the terminal restored; take it back when continued.
fn suspend(app: &mut App, term: &mut Term) -> anyhow::Result<()> {
    terminal::suspend(term, app.mouse)?;
    app.shared.dirty = true;
    Ok(())
}

fn handle_key(app: &mut App, k: KeyEvent) {
    if k.kind == KeyEventKind::Release {
        return;
    }
    // Ctrl-C quits whatever the bindings say, typing or not.
    if k.code == KeyCode::Char('c') && k.modifiers.contains(KeyModifiers::CONTROL) {
        app.quit = true;
        return;
    }
    if app.editing() {
        app.edit_key(k);
    } else if let Some(a) = app.shared.keymap.action(&k) {
        app.handle(a);
    }
}

fn handle_mouse(app: &mut App, m: MouseEvent, drag_from: &mut Option<u16>) {
    let plot = app.panels.diagram.plot_area;
    let x = app.panels.diagram.grid.x_range();
    match m.kind {
        MouseEventKind::Down(MouseButton::Left) => {
            *drag_from = alpha_at(x, plot, m.column)
                .filter(|_| m.row >= plot.y && m.row < plot.y + plot.height)
                .map(|_| m.column);
        }
        MouseEventKind::Up(MouseButton::Left) => {
            if let Some(from) = drag_from.take() {
                let a = alpha_at(x, plot, from);
                let b = alpha_at(
                    x,
                    plot,
                    m.column
                        .clamp(plot.x, plot.x + plot.width.saturating_sub(1)),
                );
                if let (Some(a), Some(b)) = (a, b) {
                    if from == m.column {
                        app.panels.diagram.cursor = a;
                        app.shared.focus = Slot::Diagram;
                        app.set_value_to_cursor();
                    } else {
                        app.zoom_to(a.min(b), a.max(b));
                    }
                }
            }
        }
        _ => {}
    }
    app.shared.dirty = true;
}

fn apply(e: Effect, app: &mut App, workers: &Workers, term: &mut Term) -> anyhow::Result<()> {
    match e {
        Effect::Start(t) => app.start(t, workers),
        // Parked workers (sweep, phase plot) keep their progress; work started while
        // paused parks at once.
        Effect::Pause(p) => workers.pause(p),
        Effect::Export => {
            let name = app.export_pending.take().unwrap_or_default();
            let stem = std::path::Path::new(name.trim());
            let msg = if app.export_view {
                let sizes = app.export_sizes;
                export_view(&mut app.shared, &mut app.panels, sizes, stem)
            } else {
                export(&app.shared, &app.panels, stem)
                    .map(|(c, t)| format!("export: wrote {} and {}", c.display(), t.display()))
            };
            match msg {
                Ok(m) => app.shared.say(m, false),
                Err(e) => app.shared.say(e, true),
            }
        }
        Effect::Suspend => suspend(app, term)?,
    }
    Ok(())
}
