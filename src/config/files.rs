//! The only place that reads input files (table files, config files, merge parts), and
//! the file `--resume` checks before it is replaced.
//!
//! Only regular files are read, so a FIFO or a device given by mistake (or a symlink to
//! /dev/zero) is refused at once instead of blocking or filling memory, and each read is
//! capped: [`SMALL_FILE`] for tables and configs, [`LARGE_FILE`] for sweep parts. Every
//! input read is noted ([`note_input`]): no output of the run may replace it.

use super::InputError;
use crate::output::sink::note_input;
use std::io::Read;
use std::path::Path;

/// Largest table or config file read, in bytes.
pub const SMALL_FILE: u64 = 1 << 20;
/// Largest sweep part file read by `merge`, in bytes.
pub const LARGE_FILE: u64 = 8 << 30;

/// The text of the regular file `path`, at most `cap` bytes. `what` names the file in
/// refusals ("table file", "config", "merge part").
pub fn read_text(path: &Path, what: &str, cap: u64) -> Result<String, InputError> {
    let text = read_capped(path, what, cap)?;
    let name = what.rsplit(": ").next().unwrap_or(what);
    note_input(
        path,
        &format!("the {name} {}", crate::output::text::shown_path(path)),
    );
    Ok(text)
}

/// The text of the file an output is about to replace (`--resume` checks it), read as
/// [`read_text`] reads an input but not noted as one.
pub fn read_existing_output(path: &Path, what: &str, cap: u64) -> Result<String, InputError> {
    read_capped(path, what, cap)
}

fn read_capped(path: &Path, what: &str, cap: u64) -> Result<String, InputError> {
    let shown = crate::output::text::shown_path(path);
    let meta = std::fs::metadata(path)
        .map_err(|e| InputError(format!("{what} {shown}: cannot read: {e}")))?;
    if !meta.is_file() {
        return Err(InputError(format!(
            "{what} {shown}: not a regular file: valid a file (not a directory, FIFO or device)"
        )));
    }
    if meta.len() > cap {
        return Err(InputError(format!(
            "{what} {shown}: {} bytes is too large: valid at most {cap} bytes",
            meta.len()
        )));
    }
    let file = std::fs::File::open(path)
        .map_err(|e| InputError(format!("{what} {shown}: cannot read: {e}")))?;
    let mut bytes = Vec::new();
    file.take(cap + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| InputError(format!("{what} {shown}: cannot read: {e}")))?;
    if bytes.len() as u64 > cap {
        return Err(InputError(format!(
            "{what} {shown}: grew beyond {cap} bytes while being read"
        )));
    }
    String::from_utf8(bytes)
        .map_err(|_| InputError(format!("{what} {shown}: not UTF-8 text: valid a text file")))
}
