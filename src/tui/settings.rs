//! The terminal application's TOML config file: frame cap, colours, marker, mouse,
//! start-up defaults and key bindings. Looked up at `--config PATH`, else
//! `$XDG_CONFIG_HOME/bouncemap/config.toml` or `~/.config/bouncemap/config.toml` if
//! present. Values are checked by the same rules as the command line
//! ([`crate::config::rules`]); unknown keys and bad values are refused with a one-line
//! message naming the file, the setting and the valid range.
//!
//! ```toml
//! fps = 15
//! color = "256"        # auto | never | 16 | 256 | truecolor
//! marker = "braille"   # braille | halfblock | dot
//! mouse = false
//! [defaults]
//! table = "fd:0.1"    # or a file: "asym.toml", "asym.toml:w=0.3"
//! d = 0.1              # F_D's D (the table's parameter D)
//! params = { w = 0.3 } # any parameter of the table's family, by name
//! alpha = 0.45
//! r = 0.8
//! k = 1
//! t0 = 0.0
//! v0 = "auto"          # or a number
//! sweep = [0.45, 0.6]   # the diagram's α window
//! start = "near-fixed-point"   # or cold, warm, warm-backward
//! transient = 20000
//! keep = 100
//! [export]             # E with the plane or the basins shown: their resolution
//! plane = "400x200"     # pixels (as plane --size)
//! basins = "200x100"    # starts (as basins --grid)
//! [keys]
//! step_one = "n"
//! quit = ["q", "ctrl-c"]
//! ```

use super::keymap::{Action, Key, Keymap};
use super::params::{ParamId, Params};
use crate::config::display::ColorChoice;
use crate::config::files::{read_text, SMALL_FILE};
use crate::config::rules;
use crate::output::hitgrid::Marker;
use crate::output::text::shortest;
use bouncemap_engine::jobs::grid::SweepParam;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

#[derive(Deserialize, Default, Debug)]
#[serde(deny_unknown_fields)]
struct File {
    fps: Option<u32>,
    color: Option<String>,
    marker: Option<String>,
    mouse: Option<bool>,
    defaults: Option<Defaults>,
    export: Option<ExportSizes>,
    keys: Option<BTreeMap<String, OneOrMany>>,
}

#[derive(Deserialize, Default, Debug)]
#[serde(deny_unknown_fields)]
struct ExportSizes {
    plane: Option<String>,
    basins: Option<String>,
}

#[derive(Deserialize, Default, Debug)]
#[serde(deny_unknown_fields)]
struct Defaults {
    table: Option<String>,
    d: Option<f64>,
    params: Option<BTreeMap<String, f64>>,
    alpha: Option<f64>,
    r: Option<f64>,
    k: Option<u32>,
    t0: Option<f64>,
    v0: Option<toml::Value>,
    sweep: Option<[f64; 2]>,
    start: Option<String>,
    transient: Option<toml::Value>,
    keep: Option<toml::Value>,
}

#[derive(Deserialize, Debug)]
#[serde(untagged)]
enum OneOrMany {
    One(String),
    Many(Vec<String>),
}

/// What a `[defaults]` entry sets: a row, or a parameter of the table's family by name
/// (found once the table is set).
#[derive(Clone, Debug, PartialEq)]
pub enum Setting {
    Row(ParamId),
    Family(String),
}

/// Settings read from a config file (None: not set there).
#[derive(Debug, Default)]
pub struct Config {
    pub path: Option<PathBuf>,
    pub fps: Option<u32>,
    pub color: Option<ColorChoice>,
    pub marker: Option<Marker>,
    pub mouse: Option<bool>,
    /// (setting, typed text) pairs applied to the default parameters in order.
    pub defaults: Vec<(Setting, String)>,
    pub sweep: Option<(f64, f64)>,
    /// `[export]`: the plane's pixels and the basins' starts of `E`'s figures.
    pub export_plane: Option<(usize, usize)>,
    pub export_basins: Option<(usize, usize)>,
    pub keymap: Keymap,
}

