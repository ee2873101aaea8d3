//! The event loop (after oha's monitor): carry out queued effects, drain the worker
//! channel, draw if something changed and the frame cap allows, then wait for input
//! until the next frame is due. Nothing here waits on a computation, and with nothing
//! changing it blocks in `poll` and writes nothing.

use super::app::{App, Effect, SweepStatus};
use super::export::export;
use super::terminal::{self, Term};
use super::views;
use super::workers::Workers;
use crossterm::event::{self, Event, KeyEventKind, MouseButton, MouseEventKind};
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
    stop: &AtomicUsize,
) -> anyhow::Result<()> {
    let frame = Duration::from_secs_f64(1.0 / app.fps.max(1) as f64);
    let mut last_draw: Option<Instant> = None;
    let mut last_input = Instant::now();
    let mut resume_sweep = false;
    loop {
        // A hang-up without a signal is the watchdog's (terminal::spawn_watchdog): the
        // event reader never returns then, so a check here would not run.
        if stop.load(Ordering::Relaxed) != 0 {
            break;
        }
        // Size the plot grids before sweeps ask for the diagram's width.
        let size = term.size()?;
        if let Some(p) = views::layout(ratatui::layout::Rect::new(0, 0, size.width, size.height)) {
            let (d, ph) = views::plot_areas(&p);
            app.set_plot_sizes(d, ph);
        }
        for e in app.take_effects() {
            apply(e, app, workers, &mut resume_sweep);
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
        if app.dirty && now >= due {
            terminal::draw_synced(term, |f| views::draw(f, app))?;
            app.dirty = false;
            last_draw = Some(now);
        }
        let timeout = if app.dirty {
            due.saturating_duration_since(Instant::now())
                .max(Duration::from_millis(1))
        } else if app.busy() {
            Duration::from_millis(40)
        } else {
            Duration::from_millis(500)
        };
        if event::poll(timeout)? {
            // Take every pending event before drawing again.
            loop {
                let ev = event::read()?;
                last_input = Instant::now();
                handle_event(app, ev);
                if app.quit || !event::poll(Duration::ZERO)? {
                    break;
                }
            }
        }
    }
    workers.cancel_all();
    Ok(())
}

fn handle_event(app: &mut App, ev: Event) {
    match ev {
        Event::Key(k) if k.kind != KeyEventKind::Release => {
            let action = app.keymap.action(&k);
            if app.editing.is_some() {
                if action == Some(super::keymap::Action::Quit)
                    && k.modifiers
                        .contains(crossterm::event::KeyModifiers::CONTROL)
                {
                    app.quit = true;
                } else {
                    app.edit_key(k.code);
                }
            } else if let Some(a) = action {
                app.handle(a);
            }
        }
        Event::Resize(..) => app.dirty = true,
        Event::Mouse(m) => {
            let plot = app.diagram.plot_area;
            let x = app.diagram.grid.x_range();
            match m.kind {
                MouseEventKind::Down(MouseButton::Left) => {
                    app.drag_from = views::diagram::alpha_at(x, plot, m.column)
                        .filter(|_| m.row >= plot.y && m.row < plot.y + plot.height)
                        .map(|_| m.column);
                }
                MouseEventKind::Up(MouseButton::Left) => {
                    if let Some(from) = app.drag_from.take() {
                        let a = views::diagram::alpha_at(x, plot, from);
                        let b = views::diagram::alpha_at(
                            x,
                            plot,
                            m.column
                                .clamp(plot.x, plot.x + plot.width.saturating_sub(1)),
                        );
                        if let (Some(a), Some(b)) = (a, b) {
                            if from == m.column {
                                app.diagram.cursor = a;
                                app.focus = super::app::Focus::Diagram;
                                app.handle(super::keymap::Action::Enter);
                            } else {
                                app.zoom_to(a.min(b), a.max(b));
                            }
                        }
                    }
                }
                _ => {}
            }
            app.dirty = true;
        }
        _ => {}
    }
}

fn apply(e: Effect, app: &mut App, workers: &Workers, resume_sweep: &mut bool) {
    match e {
        Effect::RestartSweep => {
            if app.paused {
                workers.cancel_sweep();
                app.sweep_started(0, 0, Ok(()));
                app.diagram.status = SweepStatus::Idle;
                *resume_sweep = true;
            } else {
                let spec = app.sweep_spec();
                let steps = spec.steps;
                let (gen, r) = workers.start_sweep(spec);
                app.sweep_started(gen, steps, r);
            }
        }
        Effect::RestartPhase => {
            let sys = app.system();
            if let Ok(st) = app.params.initial(&sys) {
                let gen = workers.start_phase(sys, st);
                app.phase_started(gen);
            }
        }
        Effect::RestartOrbits => {
            let gen =
                workers.start_orbits(app.system(), app.params.k, (app.params.lo, app.params.hi));
            app.orbits_started(gen);
        }
        Effect::Pause(true) => {
            // The phase-plot worker and the sweep's workers park where they are.
            workers.gate.set(true);
            workers.sweep_pause.set(true);
        }
        Effect::Pause(false) => {
            workers.gate.set(false);
            workers.sweep_pause.set(false);
            // A sweep cancelled by new parameters during the pause starts now.
            if std::mem::take(resume_sweep) {
                apply(Effect::RestartSweep, app, workers, resume_sweep);
            }
        }
        Effect::Export => {
            let dir = std::env::current_dir().unwrap_or_else(|_| ".".into());
            app.message = Some(match export(app, &dir) {
                Ok((c, t)) => (
                    format!("exported {} and {}", c.display(), t.display()),
                    false,
                ),
                Err(e) => (e, true),
            });
        }
    }
}
