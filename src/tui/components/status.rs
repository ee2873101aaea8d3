//! The status line: the export prompt while a file name is typed; else the current
//! parameters, then the latest message (a refusal naming the valid range, a note) if
//! there is one, else what the panels are computing and key hints taken from the keymap
//! (shortened to fit at 80 columns).

use super::Shared;
use crate::tui::keymap::Action;
use crate::tui::params::fmt_num;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Paragraph, Widget};

/// Draw the status line: `prompt` is the export's file name being typed and what will
/// be added to it, `computing` what the panels are computing (in the registry's order).
pub fn draw(
    app: &Shared,
    prompt: Option<(&str, &str)>,
    computing: &[String],
    area: Rect,
    buf: &mut Buffer,
) {
    let p = &app.params;
    let params = format!(
        " {} α={} r={} k={} ",
        p.table_label(),
        fmt_num(p.alpha),
        fmt_num(p.r),
        p.k
    );
    if let Some((name, added)) = prompt {
        let line = Line::from(vec![
            Span::styled(" export to: ", app.theme.focus()),
            Span::styled(format!("{name}▏"), app.theme.selected()),
            Span::styled(
                format!("  (Enter writes, Esc cancels; {added})"),
                app.theme.dim(),
            ),
        ]);
        Paragraph::new(line).render(area, buf);
        return;
    }
    if let Some((msg, err)) = &app.message {
        // The message has the rest of the line; cut with an ellipsis and the key of
        // the messages overlay (which shows it whole) if it must be.
        let room = (area.width as usize).saturating_sub(params.chars().count() + 2);
        let text: String = if msg.chars().count() > room {
            let more = format!("… ({} more)", app.keymap.hint(Action::Messages));
            let keep = room.saturating_sub(more.chars().count());
            msg.chars().take(keep).collect::<String>() + &more
        } else {
            msg.clone()
        };
        let style = if *err {
            app.theme.error()
        } else {
            app.theme.focus()
        };
        let line = Line::from(vec![
            Span::styled(params, app.theme.selected()),
            Span::styled(format!(" {text}"), style),
        ]);
        Paragraph::new(line).render(area, buf);
        return;
    }
    let work = if app.paused {
        "PAUSED".to_string()
    } else {
        if computing.is_empty() {
            "idle".into()
        } else {
            format!("computing: {}", computing.join(", "))
        }
    };
    let k = |a| app.keymap.hint(a);
    let hints = format!(
        " {} help  {} legend  {} pause  {} panel  {}/{}/{} step  {} presets  {} export  {} quit",
        k(Action::Help),
        k(Action::Legend),
        k(Action::Pause),
        k(Action::NextPanel),
        k(Action::StepOne),
        k(Action::StepTen),
        k(Action::StepBack),
        k(Action::Presets),
        k(Action::Export),
        k(Action::Quit)
    );
    let used = params.chars().count() + work.chars().count() + 3;
    let room = (area.width as usize).saturating_sub(used);
    let short = format!(
        " {}:help {}:legend {}:pause {}:presets {}:quit",
        k(Action::Help),
        k(Action::Legend),
        k(Action::Pause),
        k(Action::Presets),
        k(Action::Quit)
    );
    let hints = if hints.chars().count() <= room {
        hints
    } else if short.chars().count() <= room {
        short
    } else {
        format!(" {}:help {}:quit", k(Action::Help), k(Action::Quit))
    };
    let line = Line::from(vec![
        Span::styled(params, app.theme.selected()),
        Span::styled(
            format!(" {work} "),
            if app.paused {
                app.theme.error()
            } else {
                app.theme.focus()
            },
        ),
        Span::styled("│", app.theme.dim()),
        Span::styled(hints, app.theme.dim()),
    ]);
    Paragraph::new(line).render(area, buf);
}
