//! `bouncemap merge`: join the part files of `sweep --shard I/N` (or of `plane --shard
//! I/N`) into the file the unsharded run writes (the same layout and values in index
//! order; its provenance says `merged N/N` where the unsharded file's says `1/1`).
//! Whether the parts are of a sweep or a plane is read from the first one; a part of
//! the other kind is then refused as not a file of that kind.
//!
//! Every part is checked first ([`read_part`]), read as a stream: its provenance, its
//! specification against its hash, every row (complete, well-formed, inside its shard,
//! at the value its index means), its end line and its count of values. Then the parts
//! must be of one sweep (or plane), written by the same tool, with every shard exactly
//! once ([`join`]). Any failure is one line naming the file (and line), status 2, and
//! nothing is written. Only then are the parts read again, side by side, their values
//! merged into index order and written ([`Joined::write`]): memory holds a value per
//! part and the buffers, whatever the size of the parts; every part is open at once, so
//! more parts than the process may open files are refused before any is read. A part
//! that changed between the two readings is refused then, and `--out` is left as it was
//! (standard output has had the values before it).

use crate::config::files::{check_input, head, open_input, read_again, LARGE_FILE};
use crate::config::flags::MergeArgs;
use crate::config::InputError;
use crate::output::part_file::{join, read_part, FileKind, JoinError, Joined};
use crate::output::plane_file::{is_plane, PlaneFile};
use crate::output::sink::{note_input, Sink};
use crate::output::sweep_file::SweepFile;
use crate::output::text::shown_path;
use std::path::Path;

/// How a part is named in refusals of its reading.
const WHAT: &str = "merge: part";

/// Open files a merge needs besides its parts (standard streams, the output, the
/// executable and libraries, a second reading of a part).
const SPARE_FILES: usize = 16;

pub fn run(args: &MergeArgs) -> anyhow::Result<()> {
    // The parts are inputs before they are read, so --out, opened (and so checked)
    // before the reading, can never be one of them.
    for f in &args.files {
        note_input(
            Path::new(f),
            &format!("the part {}", shown_path(Path::new(f))),
        );
    }
    let sink = Sink::open(args.output.out.as_deref()).map_err(InputError)?;
    // Every part is there, a regular file, not too large, before any is read; and all
    // can be open at once (they are read side by side).
    for f in &args.files {
        check_input(Path::new(f), WHAT, LARGE_FILE)?;
    }
    let open = allow_open_files(args.files.len() + SPARE_FILES);
    if args.files.len() + SPARE_FILES > open {
        return Err(InputError(format!(
            "merge: {} parts, but this process may open {open} files at once: valid at most {} parts (or a higher `ulimit -n`)",
            args.files.len(),
            open.saturating_sub(SPARE_FILES)
        ))
        .into());
    }
    let first = args.files.first().map(|f| head(Path::new(f), 1600));
    if first.is_some_and(|t| is_plane(&t)) {
        merge::<PlaneFile>(args, sink)
    } else {
        merge::<SweepFile>(args, sink)
    }
}

/// Read and check every part as a file of kind `K`, join them and write the result.
fn merge<K: FileKind>(args: &MergeArgs, mut sink: Sink) -> anyhow::Result<()> {
    let mut parts = Vec::new();
    for f in &args.files {
        let path = Path::new(f);
        let mut input = open_input(path, WHAT, LARGE_FILE)?;
        let mut again =
            |offset, len| read_again(path, offset, len, 1 << 16).map(|r| Box::new(r) as Box<_>);
        let part = read_part::<K, _>(f, &mut input, &mut again);
        // What the reader found (not UTF-8 further on, grown) is said first, as when a
        // part was read whole before it was parsed.
        input.finish()?;
        parts.push(part.map_err(|e| InputError(format!("merge: {e}")))?);
    }
    let joined = join(parts).map_err(|e| InputError(format!("merge: {e}")))?;
    let written = write(&joined, &mut sink);
    match written {
        Ok(()) => sink.finish(),
        Err(JoinError::Part(e)) => Err(InputError(format!("merge: {e}")).into()),
        Err(JoinError::Write(e)) => Err(sink.describe(e.into())),
    }
}

/// Write the joined parts into `sink`, each part's values read again through a buffer
/// (smaller when there are many parts: a few MiB in all).
fn write<K: FileKind>(joined: &Joined<K>, sink: &mut Sink) -> Result<(), JoinError> {
    let buffer = ((8 << 20) / joined.parts.len().max(1)).clamp(8 << 10, 1 << 16);
    joined
        .write(&mut *sink, |p| {
            read_again(Path::new(&p.name), p.body.offset, p.body.len, buffer)
        })
        .map(drop)
}

/// Raise this process's limit on open files to `wanted`, or as near as its hard limit
/// allows (every part is open at once, and a Slurm array may have thousands of shards);
/// the limit then.
fn allow_open_files(wanted: usize) -> usize {
    // SAFETY: getrlimit and setrlimit on a structure of our own.
    unsafe {
        let mut limit: libc::rlimit = std::mem::zeroed();
        if libc::getrlimit(libc::RLIMIT_NOFILE, &mut limit) != 0 {
            return usize::MAX;
        }
        let wanted = (wanted as libc::rlim_t).min(limit.rlim_max);
        if limit.rlim_cur < wanted {
            let raised = libc::rlimit {
                rlim_cur: wanted,
                rlim_max: limit.rlim_max,
            };
            if libc::setrlimit(libc::RLIMIT_NOFILE, &raised) == 0 {
                limit.rlim_cur = wanted;
            }
        }
        usize::try_from(limit.rlim_cur).unwrap_or(usize::MAX)
    }
}
