//! Labels: a small markup for the paper's symbols, the fonts compiled into the crate,
//! and text widths measured with them (for the layout).
//!
//! Markup: `$…$` is math, where Latin letters and lower-case Greek are italic (as in
//! the paper: t̂, α, κ, D) and digits, upper-case Greek (Δ) and signs are upright;
//! inside math `_x` or `_{…}` is a subscript and `^x` or `^{…}` a superscript.
//! Outside math every character is itself. `\$`, `\_`, `\^`, `\{`, `\}` and `\\` are
//! the characters. [`plain`] escapes any text (file names, captions) so nothing in it is
//! read as markup.

use std::sync::OnceLock;

/// DejaVu Sans (Book), for all upright text.
pub const FONT_REGULAR: &[u8] = include_bytes!("../fonts/DejaVuSans.ttf");
/// DejaVu Sans Oblique, for the italic symbols of math.
pub const FONT_OBLIQUE: &[u8] = include_bytes!("../fonts/DejaVuSans-Oblique.ttf");
/// The family both fonts belong to, as the SVG names it.
pub const FAMILY: &str = "DejaVu Sans";
/// DejaVu Sans Mono and its bold, for pictures of the terminal application.
pub const FONT_MONO: &[u8] = include_bytes!("../fonts/DejaVuSansMono.ttf");
/// DejaVu Sans Mono Bold.
pub const FONT_MONO_BOLD: &[u8] = include_bytes!("../fonts/DejaVuSansMono-Bold.ttf");
/// The monospaced family, as the SVG names it.
pub const MONO_FAMILY: &str = "DejaVu Sans Mono";

/// Height of a subscript or superscript, relative to the text around it.
pub const SCRIPT_SCALE: f64 = 0.7;
/// How far a subscript sits below the baseline, in em of the text around it.
pub const SUB_SHIFT: f64 = 0.22;
/// How far a superscript sits above the baseline, in em of the text around it.
pub const SUP_SHIFT: f64 = 0.38;

/// Position of a run relative to the baseline.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Level {
    Base,
    Sub,
    Sup,
}

impl Level {
    /// Size relative to the base text.
    pub fn scale(self) -> f64 {
        match self {
            Level::Base => 1.0,
            Level::Sub | Level::Sup => SCRIPT_SCALE,
        }
    }

    /// Baseline shift downwards, in em of the base text.
    pub fn shift(self) -> f64 {
        match self {
            Level::Base => 0.0,
            Level::Sub => SUB_SHIFT,
            Level::Sup => -SUP_SHIFT,
        }
    }
}

/// A stretch of text with one style.
#[derive(Clone, Debug, PartialEq)]
pub struct Run {
    pub text: String,
    pub italic: bool,
    pub level: Level,
}

/// `text` with every markup character escaped: shown exactly as it is.
pub fn plain(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if matches!(c, '$' | '_' | '^' | '{' | '}' | '\\') {
            out.push('\\');
        }
        out.push(c);
    }
    out
}

fn is_italic(c: char) -> bool {
    c.is_ascii_alphabetic() || ('\u{3b1}'..='\u{3c9}').contains(&c)
}

fn is_mark(c: char) -> bool {
    ('\u{300}'..='\u{36f}').contains(&c)
}

/// The runs of a label in markup.
pub fn parse(markup: &str) -> Vec<Run> {
    let mut runs: Vec<Run> = Vec::new();
    let mut push = |c: char, italic: bool, level: Level| match runs.last_mut() {
        Some(r) if r.italic == italic && r.level == level => r.text.push(c),
        _ => runs.push(Run {
            text: c.to_string(),
            italic,
            level,
        }),
    };
    let chars: Vec<char> = markup.chars().collect();
    let (mut math, mut i) = (false, 0);
    // Inside a script: its level and whether it is a group `{…}` (else one character).
    let mut script: Option<(Level, bool)> = None;
    let mut last_italic = false;
    while i < chars.len() {
        let c = chars[i];
        i += 1;
        let level = script.map_or(Level::Base, |s| s.0);
        let literal = if c == '\\' && i < chars.len() {
            i += 1;
            Some(chars[i - 1])
        } else {
            None
        };
        match (literal, c) {
            (None, '$') => {
                math = !math;
                continue;
            }
            (None, '_' | '^') if math && script.is_none() => {
                let level = if c == '_' { Level::Sub } else { Level::Sup };
                let group = chars.get(i) == Some(&'{');
                if group {
                    i += 1;
                }
                script = Some((level, group));
                continue;
            }
            (None, '}') if matches!(script, Some((_, true))) => {
                script = None;
                continue;
            }
            _ => {}
        }
        let ch = literal.unwrap_or(c);
        // A combining mark takes the style of the letter it sits on.
        let italic = if is_mark(ch) {
            last_italic
        } else {
            math && is_italic(ch)
        };
        last_italic = italic;
        push(ch, italic, level);
        if let Some((_, false)) = script {
            // A one-character script ends here, with any marks on it.
            if !chars.get(i).is_some_and(|n| is_mark(*n)) {
                script = None;
            }
        }
    }
    runs
}

