//! Input from the terminal: a thread reads standard input and parses keys and mouse
//! reports itself, and a second thread turns SIGWINCH, SIGTSTP and SIGCONT into events,
//! all on one channel the event loop waits on.
//!
//! Owning the parser keeps input bounded whatever arrives: an escape sequence longer than
//! [`MAX_SEQUENCE`] bytes is dropped, a lone ESC becomes the Esc key after [`ESC_WAIT`],
//! and bracketed-paste markers (`ESC [200~`, `ESC [201~`, never enabled here) are
//! ignored, so no sequence can swallow the keys after it (Ctrl-C included). End of
//! input (a terminal that hung up) is reported as [`Input::Hangup`].

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers, MouseButton, MouseEvent, MouseEventKind};
use std::sync::mpsc::{self, Receiver, Sender};
use std::time::Duration;

/// How long a lone ESC waits for the rest of a sequence before it is the Esc key.
pub const ESC_WAIT: Duration = Duration::from_millis(40);
/// Longest escape sequence accepted; longer ones are dropped.
pub const MAX_SEQUENCE: usize = 64;

/// Something the event loop must react to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Input {
    Key(KeyEvent),
    Mouse(MouseEvent),
    /// The terminal's size changed.
    Resize,
    /// SIGTSTP: stop (after restoring the terminal).
    Suspend,
    /// SIGCONT: continued after a stop.
    Continue,
    /// Standard input ended or failed: the terminal is gone.
    Hangup,
}

/// The channel of inputs.
pub struct Inputs {
    rx: Receiver<Input>,
}

impl Inputs {
    /// Start reading standard input and the terminal's signals.
    pub fn start() -> std::io::Result<Inputs> {
        let (tx, rx) = mpsc::channel();
        let keys = tx.clone();
        std::thread::Builder::new()
            .name("input".into())
            .spawn(move || read_loop(keys))?;
        use signal_hook::consts::{SIGCONT, SIGTSTP, SIGWINCH};
        let mut signals = signal_hook::iterator::Signals::new([SIGWINCH, SIGTSTP, SIGCONT])?;
        std::thread::Builder::new()
            .name("terminal-signals".into())
            .spawn(move || {
                for s in signals.forever() {
                    let ev = match s {
                        SIGWINCH => Input::Resize,
                        SIGTSTP => Input::Suspend,
                        _ => Input::Continue,
                    };
                    if tx.send(ev).is_err() {
                        return;
                    }
                }
            })?;
        Ok(Inputs { rx })
    }

    /// The next input within `timeout`, if any.
    pub fn next(&self, timeout: Duration) -> Option<Input> {
        self.rx.recv_timeout(timeout).ok()
    }

    /// An input already waiting, if any.
    pub fn try_next(&self) -> Option<Input> {
        self.rx.try_recv().ok()
    }
}

fn read_loop(tx: Sender<Input>) {
    let mut parser = Parser::default();
    let mut buf = [0u8; 1024];
    loop {
        let timeout = if parser.waiting() {
            ESC_WAIT.as_millis() as i32
        } else {
            -1
        };
        let mut pfd = libc::pollfd {
            fd: libc::STDIN_FILENO,
            events: libc::POLLIN,
            revents: 0,
        };
        // SAFETY: one valid pollfd for the duration of the call.
        let ready = unsafe { libc::poll(&mut pfd, 1, timeout) };
        if ready < 0 {
            if std::io::Error::last_os_error().kind() == std::io::ErrorKind::Interrupted {
                continue;
            }
            let _ = tx.send(Input::Hangup);
            return;
        }
        let events = if ready == 0 {
            parser.timeout()
        } else {
            // SAFETY: reads at most buf.len() bytes into buf.
            let n = unsafe { libc::read(libc::STDIN_FILENO, buf.as_mut_ptr().cast(), buf.len()) };
            if n < 0 {
                if std::io::Error::last_os_error().kind() == std::io::ErrorKind::Interrupted {
                    continue;
                }
                let _ = tx.send(Input::Hangup);
                return;
            }
            if n == 0 {
                let _ = tx.send(Input::Hangup);
                return;
            }
            parser.feed(&buf[..n as usize])
        };
        for e in events {
            if tx.send(e).is_err() {
                return;
            }
        }
    }
}

