//! The only place that reads input files (table files, config files, merge parts), and
//! the file `--resume` checks before it is replaced.
//!
//! Only regular files are read, so a FIFO or a device given by mistake (or a symlink to
//! /dev/zero) is refused at once instead of blocking or filling memory, and each read is
//! capped: [`SMALL_FILE`] for tables and configs, [`LARGE_FILE`] for sweep parts. Every
//! input read is noted ([`note_input`]): no output of the run may replace it.
//!
//! Small files are read whole ([`read_text`]). Part files are read as streams
//! ([`InputStream`]): memory holds a buffer, never the file; the same refusals (too
//! large, grown beyond the cap while read, not UTF-8, unreadable) come from
//! [`InputStream::finish`], which reads what the reader left. [`read_again`] reads a
//! stretch of a part a second time (`merge` writes its values from there).

use super::InputError;
use crate::output::sink::note_input;
use std::fs::File;
use std::io::{self, BufRead, BufReader, Read, Seek, SeekFrom};
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

/// The regular file `path` of at most `cap` bytes, opened; `what` names it in refusals.
fn open_capped(path: &Path, what: &str, cap: u64) -> Result<File, InputError> {
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
    File::open(path).map_err(|e| InputError(format!("{what} {shown}: cannot read: {e}")))
}

