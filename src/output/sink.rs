//! The one output layer: standard output, or a file written atomically, and the rules
//! every command's output follows.
//!
//! * A file is written to a temporary file in the same directory and renamed into place
//!   only when complete ([`Sink::finish`]): an interrupted run, a second process writing
//!   the same path, or a failed write leaves whatever was there before untouched and no
//!   temporary behind (it is removed when the sink is dropped unfinished, and on every
//!   signal that ends the process by [`clean_up_on_signals`]). A path that exists and is
//!   not a regular file (a device such as /dev/null or /dev/full, a FIFO) is written
//!   directly.
//! * The `--out` rule ([`AtomicFile::create`]): an output is never a file this run read
//!   (the input files noted by [`note_input`], compared as files, so a symlink, a hard
//!   link or `./a` is the same file) nor another output of this run; it is created (and
//!   so checked writable) before any work starts.
//! * Standard output ([`Sink::stdout`]): a reader that goes away (`| head`) ends the
//!   run quietly, status 0 and nothing on stderr ([`is_closed_output`]); a long
//!   computation notices it between its batches ([`check_stdout`]) instead of at its
//!   next write. Any other write error (`> /dev/full`) is reported and fails the run.
//!
//! Exit status: an output that cannot be created (missing directory, no permission, an
//! input of the run) is bad input (the caller reports it with status 2) and is refused
//! before any computing; a write that fails afterwards (a full disk, an I/O error) is
//! status 1. Either way one line names the file (or standard output).

use super::text::shown_path;
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;

/// Temporary files being written, removed if the process is stopped by a signal.
static TEMPORARIES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// The files this run read (device and inode, and the name it was given by), which no
/// output may replace.
static INPUTS: Mutex<Vec<(u64, u64, String)>> = Mutex::new(Vec::new());

/// The files this run writes (where they really are), none of which may be written twice.
static OUTPUTS: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Whether this run's results go to standard output.
static STDOUT_IS_OUTPUT: AtomicBool = AtomicBool::new(false);

fn unregister(p: &Path) {
    TEMPORARIES
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .retain(|q| q != p);
}

/// Note that this run reads `path` (shown as `shown` in refusals): no output may
/// replace it. Called by the one reader of input files.
pub fn note_input(path: &Path, shown: &str) {
    use std::os::unix::fs::MetadataExt;
    if let Ok(m) = std::fs::metadata(path) {
        INPUTS.lock().unwrap_or_else(|e| e.into_inner()).push((
            m.dev(),
            m.ino(),
            shown.to_string(),
        ));
    }
}

/// The input `path` is the same file as, if any.
fn input_at(path: &Path) -> Option<String> {
    use std::os::unix::fs::MetadataExt;
    let m = std::fs::metadata(path).ok()?;
    INPUTS
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .iter()
        .find(|(dev, ino, _)| *dev == m.dev() && *ino == m.ino())
        .map(|(.., shown)| shown.clone())
}

/// Where `path` really is: its directory resolved (symlinks, `.`, `..`), then the file
/// itself if it is a symlink.
fn real_path(path: &Path) -> PathBuf {
    if let Ok(p) = std::fs::canonicalize(path) {
        return p;
    }
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    match (std::fs::canonicalize(dir), path.file_name()) {
        (Ok(d), Some(n)) => d.join(n),
        _ => path.to_path_buf(),
    }
}