/// Bytes from the terminal into keys and mouse reports.
#[derive(Default, Debug)]
pub struct Parser {
    pending: Vec<u8>,
}

fn key(code: KeyCode, m: KeyModifiers) -> Input {
    Input::Key(KeyEvent::new(code, m))
}

impl Parser {
    /// Whether an incomplete sequence waits for more bytes.
    pub fn waiting(&self) -> bool {
        !self.pending.is_empty()
    }

    /// No more bytes came: a lone ESC is the Esc key; an incomplete sequence is dropped.
    pub fn timeout(&mut self) -> Vec<Input> {
        let lone = self.pending.as_slice() == [0x1b];
        self.pending.clear();
        if lone {
            vec![key(KeyCode::Esc, KeyModifiers::NONE)]
        } else {
            Vec::new()
        }
    }

    /// Parse `bytes` (with whatever was pending).
    pub fn feed(&mut self, bytes: &[u8]) -> Vec<Input> {
        self.pending.extend_from_slice(bytes);
        let mut out = Vec::new();
        let mut i = 0;
        let b = std::mem::take(&mut self.pending);
        while i < b.len() {
            match parse_one(&b[i..]) {
                Step::Event(n, e) => {
                    out.extend(e);
                    i += n;
                }
                Step::Skip(n) => i += n,
                Step::More => {
                    self.pending = b[i..].to_vec();
                    break;
                }
            }
        }
        out
    }
}

enum Step {
    /// Consumed n bytes giving an input (or nothing).
    Event(usize, Option<Input>),
    /// Consumed n bytes meaning nothing here.
    Skip(usize),
    /// Needs more bytes.
    More,
}

fn parse_one(b: &[u8]) -> Step {
    let none = KeyModifiers::NONE;
    match b[0] {
        0x1b => {
            if b.len() == 1 {
                return Step::More;
            }
            match b[1] {
                b'[' => parse_csi(b),
                b'O' => {
                    if b.len() < 3 {
                        return Step::More;
                    }
                    let code = match b[2] {
                        b'P' => KeyCode::F(1),
                        b'Q' => KeyCode::F(2),
                        b'R' => KeyCode::F(3),
                        b'S' => KeyCode::F(4),
                        b'A' => KeyCode::Up,
                        b'B' => KeyCode::Down,
                        b'C' => KeyCode::Right,
                        b'D' => KeyCode::Left,
                        b'H' => KeyCode::Home,
                        b'F' => KeyCode::End,
                        _ => return Step::Skip(3),
                    };
                    Step::Event(3, Some(key(code, none)))
                }
                0x1b => Step::Event(1, Some(key(KeyCode::Esc, none))),
                _ => match parse_one(&b[1..]) {
                    // Alt + a key.
                    Step::Event(n, Some(Input::Key(k))) => {
                        Step::Event(n + 1, Some(key(k.code, k.modifiers | KeyModifiers::ALT)))
                    }
                    Step::Event(n, e) => Step::Event(n + 1, e),
                    Step::Skip(n) => Step::Skip(n + 1),
                    Step::More => Step::More,
                },
            }
        }
        b'\r' | b'\n' => Step::Event(1, Some(key(KeyCode::Enter, none))),
        b'\t' => Step::Event(1, Some(key(KeyCode::Tab, none))),
        0x7f | 0x08 => Step::Event(1, Some(key(KeyCode::Backspace, none))),
        c @ 0x01..=0x1a => Step::Event(
            1,
            Some(key(
                KeyCode::Char((b'a' + c - 1) as char),
                KeyModifiers::CONTROL,
            )),
        ),
        0x00 | 0x1c..=0x1f => Step::Skip(1),
        c => {
            // UTF-8: the sequence's length from its first byte.
            let len = match c {
                0x00..=0x7f => 1,
                0xc0..=0xdf => 2,
                0xe0..=0xef => 3,
                0xf0..=0xf7 => 4,
                _ => return Step::Skip(1),
            };
            if b.len() < len {
                return Step::More;
            }
            match std::str::from_utf8(&b[..len])
                .ok()
                .and_then(|s| s.chars().next())
            {
                Some(ch) => {
                    let m = if ch.is_uppercase() {
                        KeyModifiers::SHIFT
                    } else {
                        none
                    };
                    Step::Event(len, Some(key(KeyCode::Char(ch), m)))
                }
                None => Step::Skip(1),
            }
        }
    }
}

