//! The README's picture of the terminal application: the application itself, run
//! without a terminal on its real background jobs for a scripted sequence of keys,
//! waiting after each key until every job has finished, then drawn into an in-memory
//! screen and rendered as PNG with the figures' fonts. Times are left out of the
//! titles, so the picture is the same on every run and a test can compare it byte for
//! byte with the checked-in copy.

use crate::config::display::ColorChoice;
use crate::tui::components::{Effect, Workers};
use crate::tui::keymap::Action;
use crate::tui::settings::Config;
use crate::tui::{build_app, Options};
use anyhow::{bail, Context};
use bouncemap_engine::jobs::Executor;
use bouncemap_figures::terminal::{Cell, Screen};
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier};
use ratatui::Terminal;
use std::time::{Duration, Instant};

/// Where the picture lives under `docs/`.
pub const PATH: &str = "screenshot.png";

/// Longest the jobs after one key may take.
const PATIENCE: Duration = Duration::from_secs(300);

/// A scripted run: the screen's size and the keys pressed, in order.
pub struct Script {
    pub width: u16,
    pub height: u16,
    pub keys: Vec<Action>,
}

impl Script {
    /// The README's picture: the default window at 120 × 40, three bounces stepped,
    /// the diagram focused with its cursor moved into the period-2 range.
    pub fn readme() -> Script {
        let mut keys = vec![Action::StepOne, Action::StepOne, Action::StepOne];
        keys.push(Action::NextPanel);
        keys.extend(std::iter::repeat_n(Action::Right, 8));
        Script {
            width: 120,
            height: 40,
            keys,
        }
    }
}

/// Run the application through `script` and return its screen.
pub fn run(script: &Script) -> anyhow::Result<Buffer> {
    let opts = Options {
        color: Some(ColorChoice::Ansi256),
        ..Options::default()
    };
    let mut app = build_app(&opts, &Config::default())?;
    app.shared.show_times = false;
    let workers = Workers::new(Executor::all_cores()?);
    let area = Rect::new(0, 0, script.width, script.height);
    settle(&mut app, &workers, area)?;
    for key in &script.keys {
        app.handle(*key);
        settle(&mut app, &workers, area)?;
    }
    let mut term = Terminal::new(TestBackend::new(script.width, script.height))?;
    app.set_size(area);
    term.draw(|f| app.draw(f))?;
    workers.cancel_all();
    Ok(term.backend().buffer().clone())
}

/// Start what the last key asked for and take every result until nothing runs.
fn settle(app: &mut crate::tui::app::App, workers: &Workers, area: Rect) -> anyhow::Result<()> {
    let start = Instant::now();
    loop {
        app.set_size(area);
        let effects = app.take_effects();
        let started = !effects.is_empty();
        for e in effects {
            if let Effect::Start(t) = e {
                app.start(t, workers);
            }
        }
        while let Ok(m) = workers.rx.try_recv() {
            app.receive(m);
        }
        if !started && !app.busy() {
            return Ok(());
        }
        if start.elapsed() > PATIENCE {
            bail!(
                "the application's jobs did not finish in {} s",
                PATIENCE.as_secs()
            );
        }
        if let Ok(m) = workers.rx.recv_timeout(Duration::from_millis(20)) {
            app.receive(m);
        }
    }
}

/// The xterm colour of palette index `i`.
fn xterm(i: u8) -> (u8, u8, u8) {
    const SYSTEM: [(u8, u8, u8); 16] = [
        (0, 0, 0),
        (205, 49, 49),
        (13, 188, 121),
        (229, 229, 16),
        (36, 114, 200),
        (188, 63, 188),
        (17, 168, 205),
        (229, 229, 229),
        (102, 102, 102),
        (241, 76, 76),
        (35, 209, 139),
        (245, 245, 67),
        (59, 142, 234),
        (214, 112, 214),
        (41, 184, 219),
        (255, 255, 255),
    ];
    const LEVELS: [u8; 6] = [0, 95, 135, 175, 215, 255];
    match i {
        0..=15 => SYSTEM[i as usize],
        16..=231 => {
            let c = i - 16;
            (
                LEVELS[(c / 36) as usize],
                LEVELS[(c / 6 % 6) as usize],
                LEVELS[(c % 6) as usize],
            )
        }
        _ => {
            let g = 8 + 10 * (i - 232);
            (g, g, g)
        }
    }
}

/// A ratatui colour as RGB, `default` for the terminal's own.
fn rgb(c: Color, default: (u8, u8, u8)) -> (u8, u8, u8) {
    match c {
        Color::Reset => default,
        Color::Black => xterm(0),
        Color::Red => xterm(1),
        Color::Green => xterm(2),
        Color::Yellow => xterm(3),
        Color::Blue => xterm(4),
        Color::Magenta => xterm(5),
        Color::Cyan => xterm(6),
        Color::Gray => xterm(7),
        Color::DarkGray => xterm(8),
        Color::LightRed => xterm(9),
        Color::LightGreen => xterm(10),
        Color::LightYellow => xterm(11),
        Color::LightBlue => xterm(12),
        Color::LightMagenta => xterm(13),
        Color::LightCyan => xterm(14),
        Color::White => xterm(15),
        Color::Indexed(i) => xterm(i),
        Color::Rgb(r, g, b) => (r, g, b),
    }
}

/// The terminal's own colours in the picture (a dark theme).
const FOREGROUND: (u8, u8, u8) = (220, 220, 220);
const BACKGROUND: (u8, u8, u8) = (24, 26, 30);

/// A drawn buffer as the figures' screen.
pub fn screen(buf: &Buffer) -> Screen {
    let mut cells = Vec::with_capacity(buf.content.len());
    for y in 0..buf.area.height {
        for x in 0..buf.area.width {
            let c = &buf[(x, y)];
            let mut fg = rgb(c.fg, FOREGROUND);
            let mut bg = rgb(c.bg, BACKGROUND);
            if c.modifier.contains(Modifier::REVERSED) {
                std::mem::swap(&mut fg, &mut bg);
            }
            if c.modifier.contains(Modifier::DIM) {
                let mix = |a: u8, b: u8| ((u16::from(a) + u16::from(b)) / 2) as u8;
                fg = (mix(fg.0, bg.0), mix(fg.1, bg.1), mix(fg.2, bg.2));
            }
            cells.push(Cell {
                symbol: c.symbol().to_string(),
                fg,
                bg,
                bold: c.modifier.contains(Modifier::BOLD),
                italic: c.modifier.contains(Modifier::ITALIC),
                underline: c.modifier.contains(Modifier::UNDERLINED),
            });
        }
    }
    Screen {
        width: buf.area.width as usize,
        height: buf.area.height as usize,
        cells,
    }
}

/// The scripted run as PNG bytes.
pub fn png(script: &Script) -> anyhow::Result<Vec<u8>> {
    let buf = run(script)?;
    bouncemap_figures::terminal::png(&screen(&buf), 1.5).context("the screenshot")
}
