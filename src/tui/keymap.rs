//! Keys to actions. One table, [`Keymap`], dispatches every key press and generates the
//! `?` help overlay, so the help can never disagree with what the keys do. Bindings
//! can be overridden from the config file (`[keys]`, action name → list of keys).

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use std::collections::BTreeMap;
use std::fmt;

/// Everything a key can ask for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Action {
    Quit,
    Pause,
    Help,
    NextPanel,
    PrevPanel,
    Up,
    Down,
    Left,
    Right,
    FineLeft,
    FineRight,
    Enter,
    Cancel,
    StepOne,
    StepTen,
    StepBack,
    RestartOrbit,
    ToggleAxis,
    MarkWindow,
    ZoomIn,
    ZoomOut,
    ZoomBack,
    Colouring,
    AllAttractors,
    ToggleBasins,
    TableView,
    TogglePlane,
    PlaneCurves,
    Manifolds,
    Certify,
    ToggleGlobal,
    CyclePanels,
    Messages,
    Legend,
    Presets,
    Export,
    ExportView,
    Suspend,
}

impl Action {
    /// Every action, in help order.
    pub const ALL: [Action; 38] = [
        Action::Up,
        Action::Down,
        Action::Left,
        Action::Right,
        Action::FineLeft,
        Action::FineRight,
        Action::Enter,
        Action::Cancel,
        Action::NextPanel,
        Action::PrevPanel,
        Action::StepOne,
        Action::StepTen,
        Action::StepBack,
        Action::RestartOrbit,
        Action::ToggleAxis,
        Action::MarkWindow,
        Action::ZoomIn,
        Action::ZoomOut,
        Action::ZoomBack,
        Action::Colouring,
        Action::AllAttractors,
        Action::ToggleBasins,
        Action::TableView,
        Action::TogglePlane,
        Action::PlaneCurves,
        Action::Manifolds,
        Action::Certify,
        Action::ToggleGlobal,
        Action::CyclePanels,
        Action::Presets,
        Action::Export,
        Action::ExportView,
        Action::Pause,
        Action::Suspend,
        Action::Legend,
        Action::Messages,
        Action::Help,
        Action::Quit,
    ];