impl Config {
    /// The config file to read: the explicit path, or the default one if it exists.
    pub fn locate(explicit: Option<&Path>) -> Option<PathBuf> {
        if let Some(p) = explicit {
            return Some(p.to_path_buf());
        }
        let base = std::env::var_os("XDG_CONFIG_HOME")
            .filter(|v| !v.is_empty())
            .map(PathBuf::from)
            .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".config")))?;
        let p = base.join("bouncemap").join("config.toml");
        p.is_file().then_some(p)
    }

    /// Read and check a config file.
    pub fn load(path: &Path) -> Result<Config, String> {
        let text = read_text(path, "config", SMALL_FILE).map_err(|e| e.0)?;
        let mut c = Config::parse(&text).map_err(|e| format!("config {}: {e}", path.display()))?;
        c.path = Some(path.to_path_buf());
        Ok(c)
    }

    /// Parse config text (errors are one line, without the file name).
    pub fn parse(text: &str) -> Result<Config, String> {
        let f: File = toml::from_str(text).map_err(|e| {
            e.to_string()
                .lines()
                .rfind(|l| !l.trim().is_empty())
                .unwrap_or("invalid TOML")
                .trim()
                .to_string()
                + &e.span()
                    .map_or(String::new(), |s| format!(" (at byte {})", s.start))
        })?;
        let mut c = Config::default();
        if let Some(fps) = f.fps {
            rules::FPS
                .check(fps as f64)
                .map_err(|e| format!("fps = {fps}: {e}"))?;
            c.fps = Some(fps);
        }
        if let Some(s) = f.color {
            c.color = Some(ColorChoice::parse(&s).map_err(|e| format!("color: {e}"))?);
        }
        if let Some(s) = f.marker {
            c.marker = Some(Marker::parse(&s).map_err(|e| format!("marker: {e}"))?);
        }
        c.mouse = f.mouse;
        if let Some(d) = f.defaults {
            let mut push = |id, v: Option<String>| {
                if let Some(v) = v {
                    c.defaults.push((Setting::Row(id), v));
                }
            };
            push(ParamId::Table, d.table);
            if let Some(x) = d.d {
                c.defaults.push((Setting::Family("D".into()), shortest(x)));
            }
            for (name, x) in d.params.into_iter().flatten() {
                c.defaults.push((Setting::Family(name), shortest(x)));
            }
            let mut push = |id, v: Option<String>| {
                if let Some(v) = v {
                    c.defaults.push((Setting::Row(id), v));
                }
            };
            push(ParamId::R, d.r.map(shortest));
            push(ParamId::K, d.k.map(|x| x.to_string()));
            push(ParamId::Alpha, d.alpha.map(shortest));
            push(ParamId::T0, d.t0.map(shortest));
            push(ParamId::Start, d.start);
            for (id, v) in [
                (ParamId::V0, d.v0),
                (ParamId::Transient, d.transient),
                (ParamId::Keep, d.keep),
            ] {
                match v {
                    None => {}
                    Some(toml::Value::String(s)) => push(id, Some(s)),
                    Some(toml::Value::Float(x)) => push(id, Some(shortest(x))),
                    Some(toml::Value::Integer(x)) => push(id, Some(x.to_string())),
                    Some(_) => {
                        return Err(format!("defaults.{}: valid {}", key_of(id), id.range()))
                    }
                }
            }
            c.sweep = d.sweep.map(|[a, b]| (a, b));
        }
        if let Some(e) = f.export {
            use crate::config::flags::{parse_grid, parse_plane_size};
            if let Some(t) = e.plane {
                c.export_plane =
                    Some(parse_plane_size(&t).map_err(|e| format!("export.plane: {e}"))?);
            }
            if let Some(t) = e.basins {
                c.export_basins = Some(parse_grid(&t).map_err(|e| format!("export.basins: {e}"))?);
            }
        }
        if let Some(keys) = f.keys {
            let mut config = Vec::new();
            for (name, spec) in keys {
                let action = Action::from_name(&name).ok_or_else(|| {
                    let all: Vec<&str> = Action::ALL.iter().map(|a| a.name()).collect();
                    format!("keys.{name}: not an action; valid {}", all.join(", "))
                })?;
                let list = match spec {
                    OneOrMany::One(s) => vec![s],
                    OneOrMany::Many(v) => v,
                };
                let keys = list
                    .iter()
                    .map(|k| Key::parse(k))
                    .collect::<Result<Vec<_>, _>>()
                    .map_err(|e| format!("keys.{name}: {e}"))?;
                config.push((action, keys));
            }
            c.keymap = Keymap::with(&config)?;
        }
        Ok(c)
    }

    /// Apply the `[defaults]` to a parameter set; the message names the setting.
    pub fn apply_defaults(&self, p: &mut Params) -> Result<(), String> {
        for (setting, text) in &self.defaults {
            let (id, key) = match setting {
                Setting::Row(id) => (*id, key_of(*id).to_string()),
                Setting::Family(name) => {
                    let key = if name == "D" {
                        "d".to_string()
                    } else {
                        format!("params.{name}")
                    };
                    let found = SweepParam::parse(name, &p.table())
                        .ok()
                        .filter(SweepParam::is_table)
                        .and_then(|q| p.row_of(q));
                    let Some(id) = found else {
                        return Err(format!(
                            "defaults.{key}: the table {} has no parameter {name}: its parameters are {}",
                            p.table_label(),
                            p.table().family().map_or("none".into(), |(f, _)| f.param_names())
                        ));
                    };
                    (id, key)
                }
            };
            p.set_text(id, text).map_err(|e| {
                // The message starts with the row's label; the file's key is named instead.
                let detail = e.strip_prefix(&format!("{}: ", p.label(id))).unwrap_or(&e);
                format!("defaults.{key} = {}: {detail}", shown_value(text))
            })?;
        }
        if let Some((lo, hi)) = self.sweep {
            let mut next = p.clone();
            next.lo = lo;
            next.hi = hi;
            let ok = rules::ALPHA.limit.contains(lo)
                && rules::ALPHA.limit.contains(hi)
                && next.validate(ParamId::Lo).is_ok();
            if !ok {
                return Err(format!(
                    "defaults.sweep = [{}, {}]: valid [from, to] with from < to, both in {}",
                    shortest(lo),
                    shortest(hi),
                    rules::ALPHA.limit.text
                ));
            }
            *p = next;
        }
        Ok(())
    }
}