/// The fonts, parsed once.
struct Faces {
    regular: ttf_parser::Face<'static>,
    oblique: ttf_parser::Face<'static>,
}

fn faces() -> &'static Faces {
    static FACES: OnceLock<Faces> = OnceLock::new();
    FACES.get_or_init(|| Faces {
        regular: ttf_parser::Face::parse(FONT_REGULAR, 0).expect("the compiled-in font parses"),
        oblique: ttf_parser::Face::parse(FONT_OBLIQUE, 0).expect("the compiled-in font parses"),
    })
}

/// Advance width of `text` in one face at `size`.
fn advance(face: &ttf_parser::Face, text: &str, size: f64) -> f64 {
    let em = face.units_per_em() as f64;
    text.chars()
        .map(|c| {
            face.glyph_index(c)
                .and_then(|g| face.glyph_hor_advance(g))
                .map_or(if is_mark(c) { 0.0 } else { 0.6 * em }, |a| a as f64)
        })
        .sum::<f64>()
        * size
        / em
}

/// Width of a label in markup at font size `size` (the same unit as the result).
pub fn width(markup: &str, size: f64) -> f64 {
    runs_width(&parse(markup), size)
}

/// Width of parsed runs at font size `size`.
pub fn runs_width(runs: &[Run], size: f64) -> f64 {
    let f = faces();
    runs.iter()
        .map(|r| {
            let face = if r.italic { &f.oblique } else { &f.regular };
            advance(face, &r.text, size * r.level.scale())
        })
        .sum()
}

/// Height above the baseline of a capital letter, in em.
pub const CAP_HEIGHT: f64 = 0.73;

/// Greedy word wrap of plain (already escaped or markup) text to lines no wider than
/// `max` at `size`.
pub fn wrap(markup: &str, size: f64, max: f64) -> Vec<String> {
    let mut lines = Vec::new();
    let mut line = String::new();
    // A relation or an operation stays on one line with its neighbours: "r = 0.8".
    let glue = |w: &str| matches!(w, "=" | "+" | "\u{2212}" | "\u{b7}" | "\u{d7}");
    let mut words: Vec<String> = Vec::new();
    let mut join_next = false;
    for w in markup.split(' ') {
        match words.last_mut() {
            Some(last) if join_next || glue(w) => {
                last.push(' ');
                last.push_str(w);
            }
            _ => words.push(w.to_string()),
        }
        join_next = glue(w);
    }
    for word in &words {
        let candidate = if line.is_empty() {
            word.to_string()
        } else {
            format!("{line} {word}")
        };
        if !line.is_empty() && width(&candidate, size) > max {
            lines.push(std::mem::take(&mut line));
            line = word.clone();
        } else {
            line = candidate;
        }
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    fn show(runs: &[Run]) -> Vec<(String, bool, Level)> {
        runs.iter()
            .map(|r| (r.text.clone(), r.italic, r.level))
            .collect()
    }

    #[test]
    fn math_letters_are_italic_and_scripts_are_scripts() {
        let r = parse("log$_{10}$ $\u{394}\u{3ba}$");
        assert_eq!(
            show(&r),
            vec![
                ("log".into(), false, Level::Base),
                ("10".into(), false, Level::Sub),
                (" \u{394}".into(), false, Level::Base),
                ("\u{3ba}".into(), true, Level::Base),
            ]
        );
        // A one-character subscript, and a hat that stays on its letter.
        let r = parse("$b_T$ $t\u{302}$");
        assert_eq!(
            show(&r),
            vec![
                ("b".into(), true, Level::Base),
                ("T".into(), true, Level::Sub),
                (" ".into(), false, Level::Base),
                ("t\u{302}".into(), true, Level::Base),
            ]
        );
    }

    #[test]
    fn plain_text_is_shown_as_it_is() {
        let name = "my_table$1^{x}\\.toml";
        let r = parse(&plain(name));
        assert_eq!(r.len(), 1);
        assert_eq!(r[0].text, name);
        assert!(!r[0].italic);
    }

    #[test]
    fn widths_come_from_the_font() {
        // DejaVu Sans: 'm' is wider than 'i'; a combining mark takes no room.
        assert!(width("m", 10.0) > 2.0 * width("i", 10.0));
        assert_eq!(width("$t\u{302}$", 10.0), width("$t$", 10.0));
        assert!((width("mm", 20.0) - 4.0 * width("m", 10.0)).abs() < 1e-9);
    }

    #[test]
    fn wrapping_keeps_lines_within_the_width() {
        let text = "one two three four five six seven eight nine ten eleven twelve";
        let lines = wrap(text, 8.0, 60.0);
        assert!(lines.len() > 2);
        assert!(lines
            .iter()
            .all(|l| width(l, 8.0) <= 60.0 || !l.contains(' ')));
        assert_eq!(lines.join(" "), text);
        // "r = 0.8" is never cut.
        let text = "aaaa bbbb cccc r = 0.8 dddd";
        for max in [10.0, 40.0, 60.0, 80.0] {
            let lines = wrap(text, 8.0, max);
            assert!(lines.iter().any(|l| l.contains("r = 0.8")), "{lines:?}");
        }
    }
}