/// `ESC [` params intermediates final.
fn parse_csi(b: &[u8]) -> Step {
    let limit = b.len().min(MAX_SEQUENCE);
    let Some(end) = b[2..limit].iter().position(|&c| (0x40..=0x7e).contains(&c)) else {
        if b.len() < MAX_SEQUENCE {
            return Step::More;
        }
        // Too long to be a key: drop the introducer and its parameters, keep the rest.
        let run = b[2..]
            .iter()
            .take_while(|&&c| (0x20..=0x3f).contains(&c))
            .count();
        return Step::Skip(2 + run);
    };
    let n = end + 3;
    let body = &b[2..n - 1];
    let fin = b[n - 1];
    let text = std::str::from_utf8(body).unwrap_or("");
    if let Some(sgr) = text.strip_prefix('<') {
        return Step::Event(n, mouse(sgr, fin));
    }
    let params: Vec<u32> = text.split(';').map(|p| p.parse().unwrap_or(0)).collect();
    let modifiers = modifiers(params.get(1).copied().unwrap_or(1));
    let code = match fin {
        b'A' => KeyCode::Up,
        b'B' => KeyCode::Down,
        b'C' => KeyCode::Right,
        b'D' => KeyCode::Left,
        b'H' => KeyCode::Home,
        b'F' => KeyCode::End,
        b'Z' => return Step::Event(n, Some(key(KeyCode::BackTab, KeyModifiers::SHIFT))),
        b'~' => match params.first().copied().unwrap_or(0) {
            1 | 7 => KeyCode::Home,
            4 | 8 => KeyCode::End,
            3 => KeyCode::Delete,
            5 => KeyCode::PageUp,
            6 => KeyCode::PageDown,
            p @ 11..=15 => KeyCode::F((p - 10) as u8),
            p @ 17..=21 => KeyCode::F((p - 11) as u8),
            p @ 23..=24 => KeyCode::F((p - 12) as u8),
            // 200/201 (paste markers) and anything else: nothing.
            _ => return Step::Skip(n),
        },
        _ => return Step::Skip(n),
    };
    Step::Event(n, Some(key(code, modifiers)))
}

/// xterm's modifier parameter (1 + bits: 1 shift, 2 alt, 4 ctrl).
fn modifiers(p: u32) -> KeyModifiers {
    let bits = p.saturating_sub(1);
    let mut m = KeyModifiers::NONE;
    if bits & 1 != 0 {
        m |= KeyModifiers::SHIFT;
    }
    if bits & 2 != 0 {
        m |= KeyModifiers::ALT;
    }
    if bits & 4 != 0 {
        m |= KeyModifiers::CONTROL;
    }
    m
}