fn read_capped(path: &Path, what: &str, cap: u64) -> Result<String, InputError> {
    let shown = crate::output::text::shown_path(path);
    let file = open_capped(path, what, cap)?;
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

/// Check that `path` could be opened as an input of at most `cap` bytes (a regular file
/// that exists and is not too large), without reading it; noted as an input.
pub fn check_input(path: &Path, what: &str, cap: u64) -> Result<(), InputError> {
    drop(open_input(path, what, cap)?);
    Ok(())
}

/// The regular file `path` (at most `cap` bytes) as a stream, noted as an input; `what`
/// names it in refusals ("merge: part").
pub fn open_input(path: &Path, what: &str, cap: u64) -> Result<InputStream, InputError> {
    let stream = InputStream::open(path, what, cap)?;
    let name = what.rsplit(": ").next().unwrap_or(what);
    note_input(
        path,
        &format!("the {name} {}", crate::output::text::shown_path(path)),
    );
    Ok(stream)
}

/// The file an output is about to replace (`--resume` checks it) as a stream, opened as
/// [`open_input`] opens an input but not noted as one.
pub fn open_existing_output(path: &Path, what: &str, cap: u64) -> Result<InputStream, InputError> {
    InputStream::open(path, what, cap)
}

/// The first `bytes` bytes of `path` at most, as far as they are UTF-8 (empty if it
/// cannot be read: reading it whole says why).
pub fn head(path: &Path, bytes: u64) -> String {
    let mut head = Vec::new();
    if let Ok(f) = File::open(path) {
        let _ = f.take(bytes).read_to_end(&mut head);
    }
    let valid = match std::str::from_utf8(&head) {
        Ok(_) => head.len(),
        Err(e) => e.valid_up_to(),
    };
    head.truncate(valid);
    String::from_utf8(head).unwrap_or_default()
}

/// The `len` bytes of the regular file `path` from byte `offset`, read again through a
/// buffer of `buffer` bytes (a stretch an [`InputStream`] has already read and checked).
pub fn read_again(
    path: &Path,
    offset: u64,
    len: u64,
    buffer: usize,
) -> io::Result<BufReader<io::Take<File>>> {
    use std::os::unix::fs::OpenOptionsExt;
    // Without waiting: a FIFO put in the part's place is refused, not waited on.
    let mut file = std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(path)?;
    if !file.metadata()?.is_file() {
        return Err(io::Error::other("no longer a regular file"));
    }
    file.seek(SeekFrom::Start(offset))?;
    Ok(BufReader::with_capacity(buffer, file.take(len)))
}

/// Why a stream stopped early.
#[derive(Debug)]
enum Failure {
    Unreadable(io::Error),
    Grew,
    NotUtf8,
}

/// A part file read as a stream through a buffer: at most its cap, UTF-8 checked as it
/// goes. A failure stops it (the reader sees an error); [`Self::finish`] reports it as
/// [`read_text`] would, after reading what was left, so the same file is refused with
/// the same words whether read whole or as a stream.
pub struct InputStream {
    file: File,
    what: String,
    shown: String,
    cap: u64,
    buf: Box<[u8]>,
    pos: usize,
    filled: usize,
    /// Bytes read from the file so far.
    total: u64,
    /// The start of a UTF-8 sequence cut by the end of the last chunk.
    carry: [u8; 4],
    carried: usize,
    failure: Option<Failure>,
}

/// How much of a part file is read at once.
const CHUNK: usize = 1 << 16;

impl InputStream {
    fn open(path: &Path, what: &str, cap: u64) -> Result<InputStream, InputError> {
        Ok(InputStream {
            file: open_capped(path, what, cap)?,
            what: what.to_string(),
            shown: crate::output::text::shown_path(path),
            cap,
            buf: vec![0; CHUNK].into_boxed_slice(),
            pos: 0,
            filled: 0,
            total: 0,
            carry: [0; 4],
            carried: 0,
            failure: None,
        })
    }

    /// The next chunk of the file into the buffer (0 at its end), counted against the
    /// cap and checked as UTF-8 unless `check` is off.
    fn next_chunk(&mut self, check: bool) -> Result<usize, Failure> {
        let n = loop {
            match self.file.read(&mut self.buf) {
                Ok(n) => break n,
                Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
                Err(e) => return Err(Failure::Unreadable(e)),
            }
        };
        self.total += n as u64;
        if self.total > self.cap {
            return Err(Failure::Grew);
        }
        if check && !self.utf8(n) {
            return Err(Failure::NotUtf8);
        }
        Ok(n)
    }

    /// Whether the chunk of `n` bytes in the buffer continues valid UTF-8 (a sequence cut
    /// at its end is carried to the next; at the end of the file, `n` = 0, none may be).
    fn utf8(&mut self, n: usize) -> bool {
        let mut data = &self.buf[..n];
        if n == 0 {
            return self.carried == 0;
        }
        if self.carried > 0 {
            let width = match self.carry[0] {
                0xC0..=0xDF => 2,
                0xE0..=0xEF => 3,
                _ => 4,
            };
            let take = (width - self.carried).min(data.len());
            self.carry[self.carried..self.carried + take].copy_from_slice(&data[..take]);
            self.carried += take;
            data = &data[take..];
            if self.carried < width {
                return true;
            }
            if std::str::from_utf8(&self.carry[..width]).is_err() {
                return false;
            }
            self.carried = 0;
        }
        match std::str::from_utf8(data) {
            Ok(_) => true,
            Err(e) if e.error_len().is_none() => {
                let rest = &data[e.valid_up_to()..];
                self.carry[..rest.len()].copy_from_slice(rest);
                self.carried = rest.len();
                true
            }
            Err(_) => false,
        }
    }

    /// Read what is left (so a file that grew beyond its cap, or is not UTF-8 further
    /// on, is refused as [`read_text`] refuses it), then any failure in one line.
    pub fn finish(mut self) -> Result<(), InputError> {
        while self.failure.is_none() {
            match self.next_chunk(true) {
                Ok(0) => {
                    if !self.utf8(0) {
                        self.failure = Some(Failure::NotUtf8);
                    }
                    break;
                }
                Ok(_) => {}
                Err(f) => self.failure = Some(f),
            }
        }
        // Not UTF-8: still read to the end, where a file that grew is refused first.
        while matches!(self.failure, Some(Failure::NotUtf8)) {
            match self.next_chunk(false) {
                Ok(0) => break,
                Ok(_) => {}
                Err(f) => self.failure = Some(f),
            }
        }
        let (what, shown, cap) = (&self.what, &self.shown, self.cap);
        match self.failure {
            None => Ok(()),
            Some(Failure::Unreadable(e)) => {
                Err(InputError(format!("{what} {shown}: cannot read: {e}")))
            }
            Some(Failure::Grew) => Err(InputError(format!(
                "{what} {shown}: grew beyond {cap} bytes while being read"
            ))),
            Some(Failure::NotUtf8) => Err(InputError(format!(
                "{what} {shown}: not UTF-8 text: valid a text file"
            ))),
        }
    }
}

impl BufRead for InputStream {
    #[inline]
    fn fill_buf(&mut self) -> io::Result<&[u8]> {
        if self.pos == self.filled {
            if self.failure.is_some() {
                return Err(io::Error::other("the file cannot be read further"));
            }
            self.pos = 0;
            self.filled = 0;
            match self.next_chunk(true) {
                Ok(0) if !self.utf8(0) => {
                    self.failure = Some(Failure::NotUtf8);
                    return Err(io::Error::other("not UTF-8"));
                }
                Ok(n) => self.filled = n,
                Err(f) => {
                    self.failure = Some(f);
                    return Err(io::Error::other("the file cannot be read further"));
                }
            }
        }
        Ok(&self.buf[self.pos..self.filled])
    }

    #[inline]
    fn consume(&mut self, n: usize) {
        self.pos = (self.pos + n).min(self.filled);
    }
}

impl Read for InputStream {
    fn read(&mut self, out: &mut [u8]) -> io::Result<usize> {
        let avail = self.fill_buf()?;
        let n = avail.len().min(out.len());
        out[..n].copy_from_slice(&avail[..n]);
        self.consume(n);
        Ok(n)
    }
}
