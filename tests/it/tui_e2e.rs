//! End to end: the real binary in a pseudo-terminal at 120×40. Waits for the diagram
//! to fill, steps a bounce, opens and closes the help, pauses, quits with `q`, and
//! checks the exit status and that the terminal was restored; SIGTERM restores it too
//! and exits with 143. Also: without a terminal the binary exits with status 2 and
//! points at the headless commands.

use portable_pty::{native_pty_system, CommandBuilder, PtySize};
use std::io::{Read, Write};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// Wait until the raw output contains `needle`.
fn wait_for(out: &Arc<Mutex<Vec<u8>>>, needle: &str, timeout: Duration) -> bool {
    let t = Instant::now();
    while t.elapsed() < timeout {
        if String::from_utf8_lossy(&out.lock().unwrap()).contains(needle) {
            return true;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    false
}

/// The screen as a terminal shows it after the output so far.
fn screen(out: &Arc<Mutex<Vec<u8>>>) -> String {
    let mut p = vt100::Parser::new(40, 120, 0);
    p.process(&out.lock().unwrap());
    p.screen().contents()
}

/// Wait until the screen shows `needle`.
fn wait_screen(out: &Arc<Mutex<Vec<u8>>>, needle: &str, timeout: Duration) -> bool {
    let t = Instant::now();
    while t.elapsed() < timeout {
        if screen(out).contains(needle) {
            return true;
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    false
}

/// The binary running in a 120×40 pseudo-terminal: the child, its output so far, the
/// keyboard, and the terminal's master side (kept open while the test runs).
struct Running {
    child: Box<dyn portable_pty::Child + Send + Sync>,
    out: Arc<Mutex<Vec<u8>>>,
    writer: Box<dyn Write + Send>,
    _master: Box<dyn portable_pty::MasterPty + Send>,
}

fn start() -> Running {
    let pty = native_pty_system();
    let pair = pty
        .openpty(PtySize {
            rows: 40,
            cols: 120,
            pixel_width: 0,
            pixel_height: 0,
        })
        .unwrap();
    let mut cmd = CommandBuilder::new(env!("CARGO_BIN_EXE_bouncemap"));
    cmd.env("TERM", "xterm-256color");
    cmd.env(
        "XDG_CONFIG_HOME",
        std::env::temp_dir().join("bouncemap-e2e-no-config"),
    );
    let child = pair.slave.spawn_command(cmd).unwrap();
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
        _master: pair.master,
    }
}

/// Wait for the child to exit (at most 10 s).
fn exit_status(child: &mut Box<dyn portable_pty::Child + Send + Sync>) -> portable_pty::ExitStatus {
    let t = Instant::now();
    loop {
        if let Some(s) = child.try_wait().unwrap() {
            return s;
        }
        assert!(t.elapsed() < Duration::from_secs(10), "did not exit");
        std::thread::sleep(Duration::from_millis(50));
    }
}

#[test]
fn runs_in_a_pty_fills_the_diagram_steps_and_quits_cleanly() {
    let Running {
        mut child,
        out,
        mut writer,
        _master,
    } = start();
    assert!(
        wait_for(&out, "\x1b[?1049h", Duration::from_secs(10)),
        "no alternate screen"
    );
    assert!(
        wait_screen(&out, "Bifurcation diagram", Duration::from_secs(10)),
        "{}",
        screen(&out)
    );
    assert!(
        wait_screen(&out, "100%", Duration::from_secs(60)),
        "diagram did not fill: {}",
        screen(&out)
    );
    let lit = screen(&out)
        .chars()
        .filter(|c| ('\u{2801}'..='\u{28ff}').contains(c))
        .count();
    assert!(lit > 300, "only {lit} braille cells");
    assert!(wait_screen(&out, "κ_c = -1.0123", Duration::from_secs(10)));
    writer.write_all(b"n").unwrap();
    writer.flush().unwrap();
    assert!(
        wait_screen(&out, "Bounce #1", Duration::from_secs(10)),
        "step did not show"
    );
    writer.write_all(b"?").unwrap();
    writer.flush().unwrap();
    assert!(wait_screen(
        &out,
        "step exactly one impact",
        Duration::from_secs(10)
    ));
    writer.write_all(b"\x1b").unwrap();
    writer.flush().unwrap();
    std::thread::sleep(Duration::from_millis(200));
    writer.write_all(b" ").unwrap();
    writer.flush().unwrap();
    assert!(wait_screen(&out, "PAUSED", Duration::from_secs(10)));
    writer.write_all(b"q").unwrap();
    writer.flush().unwrap();
    let status = exit_status(&mut child);
    assert!(status.success(), "exit status {status:?}");
    assert!(
        wait_for(&out, "\x1b[?1049l", Duration::from_secs(5)),
        "alternate screen not left"
    );
}

#[test]
fn sigterm_restores_the_terminal_and_exits_143() {
    let Running {
        mut child,
        out,
        writer: _writer,
        _master,
    } = start();
    assert!(
        wait_screen(&out, "Bifurcation diagram", Duration::from_secs(10)),
        "{}",
        screen(&out)
    );
    let pid = child.process_id().expect("the child has a pid");
    let killed = std::process::Command::new("kill")
        .args(["-TERM", &pid.to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let status = exit_status(&mut child);
    assert_eq!(status.exit_code(), 143, "{status:?}");
    assert!(
        wait_for(&out, "\x1b[?1049l", Duration::from_secs(5)),
        "alternate screen not left"
    );
}

#[test]
fn without_a_terminal_it_exits_2_and_names_the_headless_commands() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_bouncemap"))
        .stdin(std::process::Stdio::null())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("bouncemap orbit"), "{err}");
}

#[test]
fn bad_flags_exit_2_with_the_valid_range() {
    for (args, want) in [
        (&["--marker", "box"][..], "valid braille, halfblock, dot"),
        (
            &["--color", "rainbow"][..],
            "valid auto, never, 16, 256, truecolor",
        ),
        (&["--fps", "0"][..], "1..=60"),
        (&["--alpha=-1"][..], "(0, 1000]"),
    ] {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_bouncemap"))
            .args(args)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(want), "{args:?}: {err}");
    }
}
