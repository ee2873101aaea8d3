//! The terminal: raw mode and the alternate screen on entry, and their undoing on every
//! way out — normal quit, panic (a hook restores before the message is printed), and
//! every signal whose default action ends the process ([`signal_flag`], the one place
//! signals that end the application are handled): SIGTERM, SIGHUP and SIGINT set a
//! flag the event loop checks several times a second (the process then exits with
//! status 128 + the signal's number, as a shell expects); every other one (SIGQUIT,
//! SIGABRT, SIGUSR1, SIGUSR2, SIGALRM, the real-time signals, ...) restores the
//! terminal inside its handler with async-signal-safe calls only (a write of the
//! restoring sequences and `tcsetattr` with the mode saved on entry) and then takes the
//! signal's default action. The program's own faults (SIGSEGV, SIGBUS, SIGILL, SIGFPE,
//! SIGTRAP) keep their default handling, and SIGKILL cannot be caught. Around a stop
//! (Ctrl-Z, SIGTSTP) the terminal is restored while stopped and taken back on `fg`.
//! Frames are wrapped in synchronized updates so slow links never show half a frame.

use crossterm::event::{DisableMouseCapture, EnableMouseCapture};
use crossterm::terminal::{
    self, BeginSynchronizedUpdate, EndSynchronizedUpdate, EnterAlternateScreen,
    LeaveAlternateScreen,
};
use crossterm::{cursor, execute, queue};
use ratatui::backend::CrosstermBackend;
use ratatui::Terminal;
use std::io::{self, BufWriter, Stdout, Write};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Once, OnceLock};

pub type Term = Terminal<CrosstermBackend<BufWriter<Stdout>>>;

/// Whether the terminal is currently in our raw/alternate state (restore is idempotent).
static ACTIVE: AtomicBool = AtomicBool::new(false);
static MOUSE: AtomicBool = AtomicBool::new(false);
static HOOK: Once = Once::new();
/// The terminal's mode before raw mode was entered (standard input's, which is the
/// terminal), for restoring it from a signal handler.
static ORIGINAL: OnceLock<libc::termios> = OnceLock::new();

/// What [`restore`] writes, as bytes a signal handler can write at once: the mouse
/// released (crossterm's `DisableMouseCapture`), then the rest.
const RELEASE_MOUSE: &[u8] = b"\x1b[?1006l\x1b[?1015l\x1b[?1003l\x1b[?1002l\x1b[?1000l";
/// The end of a synchronized update, the main screen and the cursor shown.
const LEAVE: &[u8] = b"\x1b[?2026l\x1b[?1049l\x1b[?25h";

/// Enter raw mode and the alternate screen; capture the mouse only if asked.
pub fn setup(mouse: bool) -> io::Result<Term> {
    install_panic_hook();
    enter(mouse)?;
    let backend = CrosstermBackend::new(BufWriter::with_capacity(1 << 16, io::stdout()));
    Terminal::new(backend)
}

fn enter(mouse: bool) -> io::Result<()> {
    if ORIGINAL.get().is_none() {
        // SAFETY: tcgetattr fills a termios of our own.
        unsafe {
            let mut t: libc::termios = std::mem::zeroed();
            if libc::tcgetattr(libc::STDIN_FILENO, &mut t) == 0 {
                let _ = ORIGINAL.set(t);
            }
        }
    }
    terminal::enable_raw_mode()?;
    ACTIVE.store(true, Ordering::SeqCst);
    MOUSE.store(mouse, Ordering::SeqCst);
    let mut out = io::stdout();
    // Clear ourselves: ratatui's clear() asks the terminal for the cursor position,
    // a round trip over ssh that some terminals never answer.
    execute!(
        out,
        EnterAlternateScreen,
        cursor::Hide,
        terminal::Clear(terminal::ClearType::All)
    )?;
    if mouse {
        execute!(out, EnableMouseCapture)?;
    }
    Ok(())
}

/// Stop the process as the shell's job control expects, with the terminal restored
/// (cooked mode, the main screen, the cursor shown); on `fg` take it back and redraw.
pub fn suspend(term: &mut Term, mouse: bool) -> io::Result<()> {
    restore();
    // Stops here (the default action of SIGTSTP) until continued.
    let _ = signal_hook::low_level::emulate_default_handler(signal_hook::consts::SIGTSTP);
    enter(mouse)?;
    redraw_all(term)
}

/// Clear the screen and forget what is on it, so the next frame is drawn whole.
/// (`Terminal::clear` would ask the terminal for the cursor position, an answer only
/// crossterm's own input reader can read; input here is read by [`super::input`].)
pub fn redraw_all(term: &mut Term) -> io::Result<()> {
    let size = term.size()?;
    term.resize(ratatui::layout::Rect::new(0, 0, size.width, size.height))
}

