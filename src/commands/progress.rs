//! Progress of a long headless computation on stderr: a bar redrawn in place when
//! stderr is a terminal (and cleared however the run ends); otherwise (a batch log) a
//! first line stating the command and what it computes, one line every [`LOG_EVERY`]
//! (values done, rate, estimated time left; `BOUNCEMAP_PROGRESS_EVERY=SECONDS` changes
//! the interval) and a last line. A run whose results stream into another program
//! (standard output a pipe: `| head`, `| gzip`) writes no batch log: its stderr carries
//! only errors. [`Progress::bar`] draws only the bar and says nothing in a batch log
//! (figures).

use crate::config::rules::PROGRESS_EVERY;
use crate::config::InputError;
use crate::output::sink::streams_to_program;
use crate::output::to_stderr;
use bouncemap_engine::jobs::Progress as JobProgress;
use std::io::IsTerminal;
use std::time::{Duration, Instant};

/// Interval of the log lines when stderr is not a terminal, unless
/// `BOUNCEMAP_PROGRESS_EVERY` says otherwise.
pub const LOG_EVERY: Duration = Duration::from_secs(PROGRESS_EVERY.default as u64);

/// The interval `BOUNCEMAP_PROGRESS_EVERY` sets, checked once by [`check_environment`].
static EVERY: std::sync::OnceLock<Duration> = std::sync::OnceLock::new();

/// Read and check `BOUNCEMAP_PROGRESS_EVERY` (seconds between the lines of a batch
/// log): a value that is not a number in range is bad input, refused before any work.
pub fn check_environment() -> Result<(), InputError> {
    let every = match std::env::var_os("BOUNCEMAP_PROGRESS_EVERY") {
        None => LOG_EVERY,
        Some(v) => {
            let text = v.to_string_lossy();
            let secs = PROGRESS_EVERY
                .parse(&text)
                .map_err(|e| InputError(format!("BOUNCEMAP_PROGRESS_EVERY: {e}")))?;
            Duration::from_secs_f64(secs)
        }
    };
    let _ = EVERY.set(every);
    Ok(())
}

fn every() -> Duration {
    *EVERY.get().unwrap_or(&LOG_EVERY)
}

/// Progress reporting for one computation.
pub struct Progress {
    what: String,
    /// What the units are called (`values`, `starts`).
    unit: &'static str,
    terminal: bool,
    /// Lines in a batch log (false: the bar on a terminal, nothing otherwise).
    log: bool,
    every: Duration,
    last: Instant,
    /// Whether a bar is on the terminal (to be cleared).
    drawn: bool,
}

impl Progress {
    /// Start reporting `what` (`sweep`) over `total` units; `spec` states the run in
    /// the log's first line.
    pub fn start(what: &'static str, total: usize, spec: &str) -> Progress {
        Progress::start_units(what, "values", total, spec)
    }

    /// [`Self::start`] for units called `unit`.
    pub fn start_units(
        what: &'static str,
        unit: &'static str,
        total: usize,
        spec: &str,
    ) -> Progress {
        let terminal = std::io::stderr().is_terminal();
        let every = every();
        let log = !streams_to_program();
        if !terminal && log {
            let argv: Vec<String> = std::env::args().map(|a| shell_word(&a)).collect();
            to_stderr(&format!(
                "bouncemap: {what} of {total} {unit} started: {}\nbouncemap: {what} specification: {spec}\n",
                argv.join(" ")
            ));
        }
        Progress {
            what: what.to_string(),
            unit,
            terminal,
            log,
            every,
            last: Instant::now(),
            drawn: false,
        }
    }

    /// Report `what` as a bar when stderr is a terminal, and nothing otherwise.
    pub fn bar(what: &str) -> Progress {
        Progress {
            what: what.to_string(),
            unit: "values",
            terminal: std::io::stderr().is_terminal(),
            log: false,
            every: every(),
            last: Instant::now(),
            drawn: false,
        }
    }

    /// What the units are called (`values`, `starts`, `pixels`).
    pub fn unit(&self) -> &'static str {
        self.unit
    }

    /// Report `p` if it is time to.
    pub fn update(&mut self, p: &JobProgress) {
        self.update_noting(p, "");
    }

    /// [`Self::update`] with `note` (what has been found so far) after the numbers.
    pub fn update_noting(&mut self, p: &JobProgress, note: &str) {
        let now = Instant::now();
        if self.terminal {
            // At most ten redraws a second.
            if now.duration_since(self.last) < Duration::from_millis(100) && p.done < p.total {
                return;
            }
            self.last = now;
            let width = 30;
            let filled = (p.fraction() * width as f64) as usize;
            let rate = if p.events > 0 {
                format!("  {:.2} M events/s", p.events_per_second() / 1e6)
            } else {
                String::new()
            };
            to_stderr(&format!(
                "\r\x1b[2K{} [{}{}] {}/{} {}{rate}{note}  {:.0} s",
                self.what,
                "#".repeat(filled),
                "-".repeat(width - filled),
                p.done,
                p.total,
                self.unit,
                p.elapsed.as_secs_f64()
            ));
            self.drawn = true;
        } else if self.log && now.duration_since(self.last) >= self.every {
            self.last = now;
            to_stderr(&format!(
                "bouncemap: {}{note}\n",
                line(&self.what, self.unit, p)
            ));
        }
    }

    /// The last report.
    pub fn finish(self, p: &JobProgress) {
        if !self.terminal && self.log {
            to_stderr(&format!(
                "bouncemap: {} finished: {}\n",
                self.what,
                line(&self.what, self.unit, p)
            ));
        }
    }
}

impl Drop for Progress {
    /// The bar is cleared however the run ends (finished, failed, or its output closed).
    fn drop(&mut self) {
        if self.drawn {
            to_stderr("\r\x1b[2K");
        }
    }
}

fn line(what: &str, unit: &str, p: &JobProgress) -> String {
    let secs = p.elapsed.as_secs_f64();
    let rate = p.done as f64 / secs.max(1e-9);
    let left = if p.done > 0 && p.done < p.total {
        format!(", about {:.0} s left", (p.total - p.done) as f64 / rate)
    } else {
        String::new()
    };
    let events = if p.events > 0 {
        format!(", {:.2} M events/s", p.events_per_second() / 1e6)
    } else {
        String::new()
    };
    format!(
        "{what} {}/{} {unit} ({:.1}%) in {secs:.0} s, {rate:.1} {unit}/s{events}{left}",
        p.done,
        p.total,
        100.0 * p.fraction(),
    )
}

/// `a` quoted for a shell if it needs it.
fn shell_word(a: &str) -> String {
    if !a.is_empty()
        && a.chars()
            .all(|c| c.is_ascii_alphanumeric() || "-_./:=,@+%".contains(c))
    {
        a.to_string()
    } else {
        format!("'{}'", a.replace('\'', "'\\''"))
    }
}