    /// Name used in the config file.
    pub fn name(self) -> &'static str {
        match self {
            Action::Quit => "quit",
            Action::Pause => "pause",
            Action::Help => "help",
            Action::NextPanel => "next_panel",
            Action::PrevPanel => "prev_panel",
            Action::Up => "up",
            Action::Down => "down",
            Action::Left => "left",
            Action::Right => "right",
            Action::FineLeft => "fine_left",
            Action::FineRight => "fine_right",
            Action::Enter => "enter",
            Action::Cancel => "cancel",
            Action::StepOne => "step_one",
            Action::StepTen => "step_ten",
            Action::StepBack => "step_back",
            Action::RestartOrbit => "restart_orbit",
            Action::ToggleAxis => "toggle_axis",
            Action::MarkWindow => "mark_window",
            Action::ZoomIn => "zoom_in",
            Action::ZoomOut => "zoom_out",
            Action::ZoomBack => "zoom_back",
            Action::Colouring => "color_by",
            Action::AllAttractors => "all_attractors",
            Action::ToggleBasins => "basins",
            Action::TableView => "table_view",
            Action::TogglePlane => "plane",
            Action::PlaneCurves => "plane_curves",
            Action::Manifolds => "manifolds",
            Action::Certify => "certify",
            Action::ToggleGlobal => "attractors_along",
            Action::CyclePanels => "cycle_panels",
            Action::Messages => "messages",
            Action::Legend => "legend",
            Action::Presets => "presets",
            Action::Export => "export",
            Action::ExportView => "export_view",
            Action::Suspend => "suspend",
        }
    }

    pub fn from_name(s: &str) -> Option<Action> {
        Action::ALL.iter().copied().find(|a| a.name() == s)
    }

    /// One line for the help overlay.
    pub fn describe(self) -> &'static str {
        match self {
            Action::Quit => "quit (the terminal is restored)",
            Action::Pause => "pause / resume all computing",
            Action::Help => "this help",
            Action::NextPanel => "focus the next panel (parameters, diagram)",
            Action::PrevPanel => "focus the previous panel",
            Action::Up => "previous parameter / diagram cursor up",
            Action::Down => "next parameter / diagram cursor down",
            Action::Left => "nudge down (coarse) / diagram cursor left",
            Action::Right => "nudge up (coarse) / diagram cursor right",
            Action::FineLeft => "nudge down (fine) / cursor one column left",
            Action::FineRight => "nudge up (fine) / cursor one column right",
            Action::Enter => "type an exact value / set the swept value to the cursor",
            Action::Cancel => "cancel typing, close an overlay, drop a mark",
            Action::StepOne => "bounce: step exactly one impact",
            Action::StepTen => "bounce: step ten impacts",
            Action::StepBack => "bounce: step back through history",
            Action::RestartOrbit => "bounce: restart from the initial state",
            Action::ToggleAxis => "diagram: phase t̂ or velocity v; plane: next vertical axis",
            Action::MarkWindow => "diagram: mark a corner; the second zooms (window or box)",
            Action::ZoomIn => "diagram: zoom in about the cursor",
            Action::ZoomOut => "diagram: zoom out about the cursor",
            Action::ZoomBack => "diagram: back to the previous window",
            Action::Colouring => "diagram: colour by orbit class / attractor / density",
            Action::AllAttractors => "diagram: all attractors (8 starts per value) or one start",
            Action::ToggleBasins => "basins of attraction in place of the phase plot (and back)",
            Action::TableView => "the table: F, F′, F″ with breakpoints, t̂* and release phases",
            Action::TogglePlane => "the α × D plane (t: another axis) in place of the diagram",
            Action::PlaneCurves => "plane: two-parameter curves (PD, fold, BC, G) on/off",
            Action::Manifolds => "phase, basins: saddle manifolds (cursor's cycle or (1, k))",
            Action::Certify => "stability: prove the cycle under the cursor; the branches too",
            Action::ToggleGlobal => "attractors along α and their basins, in place of the diagram",
            Action::CyclePanels => "narrow screen: show the bottom panel left out",
            Action::Messages => "the messages so far, each in full (the status line cuts them)",
            Action::Legend => "what every mark, line and colour on the screen means",
            Action::Presets => "presets: the paper's figures",
            Action::Export => "export the diagram (csv and text; the name is typed)",
            Action::ExportView => "export csv, text and the view as SVG and PNG figures",
            Action::Suspend => "stop bouncemap (the shell's fg continues it)",
        }
    }
}

impl fmt::Display for Action {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The named keys of the config file (after an optional `ctrl-`, `alt-` or `shift-`).
pub const KEY_NAMES: &str = "space, enter, esc, tab, backtab, backspace, up, down, left, right, pageup, pagedown, home, end, f1..f12";

/// A key with modifiers, as written in the config file ("q", "ctrl-c", "shift-left").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Key {
    pub ctrl: bool,
    pub alt: bool,
    pub shift: bool,
    pub code: KeyName,
}

/// The key itself.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum KeyName {
    Char(char),
    Up,
    Down,
    Left,
    Right,
    Enter,
    Esc,
    Tab,
    BackTab,
    Backspace,
    PageUp,
    PageDown,
    Home,
    End,
    F(u8),
}

impl Key {
    pub const fn plain(code: KeyName) -> Key {
        Key {
            ctrl: false,
            alt: false,
            shift: false,
            code,
        }
    }

    pub const fn ch(c: char) -> Key {
        Key::plain(KeyName::Char(c))
    }

