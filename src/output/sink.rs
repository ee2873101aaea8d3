//! Where output goes: standard output, or a file written atomically.
//!
//! A file is written to a temporary file in the same directory and renamed into place
//! only when complete ([`Sink::finish`]): an interrupted run, a second process writing
//! the same path, or a failed write leaves whatever was there before untouched and no
//! temporary behind (it is removed when the sink is dropped unfinished, and on SIGTERM,
//! SIGINT or SIGHUP by [`clean_up_on_signals`]). A path that exists and is not a regular
//! file (a device such as /dev/null or /dev/full, a FIFO) is written directly.
//!
//! Exit status: an output that cannot be created (missing directory, no permission) is
//! bad input (the caller reports it with status 2) and is refused before any computing;
//! a write that fails afterwards (a full disk, an I/O error) is status 1. Either way one
//! line names the file.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Temporary files being written, removed if the process is stopped by a signal.
static TEMPORARIES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn register(p: &Path) {
    TEMPORARIES
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .push(p.to_path_buf());
}

fn unregister(p: &Path) {
    TEMPORARIES
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .retain(|q| q != p);
}

/// On SIGTERM, SIGINT or SIGHUP: remove every temporary file being written, then exit
/// with 128 + the signal's number (as a shell expects). For the headless commands.
pub fn clean_up_on_signals() -> io::Result<()> {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let mut signals = signal_hook::iterator::Signals::new([SIGTERM, SIGINT, SIGHUP])?;
    std::thread::Builder::new()
        .name("signals".into())
        .spawn(move || {
            if let Some(sig) = signals.forever().next() {
                for p in TEMPORARIES
                    .lock()
                    .unwrap_or_else(|e| e.into_inner())
                    .drain(..)
                {
                    let _ = std::fs::remove_file(p);
                }
                std::process::exit(128 + sig);
            }
        })?;
    Ok(())
}

/// A file written to a temporary beside it and renamed into place by [`Self::commit`].
pub struct AtomicFile {
    target: PathBuf,
    /// The temporary file; None when the target is written directly (not a regular file).
    temp: Option<PathBuf>,
    out: BufWriter<File>,
}

impl AtomicFile {
    /// Start writing `path`. Refused, with the reason, if its directory is missing or
    /// not writable (bad input: status 2).
    pub fn create(path: &Path) -> Result<AtomicFile, String> {
        let shown = path.display();
        let bad = |e: io::Error| format!("cannot create {shown}: {e}");
        if let Ok(meta) = std::fs::metadata(path) {
            if meta.is_dir() {
                return Err(format!(
                    "cannot create {shown}: it is a directory: valid a file path"
                ));
            }
            if !meta.is_file() {
                // A device or a FIFO: no rename possible, write it as it is.
                let f = std::fs::OpenOptions::new()
                    .write(true)
                    .open(path)
                    .map_err(bad)?;
                return Ok(AtomicFile {
                    target: path.to_path_buf(),
                    temp: None,
                    out: BufWriter::new(f),
                });
            }
        }
        // An existing file is replaced where it really is (through a symlink).
        let target = std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf());
        let dir = match target.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let name = target
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "out".into());
        let mut attempt = 0u32;
        loop {
            let temp = dir.join(format!(".{name}.{}-{attempt}.tmp", std::process::id()));
            match std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(&temp)
            {
                Ok(f) => {
                    register(&temp);
                    return Ok(AtomicFile {
                        target,
                        temp: Some(temp),
                        out: BufWriter::with_capacity(1 << 16, f),
                    });
                }
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists && attempt < 1000 => {
                    attempt += 1;
                }
                Err(e) => return Err(bad(e)),
            }
        }
    }

    /// The file this writes.
    pub fn path(&self) -> &Path {
        &self.target
    }

    /// Flush, sync and rename into place. A failure names the file (status 1) and
    /// leaves the old file as it was.
    pub fn commit(mut self) -> anyhow::Result<()> {
        let shown = self.target.display().to_string();
        let fail = |e: io::Error| anyhow::anyhow!("cannot write {shown}: {e}");
        self.out.flush().map_err(fail)?;
        if let Some(temp) = self.temp.take() {
            let result = self
                .out
                .get_ref()
                .sync_all()
                .and_then(|_| std::fs::rename(&temp, &self.target));
            if let Err(e) = result {
                let _ = std::fs::remove_file(&temp);
                unregister(&temp);
                return Err(fail(e));
            }
            unregister(&temp);
        }
        Ok(())
    }
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.out.write(buf)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.out.flush()
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        if let Some(temp) = self.temp.take() {
            let _ = std::fs::remove_file(&temp);
            unregister(&temp);
        }
    }
}

