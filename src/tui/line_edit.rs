//! One typed line, as the parameter editor and the export prompt take it: characters
//! are added, Backspace removes one, Ctrl-U clears the line, Ctrl-W removes the last
//! word, Enter commits and Esc cancels. Any other key with Ctrl or Alt is ignored (it
//! never types its letter).

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};

/// What a key did to the line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Edit {
    /// The line changed (or the key was ignored): keep typing.
    Typing,
    /// Enter: the line is done.
    Commit,
    /// Esc: the line is abandoned.
    Cancel,
}

/// Apply `key` to `line`, which holds at most `max` characters.
pub fn edit(line: &mut String, key: KeyEvent, max: usize) -> Edit {
    let ctrl = key.modifiers.contains(KeyModifiers::CONTROL);
    let alt = key.modifiers.contains(KeyModifiers::ALT);
    match key.code {
        KeyCode::Enter => return Edit::Commit,
        KeyCode::Esc => return Edit::Cancel,
        KeyCode::Backspace => {
            line.pop();
        }
        KeyCode::Char('u') if ctrl => line.clear(),
        KeyCode::Char('h') if ctrl => {
            line.pop();
        }
        KeyCode::Char('w') if ctrl => {
            let kept = line.trim_end().len();
            line.truncate(kept);
            let start = line
                .char_indices()
                .rev()
                .find(|(_, c)| c.is_whitespace() || matches!(c, '/' | '.' | '-' | '_'))
                .map_or(0, |(i, c)| i + c.len_utf8());
            line.truncate(start);
        }
        KeyCode::Char(c) if !ctrl && !alt && !c.is_control() && line.chars().count() < max => {
            line.push(c)
        }
        _ => {}
    }
    Edit::Typing
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(code: KeyCode, m: KeyModifiers) -> KeyEvent {
        KeyEvent::new(code, m)
    }

    #[test]
    fn control_keys_edit_and_never_type_their_letter() {
        let mut s = String::new();
        for c in "view-2".chars() {
            edit(&mut s, KeyCode::Char(c).into(), 10);
        }
        assert_eq!(s, "view-2");
        edit(&mut s, key(KeyCode::Char('w'), KeyModifiers::CONTROL), 10);
        assert_eq!(s, "view-");
        edit(&mut s, key(KeyCode::Char('u'), KeyModifiers::CONTROL), 10);
        assert_eq!(s, "");
        edit(&mut s, key(KeyCode::Char('x'), KeyModifiers::ALT), 10);
        edit(&mut s, key(KeyCode::Char('k'), KeyModifiers::CONTROL), 10);
        assert_eq!(s, "");
        for c in "abcdefghijkl".chars() {
            edit(&mut s, KeyCode::Char(c).into(), 10);
        }
        assert_eq!(s, "abcdefghij", "at most max characters");
        assert_eq!(edit(&mut s, KeyCode::Enter.into(), 10), Edit::Commit);
        assert_eq!(edit(&mut s, KeyCode::Esc.into(), 10), Edit::Cancel);
        // Shift only changes the character typed.
        let mut t = String::new();
        edit(&mut t, key(KeyCode::Char('E'), KeyModifiers::SHIFT), 10);
        assert_eq!(t, "E");
    }
}
