//! The styles every panel draws with, per colour mode ([`ColorMode`], resolved from
//! `--color`); without colour they use modifiers only, so density and highlights stay
//! readable.

use crate::config::display::ColorMode;
use crate::output::classes::Class;
use bouncemap_figures::classes as attractor_palette;
use ratatui::style::{Color, Modifier, Style};

/// The attractors' colours among the 16 system colours: the nearest hue of each of the
/// figures' palette ([`attractor_palette::PALETTE`]: blue, orange, green, red, purple,
/// brown, pink, light blue).
const ATTRACTOR_16: [Color; 8] = [
    Color::LightBlue,
    Color::Yellow,
    Color::Green,
    Color::Red,
    Color::Magenta,
    Color::LightYellow,
    Color::LightMagenta,
    Color::Cyan,
];

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

    /// A line's style where it crosses data: its own colour, or reverse video without
    /// colour (a dim or bold cell alone would vanish in a dense region).
    pub fn over_data(&self, style: Style) -> Style {
        if self.mode == ColorMode::None {
            Style::new().add_modifier(Modifier::REVERSED)
        } else {
            style
        }
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

    /// A class of orbit in the diagram: the one palette of figures and screen
    /// ([`Class::rgb`] in truecolour, [`Class::ansi256`] in 256 colours; the system
    /// colour of the nearest hue in 16). Without colour the classes differ by
    /// modifiers: period 1 bold, 2 plain, 4 underlined, 8 underlined bold, other cycles
    /// italic, sticking bold italic (dim where its length is beyond double precision),
    /// chaos dim, unresolved dim italic.
    pub fn class(&self, c: Class) -> Style {
        if self.mode == ColorMode::None {
            let m = match c {
                Class::Period1 => Modifier::BOLD,
                Class::Period2 => Modifier::empty(),
                Class::Period4 => Modifier::UNDERLINED,
                Class::Period8 => Modifier::UNDERLINED | Modifier::BOLD,
                Class::Periodic => Modifier::ITALIC,
                Class::Sticking => Modifier::BOLD | Modifier::ITALIC,
                Class::StickingUnresolved => Modifier::BOLD | Modifier::ITALIC | Modifier::DIM,
                Class::Chaotic => Modifier::DIM,
                Class::Unresolved => Modifier::DIM | Modifier::ITALIC,
            };
            return Style::new().add_modifier(m);
        }
        let c16 = match c {
            Class::Period1 => Color::LightCyan,
            Class::Period2 => Color::Yellow,
            Class::Period4 => Color::Green,
            Class::Period8 => Color::Red,
            Class::Periodic => Color::Magenta,
            Class::Sticking => Color::Blue,
            Class::StickingUnresolved => Color::LightBlue,
            Class::Chaotic => Color::Gray,
            Class::Unresolved => Color::LightYellow,
        };
        self.fg(c16, c.ansi256(), c.rgb())
    }

    /// The colour of attractor number `n` (0-based) in the basins panel and the
    /// all-attractors diagram: the figures' palette ([`attractor_palette`]); None
    /// without colour.
    pub fn attractor_color(&self, n: usize) -> Option<Color> {
        let bouncemap_figures::Color(r, g, b) = attractor_palette::attractor_colour(n + 1);
        let i = n % ATTRACTOR_16.len();
        self.pick(
            ATTRACTOR_16[i],
            crate::output::classes::nearest_xterm((r, g, b)),
            (r, g, b),
        )
    }

    /// Attractor number `n` (0-based): its colour, or without colour a modifier
    /// (bold, plain, underlined, italic, reversed, dim).
    pub fn attractor(&self, n: usize) -> Style {
        match self.attractor_color(n) {
            Some(c) => Style::new().fg(c),
            None => {
                const M: [Modifier; 6] = [
                    Modifier::BOLD,
                    Modifier::empty(),
                    Modifier::UNDERLINED,
                    Modifier::ITALIC,
                    Modifier::REVERSED,
                    Modifier::DIM,
                ];
                Style::new().add_modifier(M[n % M.len()])
            }
        }
    }

    /// Resting and escaping starts in the basins panel: the figures' colour for them.
    pub fn nowhere(&self) -> Option<Color> {
        let bouncemap_figures::Color(r, g, b) = attractor_palette::REST;
        self.pick(
            Color::DarkGray,
            crate::output::classes::nearest_xterm((r, g, b)),
            (r, g, b),
        )
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
    fn attractors_have_the_figures_colours() {
        assert_eq!(ATTRACTOR_16.len(), attractor_palette::PALETTE.len());
        let t = Theme::new(ColorMode::TrueColor);
        for n in 0..10 {
            let bouncemap_figures::Color(r, g, b) = attractor_palette::attractor_colour(n + 1);
            assert_eq!(t.attractor_color(n), Some(Color::Rgb(r, g, b)));
        }
        let c = Class::Chaotic.rgb();
        assert_eq!(t.class(Class::Chaotic).fg, Some(Color::Rgb(c.0, c.1, c.2)));
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