    /// Normalise a terminal key event. Shift on a character is folded into the
    /// character itself ('N', not shift-n).
    pub fn from_event(ev: &KeyEvent) -> Option<Key> {
        let m = ev.modifiers;
        let code = match ev.code {
            KeyCode::Char(' ') => KeyName::Char(' '),
            KeyCode::Char(c) => KeyName::Char(if m.contains(KeyModifiers::CONTROL) {
                c.to_ascii_lowercase()
            } else {
                c
            }),
            KeyCode::Up => KeyName::Up,
            KeyCode::Down => KeyName::Down,
            KeyCode::Left => KeyName::Left,
            KeyCode::Right => KeyName::Right,
            KeyCode::Enter => KeyName::Enter,
            KeyCode::Esc => KeyName::Esc,
            KeyCode::Tab => KeyName::Tab,
            KeyCode::BackTab => KeyName::BackTab,
            KeyCode::Backspace => KeyName::Backspace,
            KeyCode::PageUp => KeyName::PageUp,
            KeyCode::PageDown => KeyName::PageDown,
            KeyCode::Home => KeyName::Home,
            KeyCode::End => KeyName::End,
            KeyCode::F(n) => KeyName::F(n),
            _ => return None,
        };
        let is_char = matches!(code, KeyName::Char(_));
        Some(Key {
            ctrl: m.contains(KeyModifiers::CONTROL),
            alt: m.contains(KeyModifiers::ALT),
            shift: m.contains(KeyModifiers::SHIFT) && !is_char && code != KeyName::BackTab,
            code,
        })
    }

    /// Parse "q", "ctrl-c", "shift-left", "space", "enter", "f1", ...
    pub fn parse(s: &str) -> Result<Key, String> {
        let bad = || {
            format!(
                "{} is not a key: valid a character, or [ctrl-|alt-|shift-] with {KEY_NAMES}",
                crate::output::text::quoted(s)
            )
        };
        let mut key = Key::ch(' ');
        let mut rest = s.trim();
        if rest.is_empty() {
            return Err(bad());
        }
        loop {
            let lower = rest.to_ascii_lowercase();
            if rest.chars().count() > 1 && lower.starts_with("ctrl-") {
                key.ctrl = true;
                rest = &rest[5..];
            } else if rest.chars().count() > 1 && lower.starts_with("alt-") {
                key.alt = true;
                rest = &rest[4..];
            } else if rest.chars().count() > 1 && lower.starts_with("shift-") {
                key.shift = true;
                rest = &rest[6..];
            } else {
                break;
            }
        }
        let mut chars = rest.chars();
        key.code = match (chars.next(), chars.next()) {
            (Some(c), None) => KeyName::Char(if key.ctrl { c.to_ascii_lowercase() } else { c }),
            _ => match rest.to_ascii_lowercase().as_str() {
                "space" => KeyName::Char(' '),
                "enter" | "return" => KeyName::Enter,
                "esc" | "escape" => KeyName::Esc,
                "tab" => KeyName::Tab,
                "backtab" => KeyName::BackTab,
                "backspace" => KeyName::Backspace,
                "up" => KeyName::Up,
                "down" => KeyName::Down,
                "left" => KeyName::Left,
                "right" => KeyName::Right,
                "pageup" => KeyName::PageUp,
                "pagedown" => KeyName::PageDown,
                "home" => KeyName::Home,
                "end" => KeyName::End,
                f if f.starts_with('f') => match f[1..].parse::<u8>() {
                    Ok(n @ 1..=12) => KeyName::F(n),
                    _ => return Err(bad()),
                },
                _ => return Err(bad()),
            },
        };
        if matches!(key.code, KeyName::Char(_)) && key.shift {
            return Err(format!(
                "{}: write the shifted character itself (e.g. 'N'), not shift- with a character",
                crate::output::text::quoted(s)
            ));
        }
        Ok(key)
    }
}

