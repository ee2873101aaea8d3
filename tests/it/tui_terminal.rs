//! The terminal application survives what terminals do: a stop (Ctrl-Z, or SIGTSTP
//! from outside) leaves the shell with a sane terminal and `fg` takes it back; an
//! unterminated bracketed-paste start swallows nothing; a config that leaves no way to
//! quit is refused. Runs the real binary in a pseudo-terminal and reads the terminal's
//! modes with `stty`.

use portable_pty::{native_pty_system, CommandBuilder, PtySize};
use std::io::{Read, Write};
use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

struct Running {
    child: Box<dyn portable_pty::Child + Send + Sync>,
    out: Arc<Mutex<Vec<u8>>>,
    writer: Box<dyn Write + Send>,
    tty: PathBuf,
    _master: Box<dyn portable_pty::MasterPty + Send>,
}

fn start(args: &[&str]) -> Running {
    let pair = native_pty_system()
        .openpty(PtySize {
            rows: 40,
            cols: 120,
            pixel_width: 0,
            pixel_height: 0,
        })
        .unwrap();
    let mut cmd = CommandBuilder::new(env!("CARGO_BIN_EXE_bouncemap"));
    cmd.args(args);
    cmd.env("TERM", "xterm-256color");
    cmd.env(
        "XDG_CONFIG_HOME",
        std::env::temp_dir().join("bouncemap-terminal-no-config"),
    );
    let child = pair.slave.spawn_command(cmd).unwrap();
    let tty = pair.master.tty_name().expect("the pty has a device name");
    drop(pair.slave);
    let mut reader = pair.master.try_clone_reader().unwrap();
    let writer = pair.master.take_writer().unwrap();
    let out = Arc::new(Mutex::new(Vec::new()));
    let sink = out.clone();
    std::thread::spawn(move || {
        let mut buf = [0u8; 8192];
        while let Ok(n) = reader.read(&mut buf) {
            if n == 0 {
                break;
            }
            sink.lock().unwrap().extend_from_slice(&buf[..n]);
        }
    });
    Running {
        child,
        out,
        writer,
        tty,
        _master: pair.master,
    }
}

impl Running {
    fn send(&mut self, bytes: &[u8]) {
        self.writer.write_all(bytes).unwrap();
        self.writer.flush().unwrap();
    }

    /// How often `needle` occurs in the output so far.
    fn count(&self, needle: &str) -> usize {
        String::from_utf8_lossy(&self.out.lock().unwrap())
            .matches(needle)
            .count()
    }