/// Standard output or an atomically written file.
pub enum Sink {
    Stdout(BufWriter<io::StdoutLock<'static>>),
    File(AtomicFile),
}

impl Sink {
    /// `--out FILE` (created now, so a bad path is refused before any work) or stdout.
    /// A refusal is bad input (status 2).
    pub fn open(out: Option<&str>) -> Result<Sink, String> {
        match out {
            Some(path) => AtomicFile::create(Path::new(path))
                .map(Sink::File)
                .map_err(|e| format!("--out: {e}")),
            None => Ok(Sink::Stdout(BufWriter::with_capacity(
                1 << 16,
                io::stdout().lock(),
            ))),
        }
    }

    /// Flush, and put a file into place. Write errors name the file.
    pub fn finish(self) -> anyhow::Result<()> {
        match self {
            Sink::Stdout(mut o) => Ok(o.flush()?),
            Sink::File(f) => f.commit(),
        }
    }

    /// A write error with the destination named (stdout errors, such as a closed pipe,
    /// pass unchanged).
    pub fn describe(&self, e: anyhow::Error) -> anyhow::Error {
        match self {
            Sink::Stdout(_) => e,
            Sink::File(f) => anyhow::anyhow!("cannot write {}: {e}", f.path().display()),
        }
    }
}

impl Write for Sink {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        match self {
            Sink::Stdout(o) => o.write(buf),
            Sink::File(f) => f.write(buf),
        }
    }

    fn flush(&mut self) -> io::Result<()> {
        match self {
            Sink::Stdout(o) => o.flush(),
            Sink::File(f) => f.flush(),
        }
    }
}

/// The first `PREFIX-N` (N = 1, 2, …) in `dir` for which no `PREFIX-N.EXT` exists for
/// any of `exts` (e.g. ".csv", ".txt").
pub fn free_stem(dir: &Path, prefix: &str, exts: &[&str]) -> String {
    (1..100_000)
        .map(|n| format!("{prefix}-{n}"))
        .find(|stem| {
            exts.iter()
                .all(|e| !dir.join(format!("{stem}{e}")).exists())
        })
        .unwrap_or_else(|| prefix.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("bouncemap-sink-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn a_file_appears_only_when_committed_and_nothing_else_is_left() {
        let d = dir("commit");
        let p = d.join("out.csv");
        std::fs::write(&p, "old\n").unwrap();
        let mut f = AtomicFile::create(&p).unwrap();
        f.write_all(b"new\n").unwrap();
        f.flush().unwrap();
        assert_eq!(
            std::fs::read_to_string(&p).unwrap(),
            "old\n",
            "untouched while writing"
        );
        f.commit().unwrap();
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "new\n");
        assert_eq!(
            std::fs::read_dir(&d).unwrap().count(),
            1,
            "no temporary left"
        );
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn an_abandoned_write_leaves_the_old_file_and_no_temporary() {
        let d = dir("drop");
        let p = d.join("out.csv");
        std::fs::write(&p, "old\n").unwrap();
        {
            let mut f = AtomicFile::create(&p).unwrap();
            f.write_all(b"half").unwrap();
        }
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "old\n");
        assert_eq!(std::fs::read_dir(&d).unwrap().count(), 1);
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn a_missing_directory_is_refused_up_front() {
        let e = AtomicFile::create(Path::new("/nonexistent-dir/x.csv"))
            .err()
            .unwrap();
        assert!(e.contains("/nonexistent-dir/x.csv"), "{e}");
    }

    #[test]
    fn a_device_is_written_directly_and_a_full_one_names_itself() {
        let mut f = AtomicFile::create(Path::new("/dev/full")).unwrap();
        // Buffered: the failure comes when the file is completed.
        f.write_all(b"x,y\n").unwrap();
        let e = f.commit().unwrap_err().to_string();
        assert!(e.starts_with("cannot write /dev/full:"), "{e}");
    }
}