/// On any signal that ends the process: remove every temporary file being written,
/// then end as that signal asks: SIGTERM, SIGINT or SIGHUP exit with 128 + the signal's
/// number (as a shell expects), every other one ([`super::signals::ending`]: SIGQUIT,
/// SIGUSR1, ...) by its default action. For the headless commands.
pub fn clean_up_on_signals() -> io::Result<()> {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let mut signals = signal_hook::iterator::Signals::new([SIGTERM, SIGINT, SIGHUP])?;
    // Each of the others where it can be caught (a tool the program runs under, such as
    // valgrind, may keep a real-time signal for itself).
    for sig in super::signals::ending() {
        let _ = signals.add_signal(sig);
    }
    std::thread::Builder::new()
        .name("signals".into())
        .spawn(move || {
            if let Some(sig) = signals.forever().next() {
                // The lock is held until the process ends, so no temporary is created
                // after these are removed.
                let mut temporaries = TEMPORARIES.lock().unwrap_or_else(|e| e.into_inner());
                for p in temporaries.drain(..) {
                    let _ = std::fs::remove_file(p);
                }
                if [SIGTERM, SIGINT, SIGHUP].contains(&sig) {
                    std::process::exit(128 + sig);
                }
                super::signals::die_by(sig);
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
    /// Where the file really is, held as an output of this run until it is dropped.
    claimed: Option<PathBuf>,
    out: BufWriter<File>,
}

impl AtomicFile {
    /// Start writing `path`. Refused, with the reason, if its directory is missing or
    /// not writable, if it is a file this run reads or another output of this run, or
    /// if it is a FIFO nobody reads (bad input: status 2).
    pub fn create(path: &Path) -> Result<AtomicFile, String> {
        use std::os::unix::fs::{FileTypeExt, OpenOptionsExt};
        if path.as_os_str().is_empty() {
            return Err("an empty path: valid a file path".into());
        }
        let shown = shown_path(path);
        let bad = |e: io::Error| format!("cannot create {shown}: {e}");
        if let Ok(meta) = std::fs::metadata(path) {
            if meta.is_dir() {
                return Err(format!(
                    "cannot create {shown}: it is a directory: valid a file path"
                ));
            }
            if !meta.is_file() {
                // A device or a FIFO: no rename possible, write it as it is. A FIFO is
                // opened without waiting: one that nobody reads is refused, not waited on.
                let fifo = meta.file_type().is_fifo();
                let f = std::fs::OpenOptions::new()
                    .write(true)
                    .custom_flags(if fifo { libc::O_NONBLOCK } else { 0 })
                    .open(path)
                    .map_err(|e| {
                        if e.raw_os_error() == Some(libc::ENXIO) {
                            format!("cannot create {shown}: a FIFO that nobody reads: valid a file, or a FIFO with a reader")
                        } else {
                            bad(e)
                        }
                    })?;
                if fifo {
                    use std::os::fd::AsRawFd;
                    // Writes wait for the reader again.
                    unsafe {
                        let fd = f.as_raw_fd();
                        let flags = libc::fcntl(fd, libc::F_GETFL);
                        libc::fcntl(fd, libc::F_SETFL, flags & !libc::O_NONBLOCK);
                    }
                }
                return Ok(AtomicFile {
                    target: path.to_path_buf(),
                    temp: None,
                    claimed: None,
                    out: BufWriter::new(f),
                });
            }
            if let Some(input) = input_at(path) {
                return Err(format!(
                    "{shown}: it is {input}, an input of this run: valid a file that is none of its inputs"
                ));
            }
            if !writable(path) {
                return Err(format!(
                    "cannot replace {shown}: it is read-only for this user: valid a file you may write (or a new path)"
                ));
            }
        }
        let real = real_path(path);
        {
            let mut outputs = OUTPUTS.lock().unwrap_or_else(|e| e.into_inner());
            if outputs.contains(&real) {
                return Err(format!(
                    "{shown} is already an output of this run: valid a file of its own for each output"
                ));
            }
            outputs.push(real.clone());
        }
        let mut claim = Claim(Some(real));
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
            // Created and registered under the lock the signal handler takes first: a
            // signal between the two would otherwise leave the file behind.
            let mut temporaries = TEMPORARIES.lock().unwrap_or_else(|e| e.into_inner());
            let created = std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(&temp);
            if created.is_ok() {
                temporaries.push(temp.clone());
            }
            drop(temporaries);
            match created {
                Ok(f) => {
                    // A file replaced keeps its permissions; a new one gets the umask's.
                    if let Ok(meta) = std::fs::metadata(&target) {
                        let _ = f.set_permissions(meta.permissions());
                    }
                    return Ok(AtomicFile {
                        target,
                        temp: Some(temp),
                        claimed: claim.0.take(),
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
    pub fn commit(self) -> anyhow::Result<()> {
        Self::commit_all(vec![self])
    }

    /// Put several files of one run into place together: every one is flushed and
    /// synced first, and only when all of them are complete are they renamed. A
    /// failure (a full disk while finishing any of them) names the file and leaves
    /// every old file as it was.
    pub fn commit_all(mut files: Vec<AtomicFile>) -> anyhow::Result<()> {
        for f in &mut files {
            f.complete()?;
        }
        for f in &mut files {
            f.place()?;
        }
        Ok(())
    }

    /// Flush and sync the temporary (or flush a file written directly).
    fn complete(&mut self) -> anyhow::Result<()> {
        let shown = shown_path(&self.target);
        let fail = |e: io::Error| anyhow::anyhow!("cannot write {shown}: {e}");
        self.out.flush().map_err(fail)?;
        if self.temp.is_some() {
            self.out.get_ref().sync_all().map_err(fail)?;
        }
        Ok(())
    }

    /// Rename the completed temporary into place.
    fn place(&mut self) -> anyhow::Result<()> {
        if let Some(temp) = self.temp.take() {
            let result = std::fs::rename(&temp, &self.target);
            unregister(&temp);
            if let Err(e) = result {
                let _ = std::fs::remove_file(&temp);
                return Err(anyhow::anyhow!(
                    "cannot write {}: {e}",
                    shown_path(&self.target)
                ));
            }
        }
        Ok(())
    }
}

/// Whether this process may write the existing file `path` (its permissions and the
/// effective user, as `open` would judge them).
fn writable(path: &Path) -> bool {
    use std::os::unix::ffi::OsStrExt;
    let Ok(c) = std::ffi::CString::new(path.as_os_str().as_bytes()) else {
        return true;
    };
    // SAFETY: faccessat on a NUL-terminated path of our own.
    unsafe { libc::faccessat(libc::AT_FDCWD, c.as_ptr(), libc::W_OK, libc::AT_EACCESS) == 0 }
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
        drop(Claim(self.claimed.take()));
    }
}

/// A path held in [`OUTPUTS`], given back when dropped.
struct Claim(Option<PathBuf>);

impl Drop for Claim {
    fn drop(&mut self) {
        if let Some(p) = self.0.take() {
            OUTPUTS
                .lock()
                .unwrap_or_else(|e| e.into_inner())
                .retain(|q| *q != p);
        }
    }
}

/// Standard output or an atomically written file: where every command writes; or,
/// inside [`capture`], a buffer in place of standard output.
pub enum Sink {
    Stdout(BufWriter<io::StdoutLock<'static>>),
    File(AtomicFile),
    Captured(std::sync::Arc<std::sync::Mutex<Vec<u8>>>),
}

thread_local! {
    /// What [`Sink::stdout`] writes into on this thread instead of standard output,
    /// inside [`capture`].
    static CAPTURE: std::cell::RefCell<Option<std::sync::Arc<std::sync::Mutex<Vec<u8>>>>> =
        const { std::cell::RefCell::new(None) };
}

/// Run `f` with what it writes to standard output (through [`Sink`]) kept instead:
/// its result and those bytes (a command run for another front end, the Python module).
pub fn capture<T>(f: impl FnOnce() -> T) -> (T, Vec<u8>) {
    let buffer = std::sync::Arc::new(std::sync::Mutex::new(Vec::new()));
    let before = CAPTURE.with(|c| c.replace(Some(buffer.clone())));
    let result = f();
    CAPTURE.with(|c| c.replace(before));
    let bytes = std::mem::take(&mut *buffer.lock().unwrap_or_else(|e| e.into_inner()));
    (result, bytes)
}

impl Sink {
    /// `--out FILE` (created now, so a bad path is refused before any work) or stdout.
    /// A refusal is bad input (status 2).
    pub fn open(out: Option<&str>) -> Result<Sink, String> {
        match out {
            Some(path) => AtomicFile::create(Path::new(path))
                .map(Sink::File)
                .map_err(|e| format!("--out: {e}")),
            None => Ok(Sink::stdout()),
        }
    }

    /// Standard output, for a command that writes there.
    pub fn stdout() -> Sink {
        if let Some(b) = CAPTURE.with(|c| c.borrow().clone()) {
            return Sink::Captured(b);
        }
        STDOUT_IS_OUTPUT.store(true, Ordering::Relaxed);
        Sink::Stdout(BufWriter::with_capacity(1 << 16, io::stdout().lock()))
    }

    /// Flush, and put a file into place. Write errors name the file (or standard
    /// output); a closed standard output stays a closed pipe ([`is_closed_output`]).
    pub fn finish(self) -> anyhow::Result<()> {
        match self {
            Sink::Stdout(mut o) => o.flush().map_err(|e| describe_stdout(e.into())),
            Sink::File(f) => f.commit(),
            Sink::Captured(_) => Ok(()),
        }
    }

    /// `written` (the result of writing everything) and then [`Self::finish`]: the
    /// end of every command's output. A write error names the destination; a failed
    /// file is not put into place.
    pub fn end(self, written: anyhow::Result<()>) -> anyhow::Result<()> {
        match written {
            Ok(()) => self.finish(),
            Err(e) => Err(self.describe(e)),
        }
    }

    /// A write error with the destination named (a closed pipe passes unchanged, to end
    /// the run quietly).
    pub fn describe(&self, e: anyhow::Error) -> anyhow::Error {
        if is_closed_output(&e) {
            return e;
        }
        match self {
            Sink::Stdout(_) => describe_stdout(e),
            Sink::File(f) => anyhow::anyhow!("cannot write {}: {e}", shown_path(f.path())),
            Sink::Captured(_) => e,
        }
    }
}

fn describe_stdout(e: anyhow::Error) -> anyhow::Error {
    if is_closed_output(&e) {
        e
    } else {
        anyhow::anyhow!("cannot write standard output: {e}")
    }
}

/// Whether `e` is a write to a pipe (or socket) that its reader has closed: the run
/// ends quietly with status 0.
pub fn is_closed_output(e: &anyhow::Error) -> bool {
    e.chain().any(closed)
}

/// A broken pipe, however wrapped (an io error around a csv or json error around one).
fn closed(e: &(dyn std::error::Error + 'static)) -> bool {
    if let Some(io) = e.downcast_ref::<io::Error>() {
        return io.kind() == io::ErrorKind::BrokenPipe
            || io.get_ref().is_some_and(|inner| closed(inner));
    }
    if let Some(ce) = e.downcast_ref::<csv::Error>() {
        return matches!(ce.kind(), csv::ErrorKind::Io(io) if closed(io));
    }
    if let Some(je) = e.downcast_ref::<serde_json::Error>() {
        return je.io_error_kind() == Some(io::ErrorKind::BrokenPipe);
    }
    false
}

/// Err(BrokenPipe) if this run writes to standard output and its reader has gone (a
/// pipe or socket closed at the other end): a long computation asks between batches and
/// ends quietly at once instead of at its next write.
pub fn check_stdout() -> io::Result<()> {
    if STDOUT_IS_OUTPUT.load(Ordering::Relaxed) && stdout_closed() {
        return Err(io::ErrorKind::BrokenPipe.into());
    }
    Ok(())
}

/// Whether standard output is a pipe or socket whose reader has gone.
fn stdout_closed() -> bool {
    if !stdout_kind().is_some_and(|k| k.pipe) {
        return false;
    }
    // SAFETY: poll on descriptor 1 with a structure of its own.
    unsafe {
        let mut p = libc::pollfd {
            fd: 1,
            events: 0,
            revents: 0,
        };
        libc::poll(&mut p, 1, 0) == 1 && p.revents & (libc::POLLERR | libc::POLLHUP) != 0
    }
}

/// Whether this run's results stream into another program: they go to standard output
/// and it is a pipe or a socket. Such a run's stderr carries only errors (no batch log),
/// so a reader that stops early (`| head`) ends it with nothing on stderr.
pub fn streams_to_program() -> bool {
    STDOUT_IS_OUTPUT.load(Ordering::Relaxed) && stdout_kind().is_some_and(|k| k.pipe)
}

/// What standard output is: `pipe` for a pipe or socket.
struct StdoutKind {
    pipe: bool,
}

fn stdout_kind() -> Option<StdoutKind> {
    // SAFETY: fstat on descriptor 1 into a structure of its own.
    unsafe {
        let mut st: libc::stat = std::mem::zeroed();
        if libc::fstat(1, &mut st) != 0 {
            return None;
        }
        let kind = st.st_mode & libc::S_IFMT;
        Some(StdoutKind {
            pipe: kind == libc::S_IFIFO || kind == libc::S_IFSOCK,
        })
    }
}

impl Write for Sink {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        match self {
            Sink::Stdout(o) => o.write(buf),
            Sink::File(f) => f.write(buf),
            Sink::Captured(b) => {
                b.lock()
                    .unwrap_or_else(|e| e.into_inner())
                    .extend_from_slice(buf);
                Ok(buf.len())
            }
        }
    }

    fn flush(&mut self) -> io::Result<()> {
        match self {
            Sink::Stdout(o) => o.flush(),
            Sink::File(f) => f.flush(),
            Sink::Captured(_) => Ok(()),
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