    fn wait_count(&self, needle: &str, n: usize) -> bool {
        let t = Instant::now();
        while t.elapsed() < Duration::from_secs(10) {
            if self.count(needle) >= n {
                return true;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        false
    }

    /// The terminal's modes, as `stty -a` prints them.
    fn stty(&self) -> String {
        let o = std::process::Command::new("stty")
            .arg("-a")
            .arg("-F")
            .arg(&self.tty)
            .output()
            .unwrap();
        String::from_utf8_lossy(&o.stdout).into_owned()
    }

    /// The process state letter from /proc (T: stopped).
    fn state(&self) -> char {
        let pid = self.child.process_id().unwrap();
        let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).unwrap_or_default();
        stat.rsplit(')')
            .next()
            .and_then(|s| s.trim().chars().next())
            .unwrap_or('?')
    }

    fn wait_state(&self, want: char) -> bool {
        let t = Instant::now();
        while t.elapsed() < Duration::from_secs(10) {
            if self.state() == want {
                return true;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        false
    }

    fn kill(&self, sig: &str) {
        let pid = self.child.process_id().unwrap();
        assert!(std::process::Command::new("kill")
            .args([sig, &pid.to_string()])
            .status()
            .unwrap()
            .success());
    }

    /// Wait for the exit (at most `limit`).
    fn exit_code(&mut self, limit: Duration) -> Option<u32> {
        let t = Instant::now();
        while t.elapsed() < limit {
            if let Some(s) = self.child.try_wait().unwrap() {
                return Some(s.exit_code());
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        let _ = self.child.kill();
        None
    }
}

/// A stop and `fg` taken as the shell sees them: raw while running, cooked with the
/// main screen and the cursor while stopped, raw again after, then `q` quits at once.
fn stop_and_continue(r: &mut Running, stop: impl Fn(&mut Running)) {
    assert!(r.wait_count("\x1b[?1049h", 1), "no alternate screen");
    assert!(r.wait_count("Bifurcation diagram", 1));
    let running = r.stty();
    assert!(
        running.contains("-icanon") && running.contains("-echo "),
        "{running}"
    );
    let left = r.count("\x1b[?1049l");
    stop(r);
    assert!(r.wait_state('T'), "the process did not stop");
    assert!(
        r.wait_count("\x1b[?1049l", left + 1),
        "the main screen was not restored"
    );
    assert!(r.count("\x1b[?25h") >= 1, "the cursor was not shown");
    let stopped = r.stty();
    assert!(
        stopped.contains(" icanon") && stopped.contains(" echo "),
        "the shell gets a raw terminal: {stopped}"
    );
    let entered = r.count("\x1b[?1049h");
    r.kill("-CONT");
    assert!(
        r.wait_count("\x1b[?1049h", entered + 1),
        "not back in the alternate screen"
    );
    let again = r.stty();
    assert!(
        again.contains("-icanon") && again.contains("-echo "),
        "{again}"
    );
    let t = Instant::now();
    r.send(b"q");
    assert_eq!(r.exit_code(Duration::from_secs(5)), Some(0));
    assert!(
        t.elapsed() < Duration::from_secs(2),
        "q took {:?}",
        t.elapsed()
    );
    let after = r.stty();
    assert!(
        after.contains(" icanon") && after.contains(" echo "),
        "{after}"
    );
}

#[test]
fn ctrl_z_stops_with_a_sane_terminal_and_fg_takes_it_back() {
    let mut r = start(&[]);
    stop_and_continue(&mut r, |r| r.send(b"\x1a"));
}

#[test]
fn sigtstp_from_outside_stops_the_same_way() {
    let mut r = start(&[]);
    stop_and_continue(&mut r, |r| r.kill("-TSTP"));
}

#[test]
fn an_unterminated_paste_start_swallows_no_keys() {
    let mut r = start(&[]);
    assert!(r.wait_count("Bifurcation diagram", 1));
    r.send(b"\x1b[200~some text");
    std::thread::sleep(Duration::from_millis(200));
    r.send(b"\x03");
    assert_eq!(
        r.exit_code(Duration::from_secs(5)),
        Some(0),
        "Ctrl-C did not quit"
    );
}

#[test]
fn configs_that_leave_no_way_to_quit_or_bind_a_key_twice_are_refused() {
    let dir = std::env::temp_dir().join(format!("bouncemap-keys-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (text, want) in [
        ("[keys]\nquit = []\n", "quit has no key"),
        ("[keys]\nup = \"q\"\n", "q is quit's key by default"),
        ("[keys]\nup = \"x\"\ndown = \"x\"\n", "bound to both"),
        ("[keys]\nhelp = \"hyper-x\"\n", "is not a key"),
    ] {
        let path = dir.join("config.toml");
        std::fs::write(&path, text).unwrap();
        // Refused before a terminal is needed.
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_bouncemap"))
            .arg("--config")
            .arg(&path)
            .stdin(std::process::Stdio::null())
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{text:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains(want), "{text:?}: {err}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// CPU time (user + system, in clock ticks) the process has used so far.
fn cpu_ticks(pid: u32) -> u64 {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).unwrap();
    let fields: Vec<&str> = stat
        .rsplit(')')
        .next()
        .unwrap()
        .split_whitespace()
        .collect();
    // utime and stime are fields 14 and 15 of the whole line: 12 and 13 after the name.
    fields[11].parse::<u64>().unwrap() + fields[12].parse::<u64>().unwrap()
}

#[test]
fn a_paused_application_uses_no_cpu_whatever_was_pressed() {
    let mut r = start(&[]);
    assert!(r.wait_count("Bifurcation diagram", 1));
    r.send(b" ");
    assert!(r.wait_count("PAUSED", 1), "not paused");
    // A storm of every kind of key but pause, quit, stop and export: parameters moved
    // up and down (table, D, α, r, k, the window), panels, steps, zooms, overlays.
    let keys: [&[u8]; 22] = [
        b"\x1b[A", b"\x1b[B", b"\x1b[C", b"\x1b[D", b"\t", b"\x1b[Z", b"n", b"N", b"b", b"0", b"t",
        b"m", b"+", b"-", b"z", b"c", b"a", b"B", b"M", b"T", b"\x1b", b"\r",
    ];
    for i in 0..600 {
        r.send(keys[(i * 7 + i / 22) % keys.len()]);
    }
    let pid = r.child.process_id().unwrap();
    std::thread::sleep(Duration::from_millis(1500));
    let before = cpu_ticks(pid);
    std::thread::sleep(Duration::from_secs(3));
    let used = cpu_ticks(pid) - before;
    // A clock tick is 10 ms: at most 60 ms of CPU in 3 s (the event loop's idle wake-ups
    // and parked workers' polls), against seconds for any computation.
    assert!(used <= 6, "{used} ticks of CPU in 3 s while paused");
    r.send(b"q");
    assert_eq!(r.exit_code(Duration::from_secs(5)), Some(0));
}

/// Every signal whose default action ends the process leaves the terminal as it was:
/// cooked, the main screen, the cursor shown; and the process ends by that signal.
#[test]
fn every_signal_that_ends_the_application_restores_the_terminal() {
    for sig in ["-QUIT", "-USR1", "-ALRM", "-USR2", "-RTMIN"] {
        let mut r = start(&[]);
        assert!(r.wait_count("Bifurcation diagram", 1), "{sig}");
        let running = r.stty();
        assert!(running.contains("-icanon"), "{sig}: {running}");
        let left = r.count("\x1b[?1049l");
        r.kill(sig);
        let t = Instant::now();
        let status = loop {
            if let Some(s) = r.child.try_wait().unwrap() {
                break s;
            }
            assert!(t.elapsed() < Duration::from_secs(5), "{sig}: still running");
            std::thread::sleep(Duration::from_millis(20));
        };
        assert!(
            status.signal().is_some(),
            "{sig}: not ended by the signal: {status:?}"
        );
        assert!(
            r.wait_count("\x1b[?1049l", left + 1),
            "{sig}: the main screen was not restored"
        );
        assert!(r.count("\x1b[?25h") >= 1, "{sig}: the cursor was not shown");
        let after = r.stty();
        assert!(
            after.contains(" icanon") && after.contains(" echo "),
            "{sig}: the terminal is left raw: {after}"
        );
    }
}