/// An SGR mouse report `b;x;y` ending in M (press, drag) or m (release).
fn mouse(params: &str, fin: u8) -> Option<Input> {
    let v: Vec<u16> = params.split(';').filter_map(|p| p.parse().ok()).collect();
    let [b, x, y] = v[..] else {
        return None;
    };
    let (column, row) = (x.saturating_sub(1), y.saturating_sub(1));
    let button = match b & 0b11 {
        0 => MouseButton::Left,
        1 => MouseButton::Middle,
        _ => MouseButton::Right,
    };
    let kind = if b & 64 != 0 {
        if b & 1 == 0 {
            MouseEventKind::ScrollUp
        } else {
            MouseEventKind::ScrollDown
        }
    } else if b & 32 != 0 {
        MouseEventKind::Drag(button)
    } else if fin == b'm' {
        MouseEventKind::Up(button)
    } else {
        MouseEventKind::Down(button)
    };
    Some(Input::Mouse(MouseEvent {
        kind,
        column,
        row,
        modifiers: modifiers(1 + ((b as u32 >> 2) & 0b111)),
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn keys(p: &mut Parser, bytes: &[u8]) -> Vec<(KeyCode, KeyModifiers)> {
        p.feed(bytes)
            .into_iter()
            .filter_map(|e| match e {
                Input::Key(k) => Some((k.code, k.modifiers)),
                _ => None,
            })
            .collect()
    }

    #[test]
    fn keys_arrows_and_control_characters() {
        let mut p = Parser::default();
        let none = KeyModifiers::NONE;
        assert_eq!(
            keys(&mut p, b"qN\r\x03\x1a"),
            vec![
                (KeyCode::Char('q'), none),
                (KeyCode::Char('N'), KeyModifiers::SHIFT),
                (KeyCode::Enter, none),
                (KeyCode::Char('c'), KeyModifiers::CONTROL),
                (KeyCode::Char('z'), KeyModifiers::CONTROL),
            ]
        );
        assert_eq!(
            keys(&mut p, b"\x1b[A\x1b[1;2D\x1bOP\x1b[5~\x1b[Z"),
            vec![
                (KeyCode::Up, none),
                (KeyCode::Left, KeyModifiers::SHIFT),
                (KeyCode::F(1), none),
                (KeyCode::PageUp, none),
                (KeyCode::BackTab, KeyModifiers::SHIFT),
            ]
        );
        assert_eq!(
            keys(&mut p, "é".as_bytes()),
            vec![(KeyCode::Char('é'), none)]
        );
    }

    #[test]
    fn a_sequence_split_across_reads_is_joined_and_a_lone_esc_times_out() {
        let mut p = Parser::default();
        assert!(keys(&mut p, b"\x1b").is_empty());
        assert!(p.waiting());
        assert_eq!(
            keys(&mut p, b"[B"),
            vec![(KeyCode::Down, KeyModifiers::NONE)]
        );
        assert!(keys(&mut p, b"\x1b").is_empty());
        let t = p.timeout();
        assert_eq!(
            t,
            vec![Input::Key(KeyEvent::new(KeyCode::Esc, KeyModifiers::NONE))]
        );
    }

    #[test]
    fn an_unterminated_paste_never_swallows_the_keys_after_it() {
        let mut p = Parser::default();
        let got = keys(&mut p, b"\x1b[200~pasted\x03q");
        assert!(
            got.contains(&(KeyCode::Char('c'), KeyModifiers::CONTROL)),
            "{got:?}"
        );
        assert_eq!(got.last(), Some(&(KeyCode::Char('q'), KeyModifiers::NONE)));
        assert!(!p.waiting());
        // An endless unterminated sequence is dropped once it exceeds the bound.
        let mut long = b"\x1b[".to_vec();
        long.extend(std::iter::repeat_n(b'1', 200));
        long.push(b'q');
        let got = keys(&mut p, &long);
        assert_eq!(got.last(), Some(&(KeyCode::Char('q'), KeyModifiers::NONE)));
    }

    #[test]
    fn sgr_mouse_reports() {
        let mut p = Parser::default();
        let got = p.feed(b"\x1b[<0;10;5M\x1b[<0;12;5m");
        assert_eq!(
            got,
            vec![
                Input::Mouse(MouseEvent {
                    kind: MouseEventKind::Down(MouseButton::Left),
                    column: 9,
                    row: 4,
                    modifiers: KeyModifiers::NONE
                }),
                Input::Mouse(MouseEvent {
                    kind: MouseEventKind::Up(MouseButton::Left),
                    column: 11,
                    row: 4,
                    modifiers: KeyModifiers::NONE
                }),
            ]
        );
    }
}