impl fmt::Display for Key {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.ctrl {
            f.write_str("Ctrl-")?;
        }
        if self.alt {
            f.write_str("Alt-")?;
        }
        if self.shift {
            f.write_str("Shift-")?;
        }
        match self.code {
            KeyName::Char(' ') => f.write_str("space"),
            KeyName::Char(c) => write!(f, "{c}"),
            KeyName::Up => f.write_str("↑"),
            KeyName::Down => f.write_str("↓"),
            KeyName::Left => f.write_str("←"),
            KeyName::Right => f.write_str("→"),
            KeyName::Enter => f.write_str("Enter"),
            KeyName::Esc => f.write_str("Esc"),
            KeyName::Tab => f.write_str("Tab"),
            KeyName::BackTab => f.write_str("Shift-Tab"),
            KeyName::Backspace => f.write_str("Backspace"),
            KeyName::PageUp => f.write_str("PgUp"),
            KeyName::PageDown => f.write_str("PgDn"),
            KeyName::Home => f.write_str("Home"),
            KeyName::End => f.write_str("End"),
            KeyName::F(n) => write!(f, "F{n}"),
        }
    }
}

/// The one table of key bindings.
#[derive(Clone, Debug)]
pub struct Keymap {
    map: BTreeMap<Key, Action>,
}

impl Default for Keymap {
    fn default() -> Self {
        use KeyName::*;
        let shift = |code| Key {
            shift: true,
            ..Key::plain(code)
        };
        let ctrl = |c| Key {
            ctrl: true,
            ..Key::ch(c)
        };
        let pairs: Vec<(Key, Action)> = vec![
            (Key::ch('q'), Action::Quit),
            (ctrl('c'), Action::Quit),
            (ctrl('z'), Action::Suspend),
            (Key::ch(' '), Action::Pause),
            (Key::ch('?'), Action::Help),
            (Key::ch('l'), Action::Legend),
            (Key::ch('L'), Action::Messages),
            (Key::ch('o'), Action::CyclePanels),
            (Key::plain(Tab), Action::NextPanel),
            (Key::plain(BackTab), Action::PrevPanel),
            (Key::plain(Up), Action::Up),
            (Key::ch('k'), Action::Up),
            (Key::plain(Down), Action::Down),
            (Key::ch('j'), Action::Down),
            (Key::plain(Left), Action::Left),
            (Key::ch('h'), Action::Left),
            (Key::plain(Right), Action::Right),
            (shift(Left), Action::FineLeft),
            (Key::ch(','), Action::FineLeft),
            (shift(Right), Action::FineRight),
            (Key::ch('.'), Action::FineRight),
            (Key::plain(Enter), Action::Enter),
            (Key::plain(Esc), Action::Cancel),
            (Key::ch('n'), Action::StepOne),
            (Key::ch('N'), Action::StepTen),
            (Key::ch('b'), Action::StepBack),
            (Key::ch('0'), Action::RestartOrbit),
            (Key::ch('t'), Action::ToggleAxis),
            (Key::ch('m'), Action::MarkWindow),
            (Key::ch('+'), Action::ZoomIn),
            (Key::ch('='), Action::ZoomIn),
            (Key::ch('-'), Action::ZoomOut),
            (Key::ch('z'), Action::ZoomBack),
            (Key::plain(Backspace), Action::ZoomBack),
            (Key::ch('c'), Action::Colouring),
            (Key::ch('a'), Action::AllAttractors),
            (Key::ch('B'), Action::ToggleBasins),
            (Key::ch('T'), Action::TableView),
            (Key::ch('M'), Action::TogglePlane),
            (Key::ch('C'), Action::PlaneCurves),
            (Key::ch('W'), Action::Manifolds),
            (Key::ch('V'), Action::Certify),
            (Key::ch('A'), Action::ToggleGlobal),
            (Key::ch('p'), Action::Presets),
            (Key::ch('e'), Action::Export),
            (Key::ch('E'), Action::ExportView),
        ];
        Keymap {
            map: pairs.into_iter().collect(),
        }
    }
}

impl Keymap {
    /// The action bound to a key event, if any.
    pub fn action(&self, ev: &KeyEvent) -> Option<Action> {
        Key::from_event(ev).and_then(|k| self.map.get(&k).copied())
    }

