//! How pictures are shown: the colour choice (`--color`, `color =` in the config file).
//! The glyphs (`--marker`) are [`crate::output::hitgrid::Marker`].

use crate::output::text::quoted;
use std::fmt;

/// How many colours the terminal is assumed to have.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ColorMode {
    None,
    Ansi16,
    Ansi256,
    TrueColor,
}

/// The `--color` choice before `auto` is resolved.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ColorChoice {
    #[default]
    Auto,
    Never,
    Ansi16,
    Ansi256,
    TrueColor,
}

impl ColorChoice {
    /// Parse `auto | never | 16 | 256 | truecolor`.
    pub fn parse(s: &str) -> Result<ColorChoice, String> {
        match s.trim() {
            "auto" => Ok(ColorChoice::Auto),
            "never" | "none" => Ok(ColorChoice::Never),
            "16" => Ok(ColorChoice::Ansi16),
            "256" => Ok(ColorChoice::Ansi256),
            "truecolor" | "24bit" => Ok(ColorChoice::TrueColor),
            _ => Err(format!(
                "{} is not a colour mode: valid auto, never, 16, 256, truecolor",
                quoted(s)
            )),
        }
    }

    /// Resolve `auto`: NO_COLOR (set and non-empty) means none, else 256 colours
    /// (COLORTERM does not cross ssh).
    pub fn resolve(self, no_color_env: Option<&str>) -> ColorMode {
        match self {
            ColorChoice::Auto => match no_color_env {
                Some(v) if !v.is_empty() => ColorMode::None,
                _ => ColorMode::Ansi256,
            },
            ColorChoice::Never => ColorMode::None,
            ColorChoice::Ansi16 => ColorMode::Ansi16,
            ColorChoice::Ansi256 => ColorMode::Ansi256,
            ColorChoice::TrueColor => ColorMode::TrueColor,
        }
    }
}

impl fmt::Display for ColorChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            ColorChoice::Auto => "auto",
            ColorChoice::Never => "never",
            ColorChoice::Ansi16 => "16",
            ColorChoice::Ansi256 => "256",
            ColorChoice::TrueColor => "truecolor",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn auto_honours_no_color_and_defaults_to_256() {
        assert_eq!(ColorChoice::Auto.resolve(Some("1")), ColorMode::None);
        assert_eq!(ColorChoice::Auto.resolve(Some("")), ColorMode::Ansi256);
        assert_eq!(ColorChoice::Auto.resolve(None), ColorMode::Ansi256);
        assert_eq!(
            ColorChoice::TrueColor.resolve(Some("1")),
            ColorMode::TrueColor
        );
    }

    #[test]
    fn parse_rejects_unknown_modes_with_the_valid_list() {
        assert_eq!(ColorChoice::parse("256"), Ok(ColorChoice::Ansi256));
        let e = ColorChoice::parse("rainbow").unwrap_err();
        assert!(e.contains("valid auto, never, 16, 256, truecolor"), "{e}");
    }
}
