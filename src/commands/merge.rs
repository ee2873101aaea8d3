//! `bouncemap merge`: join the part files of `sweep --shard I/N` (or of `plane --shard
//! I/N`) into the file the unsharded run writes (the same layout and values in index
//! order; its provenance says `merged N/N` where the unsharded file's says `1/1`). The
//! parts of `attractors --shard I/N` are read whole, checked
//! ([`attractors_file`](crate::output::attractors_file)), joined at the α values they
//! share, and written as `attractors`' report in `--format` (with a line per join).
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

use crate::config::files::{check_input, head, open_input, read_again, read_text, LARGE_FILE};
use crate::config::flags::{AttractorsFormat, MergeArgs};
use crate::config::run::attractors_spec_of;
use crate::config::InputError;
use crate::output::attractors_file::{self, is_attractors, ATTRACTORS_PART};
use crate::output::part_file::{join, read_part, FileKind, JoinError, Joined};
use crate::output::part_file::{shard_name, Layout};
use crate::output::plane_file::{is_plane, PlaneFile};
use crate::output::sink::{note_input, Sink};
use crate::output::sweep_file::SweepFile;
use crate::output::text::shown_path;
use clap::ValueEnum;
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
    if first.as_deref().is_some_and(is_attractors) {
        return merge_attractors(args, sink);
    }
    if let Some(f) = args.format {
        return Err(InputError(format!(
            "--format {}: parts of `sweep` and `plane` are merged into their own format; valid only for parts of `attractors`",
            f.to_possible_value().map(|v| v.get_name().to_string()).unwrap_or_default()
        ))
        .into());
    }
    if first.is_some_and(|t| is_plane(&t)) {
        merge::<PlaneFile>(args, sink)
    } else {
        merge::<SweepFile>(args, sink)
    }
}

/// Read and check every part of an `attractors` run, join them in the order of their
/// shards at the α values they share, and write the report of the whole window.
fn merge_attractors(args: &MergeArgs, mut sink: Sink) -> anyhow::Result<()> {
    let mut parts: Vec<attractors_file::Part> = Vec::new();
    for f in &args.files {
        let text = read_text(Path::new(f), WHAT, ATTRACTORS_PART)?;
        let part = attractors_file::read_part(&text, &attractors_spec_of)
            .map_err(|e| InputError(format!("merge: {}: {e}", shown_path(Path::new(f)))))?;
        if let Some(first) = parts.first() {
            if part.header != first.header || part.shard.count != first.shard.count {
                return Err(InputError(format!(
                    "merge: {}: a part of another attractors run than {} (its spec or its number of shards differs)",
                    shown_path(Path::new(f)),
                    shown_path(Path::new(&args.files[0]))
                ))
                .into());
            }
        }
        parts.push(part);
    }
    let count = parts[0].shard.count;
    parts.sort_by_key(|p| p.shard.index);
    for (i, p) in parts.iter().enumerate() {
        if p.shard.index != i {
            let what = if i > 0 && parts[i - 1].shard.index == p.shard.index {
                format!("shard {} is given twice", shard_name(p.shard))
            } else {
                format!("shard {i_1}/{count} is missing", i_1 = i + 1)
            };
            return Err(InputError(format!(
                "merge: {what}: valid every shard 1/{count} .. {count}/{count} once"
            ))
            .into());
        }
    }
    if parts.len() != count {
        return Err(InputError(format!(
            "merge: shard {}/{count} is missing: valid every shard 1/{count} .. {count}/{count} once",
            parts.len() + 1
        ))
        .into());
    }
    let mut parts = parts.into_iter();
    let mut whole = parts.next().expect("one part at least").cont;
    let mut joins = Vec::new();
    for p in parts {
        let (joined, join) = whole
            .join(p.cont)
            .map_err(|e| InputError(format!("merge: shard {}: {e}", shard_name(p.shard))))?;
        whole = joined;
        joins.push(join);
    }
    let layout = match args.format {
        Some(AttractorsFormat::Csv) => Some(Layout::Csv),
        Some(AttractorsFormat::Json) => Some(Layout::Json),
        Some(AttractorsFormat::Text) | None => None,
    };
    super::attractors::write(layout, &whole, &joins, None, &mut sink)
        .map_err(|e| sink.describe(e))?;
    sink.finish()
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