    /// Ctrl-C, which always quits.
    pub const CTRL_C: Key = Key {
        ctrl: true,
        alt: false,
        shift: false,
        code: KeyName::Char('c'),
    };

    /// The default bindings with those of `config` (action → its keys) in place of the
    /// configured actions' defaults. Refused: a key bound to two actions (in the config,
    /// or in the config and by default to an action the config leaves alone), Ctrl-C for
    /// anything but quitting, and quit without a key.
    pub fn with(config: &[(Action, Vec<Key>)]) -> Result<Keymap, String> {
        let mut km = Keymap::default();
        let mut owner: BTreeMap<Key, Action> = BTreeMap::new();
        for (a, keys) in config {
            for k in keys {
                if *k == Self::CTRL_C && *a != Action::Quit {
                    return Err(format!("keys.{a}: ctrl-c always quits: valid another key"));
                }
                if let Some(b) = owner.insert(*k, *a) {
                    if b != *a {
                        return Err(format!(
                            "keys: {k} is bound to both {b} and {a}: valid one action per key"
                        ));
                    }
                }
            }
            km.map.retain(|_, x| x != a);
        }
        for (k, a) in owner {
            if let Some(b) = km.map.get(&k) {
                return Err(format!(
                    "keys.{a}: {k} is {b}'s key by default: valid one action per key (rebind {b} too)"
                ));
            }
            km.map.insert(k, a);
        }
        if km.keys_for(Action::Quit).is_empty() {
            return Err(
                "keys.quit: quit has no key left: valid at least one key (ctrl-c also always quits)"
                    .into(),
            );
        }
        km.map.insert(Self::CTRL_C, Action::Quit);
        Ok(km)
    }

    /// Keys bound to an action, in a stable order.
    pub fn keys_for(&self, action: Action) -> Vec<Key> {
        self.map
            .iter()
            .filter(|(_, a)| **a == action)
            .map(|(k, _)| *k)
            .collect()
    }

    /// Lines for the help overlay: (keys, description), in [`Action::ALL`] order.
    pub fn help(&self) -> Vec<(String, &'static str)> {
        Action::ALL
            .iter()
            .map(|a| {
                let keys = self.keys_for(*a);
                let text = if keys.is_empty() {
                    "(unbound)".to_string()
                } else {
                    keys.iter()
                        .map(|k| k.to_string())
                        .collect::<Vec<_>>()
                        .join(" ")
                };
                (text, a.describe())
            })
            .collect()
    }

