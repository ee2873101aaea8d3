//! Colour modes and the styles every panel draws with. `--color auto` honours NO_COLOR
//! and otherwise picks 256 colours (COLORTERM does not cross ssh); `never` draws with
//! modifiers only, so density and highlights stay readable without colour.

use ratatui::style::{Color, Modifier, Style};
use std::fmt;
use std::str::FromStr;

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

impl FromStr for ColorChoice {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.trim() {
            "auto" => Ok(ColorChoice::Auto),
            "never" | "none" => Ok(ColorChoice::Never),
            "16" => Ok(ColorChoice::Ansi16),
            "256" => Ok(ColorChoice::Ansi256),
            "truecolor" | "24bit" => Ok(ColorChoice::TrueColor),
            _ => Err(format!(
                "'{s}' is not a colour mode: valid auto, never, 16, 256, truecolor"
            )),
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

impl ColorChoice {
    /// Resolve `auto`: NO_COLOR (set and non-empty) means none, else 256 colours.
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

/// Styles for one colour mode.
#[derive(Clone, Debug)]
pub struct Theme {
    pub mode: ColorMode,
}

impl Theme {
    pub fn new(mode: ColorMode) -> Theme {
        Theme { mode }
    }

    fn pick(&self, c16: Color, c256: u8, rgb: (u8, u8, u8)) -> Option<Color> {
        match self.mode {
            ColorMode::None => None,
            ColorMode::Ansi16 => Some(c16),
            ColorMode::Ansi256 => Some(Color::Indexed(c256)),
            ColorMode::TrueColor => Some(Color::Rgb(rgb.0, rgb.1, rgb.2)),
        }
    }

    fn fg(&self, c16: Color, c256: u8, rgb: (u8, u8, u8)) -> Style {
        match self.pick(c16, c256, rgb) {
            Some(c) => Style::new().fg(c),
            None => Style::new(),
        }
    }

    /// Density shading for hit counts, `level` in 0..4 (sparse to dense). Without
    /// colour the levels are dim, normal, normal, bold.
    pub fn density(&self, level: usize) -> Style {
        let s = match level.min(3) {
            0 => self.fg(Color::Blue, 61, (72, 40, 120)),
            1 => self.fg(Color::Cyan, 38, (38, 130, 142)),
            2 => self.fg(Color::Green, 78, (53, 183, 121)),
            _ => self.fg(Color::Yellow, 226, (253, 231, 37)),
        };
        if self.mode == ColorMode::None {
            match level {
                0 => s.add_modifier(Modifier::DIM),
                3.. => s.add_modifier(Modifier::BOLD),
                _ => s,
            }
        } else {
            s
        }
    }

    /// Recent points of the phase plot.
    pub fn recent(&self) -> Style {
        self.fg(Color::LightRed, 203, (255, 95, 95))
            .add_modifier(Modifier::BOLD)
    }

    /// The cursor line of the diagram (current α or zoom cursor).
    pub fn cursor(&self) -> Style {
        self.fg(Color::Magenta, 170, (215, 95, 215))
    }

    /// Marks of analytic values (birth, α_PD, fixed points).
    pub fn mark(&self) -> Style {
        self.fg(Color::LightRed, 196, (255, 60, 60))
            .add_modifier(Modifier::BOLD)
    }

    /// A second kind of mark (the (2, 2k) solution, the window being marked).
    pub fn mark2(&self) -> Style {
        self.fg(Color::LightGreen, 82, (95, 255, 95))
            .add_modifier(Modifier::BOLD)
    }

    /// Stable region and band.
    pub fn stable(&self) -> Style {
        match self.mode {
            ColorMode::None => Style::new(),
            _ => self.fg(Color::Green, 71, (95, 175, 95)),
        }
    }

    /// Axes, tick labels, borders of unfocused panels.
    pub fn axis(&self) -> Style {
        self.fg(Color::Gray, 245, (138, 138, 138))
    }

    /// Titles and the border of the focused panel.
    pub fn focus(&self) -> Style {
        self.fg(Color::LightCyan, 117, (135, 215, 255))
            .add_modifier(Modifier::BOLD)
    }

    /// The selected parameter row.
    pub fn selected(&self) -> Style {
        Style::new().add_modifier(Modifier::REVERSED)
    }

    /// Inline refusals and errors.
    pub fn error(&self) -> Style {
        self.fg(Color::LightRed, 203, (255, 95, 95))
            .add_modifier(Modifier::BOLD)
    }

    /// Secondary text.
    pub fn dim(&self) -> Style {
        match self.mode {
            ColorMode::None => Style::new().add_modifier(Modifier::DIM),
            _ => self.fg(Color::DarkGray, 243, (118, 118, 118)),
        }
    }

    /// The table curve in the bounce panel.
    pub fn table_curve(&self) -> Style {
        self.fg(Color::Yellow, 179, (215, 175, 95))
    }

    /// The ball's flight in the bounce panel.
    pub fn ball(&self) -> Style {
        self.fg(Color::LightCyan, 81, (95, 215, 255))
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
        assert_eq!("256".parse::<ColorChoice>(), Ok(ColorChoice::Ansi256));
        let e = "rainbow".parse::<ColorChoice>().unwrap_err();
        assert!(e.contains("valid auto, never, 16, 256, truecolor"), "{e}");
    }

    #[test]
    fn no_color_theme_uses_no_colours() {
        let t = Theme::new(ColorMode::None);
        for l in 0..4 {
            assert_eq!(t.density(l).fg, None);
        }
        assert!(t.density(3).add_modifier.contains(Modifier::BOLD));
    }
}