/// Leave the alternate screen and raw mode. Safe to call more than once, and from the
/// panic hook; errors are ignored (the link may be gone after SIGHUP).
pub fn restore() {
    if !ACTIVE.swap(false, Ordering::SeqCst) {
        return;
    }
    let mut out = io::stdout();
    if MOUSE.load(Ordering::SeqCst) {
        let _ = execute!(out, DisableMouseCapture);
    }
    let _ = execute!(
        out,
        EndSynchronizedUpdate,
        LeaveAlternateScreen,
        cursor::Show
    );
    let _ = terminal::disable_raw_mode();
    let _ = out.flush();
}

fn install_panic_hook() {
    HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            restore();
            previous(info);
        }));
    });
}

/// Draw one frame inside a synchronized update.
pub fn draw_synced(term: &mut Term, f: impl FnOnce(&mut ratatui::Frame)) -> io::Result<()> {
    queue!(term.backend_mut(), BeginSynchronizedUpdate)?;
    term.draw(f)?;
    execute!(term.backend_mut(), EndSynchronizedUpdate)?;
    Ok(())
}

/// The one handler of the signals that end the application. Returns the stop signal
/// received, if any: 0 until SIGTERM, SIGHUP or SIGINT arrives, then that signal's
/// number (the event loop answers it). Every other signal whose default action ends the
/// process ([`crate::output::signals::ending`]) restores the terminal in its handler and
/// then takes that action.
pub fn signal_flag() -> io::Result<Arc<AtomicUsize>> {
    let flag = Arc::new(AtomicUsize::new(0));
    for sig in [
        signal_hook::consts::SIGTERM,
        signal_hook::consts::SIGHUP,
        signal_hook::consts::SIGINT,
    ] {
        signal_hook::flag::register_usize(sig, flag.clone(), sig as usize)?;
    }
    for sig in crate::output::signals::ending() {
        // SAFETY: the action calls only async-signal-safe functions (atomics, write,
        // tcsetattr, sigaction, pthread_sigmask, raise). A signal that cannot be caught
        // here (one a tool the program runs under keeps for itself) is left as it is.
        let _ = unsafe {
            signal_hook::low_level::register(sig, move || {
                restore_in_handler();
                crate::output::signals::die_by(sig);
            })
        };
    }
    Ok(flag)
}

/// [`restore`] as a signal handler may do it: one write of the restoring sequences and
/// the terminal mode saved on entry, nothing that allocates or locks.
fn restore_in_handler() {
    if !ACTIVE.swap(false, Ordering::SeqCst) {
        return;
    }
    // SAFETY: write and tcsetattr are async-signal-safe; the buffers are static.
    unsafe {
        if MOUSE.load(Ordering::SeqCst) {
            libc::write(
                libc::STDOUT_FILENO,
                RELEASE_MOUSE.as_ptr().cast(),
                RELEASE_MOUSE.len(),
            );
        }
        libc::write(libc::STDOUT_FILENO, LEAVE.as_ptr().cast(), LEAVE.len());
        if let Some(t) = ORIGINAL.get() {
            libc::tcsetattr(libc::STDIN_FILENO, libc::TCSANOW, t);
        }
    }
}

/// The exit status after stop signal `sig` (0: none): 128 + its number.
pub fn signal_status(sig: usize) -> Option<i32> {
    (sig != 0).then(|| 128 + sig as i32)
}

/// Whether stdin and stdout are still terminals; after a hang-up they are not.
fn terminal_alive() -> bool {
    use std::io::IsTerminal;
    io::stdin().is_terminal() && io::stdout().is_terminal()
}

/// How often the watchdog looks, and how long a stop signal may go unanswered.
const WATCH_EVERY: std::time::Duration = std::time::Duration::from_millis(250);
const STOP_GRACE: std::time::Duration = std::time::Duration::from_secs(1);

/// Guard against a terminal that disappears without a signal (an SSH link dropped, a
/// terminal emulator killed) and against a stop signal (SIGTERM, SIGHUP, SIGINT) left
/// unanswered: this thread ends the process when the terminal is gone, or when the
/// signal has not been answered within a second, restoring the terminal first where
/// there still is one. (End of input also reaches the event loop as a hang-up.)
pub fn spawn_watchdog(stop: Arc<AtomicUsize>) {
    let _ = std::thread::Builder::new()
        .name("terminal-watchdog".into())
        .spawn(move || {
            let mut stop_seen: Option<std::time::Instant> = None;
            loop {
                std::thread::sleep(WATCH_EVERY);
                if !terminal_alive() {
                    // A hang-up, whether or not SIGHUP was delivered.
                    std::process::exit(128 + signal_hook::consts::SIGHUP);
                }
                let sig = stop.load(Ordering::Relaxed);
                if let Some(status) = signal_status(sig) {
                    let since = *stop_seen.get_or_insert_with(std::time::Instant::now);
                    if since.elapsed() >= STOP_GRACE {
                        restore();
                        std::process::exit(status);
                    }
                }
            }
        });
}