    /// The first key of an action, for hints ("?" for help).
    pub fn hint(&self, action: Action) -> String {
        self.keys_for(action)
            .first()
            .map_or_else(|| "-".into(), |k| k.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The help overlay spans the screen inside its border: at 80 columns every line of
    /// it (the keys, padded as the overlay pads them, and the description) fits in 78.
    #[test]
    fn every_help_line_fits_an_80_column_terminal() {
        let help = Keymap::default().help();
        let key_w = help
            .iter()
            .map(|(k, _)| k.chars().count())
            .max()
            .unwrap()
            .min(24);
        let long: Vec<String> = help
            .iter()
            .map(|(k, d)| {
                (
                    k,
                    d,
                    1 + key_w.max(k.chars().count()) + 2 + d.chars().count(),
                )
            })
            .filter(|(_, _, w)| *w > 78)
            .map(|(k, d, w)| format!("{k}: {d} ({w} columns)"))
            .collect();
        assert!(long.is_empty(), "{long:#?}");
    }

    fn ev(code: KeyCode, m: KeyModifiers) -> KeyEvent {
        KeyEvent::new(code, m)
    }

    #[test]
    fn default_keys_dispatch_to_the_documented_actions() {
        let k = Keymap::default();
        assert_eq!(
            k.action(&ev(KeyCode::Char('q'), KeyModifiers::NONE)),
            Some(Action::Quit)
        );
        assert_eq!(
            k.action(&ev(KeyCode::Char('c'), KeyModifiers::CONTROL)),
            Some(Action::Quit)
        );
        assert_eq!(
            k.action(&ev(KeyCode::Char(' '), KeyModifiers::NONE)),
            Some(Action::Pause)
        );
        assert_eq!(
            k.action(&ev(KeyCode::Char('?'), KeyModifiers::SHIFT)),
            Some(Action::Help)
        );
        assert_eq!(
            k.action(&ev(KeyCode::Char('N'), KeyModifiers::SHIFT)),
            Some(Action::StepTen)
        );
        assert_eq!(
            k.action(&ev(KeyCode::Char('n'), KeyModifiers::NONE)),
            Some(Action::StepOne)
        );
        assert_eq!(
            k.action(&ev(KeyCode::Left, KeyModifiers::SHIFT)),
            Some(Action::FineLeft)
        );
        assert_eq!(
            k.action(&ev(KeyCode::Left, KeyModifiers::NONE)),
            Some(Action::Left)
        );
        assert_eq!(k.action(&ev(KeyCode::Char('x'), KeyModifiers::NONE)), None);
    }

    #[test]
    fn parse_keys_and_refuse_nonsense() {
        assert_eq!(
            Key::parse("ctrl-c").unwrap(),
            Key {
                ctrl: true,
                ..Key::ch('c')
            }
        );
        assert_eq!(Key::parse("space").unwrap(), Key::ch(' '));
        assert_eq!(Key::parse("-").unwrap(), Key::ch('-'));
        assert_eq!(Key::parse("F5").unwrap(), Key::plain(KeyName::F(5)));
        assert!(Key::parse("shift-n").unwrap_err().contains("'N'"));
        assert!(Key::parse("hyper-x").unwrap_err().contains("is not a key"));
        assert!(Key::parse("").is_err());
    }

    #[test]
    fn help_is_generated_from_the_bindings() {
        let k = Keymap::with(&[(Action::StepOne, vec![Key::ch('s')])]).unwrap();
        let help = k.help();
        let line = help
            .iter()
            .find(|(_, d)| *d == Action::StepOne.describe())
            .unwrap();
        assert_eq!(line.0, "s");
        assert_eq!(k.action(&ev(KeyCode::Char('n'), KeyModifiers::NONE)), None);
        assert_eq!(help.len(), Action::ALL.len());
    }

    #[test]
    fn configs_that_bind_a_key_twice_or_leave_quit_unbound_are_refused() {
        let q = Key::ch('q');
        for (config, want) in [
            (vec![(Action::Quit, vec![])], "quit has no key"),
            (vec![(Action::Up, vec![q])], "q is quit's key by default"),
            (
                vec![
                    (Action::Up, vec![Key::ch('x')]),
                    (Action::Down, vec![Key::ch('x')]),
                ],
                "bound to both",
            ),
            (
                vec![(Action::Help, vec![Keymap::CTRL_C])],
                "ctrl-c always quits",
            ),
        ] {
            let e = Keymap::with(&config).unwrap_err();
            assert!(e.contains(want), "{config:?}: {e}");
        }
        // Moving quit away from q frees q for another action; Ctrl-C still quits.
        let k = Keymap::with(&[(Action::Quit, vec![Key::ch('Q')]), (Action::Up, vec![q])]).unwrap();
        assert_eq!(k.keys_for(Action::Quit), vec![Key::ch('Q'), Keymap::CTRL_C]);
        assert_eq!(
            k.action(&ev(KeyCode::Char('q'), KeyModifiers::NONE)),
            Some(Action::Up)
        );
    }

    #[test]
    fn every_action_has_a_default_key_and_a_unique_name() {
        let k = Keymap::default();
        let mut names = std::collections::HashSet::new();
        for a in Action::ALL {
            assert!(!k.keys_for(a).is_empty(), "{a} unbound");
            assert!(names.insert(a.name()));
            assert_eq!(Action::from_name(a.name()), Some(a));
        }
    }
}