/// A value from the file as a refusal shows it: as written if short, else quoted and
/// cut (the refusal stays one short line).
fn shown_value(text: &str) -> String {
    if text.chars().count() <= crate::output::text::QUOTED_MAX
        && !text.chars().any(char::is_control)
    {
        text.to_string()
    } else {
        crate::output::text::quoted(text)
    }
}

/// The config file's key of a row.
fn key_of(id: ParamId) -> &'static str {
    match id {
        ParamId::Table => "table",
        ParamId::V0 => "v0",
        ParamId::Lo | ParamId::Hi => "sweep",
        ParamId::Start => "start",
        ParamId::Sweep => "param",
        other => other.rule().map_or("", |r| r.key),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};

    #[test]
    fn full_config_parses_and_rebinds_keys() {
        let c = Config::parse(
            r#"
fps = 10
color = "never"
marker = "halfblock"
[defaults]
table = "sine"
alpha = 0.03
r = 0.7
sweep = [0.01, 0.05]
v0 = "auto"
[keys]
step_one = ["s", "F5"]
"#,
        )
        .unwrap();
        assert_eq!(c.fps, Some(10));
        assert_eq!(c.color, Some(ColorChoice::Never));
        assert_eq!(c.marker, Some(Marker::HalfBlock));
        let ev = KeyEvent::new(KeyCode::Char('s'), KeyModifiers::NONE);
        assert_eq!(c.keymap.action(&ev), Some(Action::StepOne));
        let mut p = Params::default();
        c.apply_defaults(&mut p).unwrap();
        assert_eq!(p.table_label(), "sine");
        assert_eq!((p.alpha, p.r, p.lo, p.hi), (0.03, 0.7, 0.01, 0.05));
    }

    #[test]
    fn bad_configs_are_refused_in_one_line_naming_the_setting() {
        for (text, want) in [
            ("fps = 0", "valid a whole number in 1..=60"),
            ("colour = \"256\"", "unknown field"),
            (
                "color = \"rainbow\"",
                "valid auto, never, 16, 256, truecolor",
            ),
            ("[keys]\njump = \"j\"", "keys.jump: not an action"),
            ("[keys]\nquit = \"hyper-q\"", "keys.quit"),
            ("fps = ", "at byte"),
        ] {
            let e = Config::parse(text).unwrap_err();
            assert!(e.contains(want), "{text:?} gave {e:?}");
            assert!(!e.contains('\n'), "{e:?}");
        }
        let c = Config::parse("[defaults]\nalpha = 2000").unwrap();
        let e = c.apply_defaults(&mut Params::default()).unwrap_err();
        assert!(e.contains("(0, 1000]"), "{e}");
        assert!(e.starts_with("defaults.alpha = 2000"), "{e}");
    }
}
