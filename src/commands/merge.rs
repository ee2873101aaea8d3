//! `bouncemap merge`: join the part files of `sweep --shard I/N` (or of `plane --shard
//! I/N`) into the file the unsharded run writes (the same layout and values in index
//! order; its provenance says `merged N/N` where the unsharded file's says `1/1`).
//! Whether the parts are of a sweep or a plane is read from the first one; a part of
//! the other kind is then refused as not a file of that kind.
//!
//! Every part is checked first ([`read_part`]): its provenance, its specification
//! against its hash, every row (complete, well-formed, inside its shard, at the value its
//! index means), its end line and its count of values. Then the parts must be of one
//! sweep (or plane), written by the same tool, with every shard exactly once
//! ([`join`]). Any failure is one line naming the file (and line), status 2, and nothing
//! is written.

use crate::config::files::{read_text, LARGE_FILE};
use crate::config::flags::MergeArgs;
use crate::config::InputError;
use crate::output::part_file::{join, read_part, FileKind};
use crate::output::plane_file::{is_plane, PlaneFile};
use crate::output::sink::{note_input, Sink};
use crate::output::sweep_file::SweepFile;
use crate::output::text::shown_path;
use std::path::Path;

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
    let mut texts = Vec::new();
    for f in &args.files {
        texts.push(read_text(Path::new(f), "merge: part", LARGE_FILE)?);
    }
    if texts.first().is_some_and(|t| is_plane(t)) {
        merge::<PlaneFile>(args, &texts, sink)
    } else {
        merge::<SweepFile>(args, &texts, sink)
    }
}

/// Read and check every part as a file of kind `K`, join them and write the result.
fn merge<K: FileKind>(args: &MergeArgs, texts: &[String], mut sink: Sink) -> anyhow::Result<()> {
    let mut parts = Vec::new();
    for (f, text) in args.files.iter().zip(texts) {
        parts.push(read_part::<K>(f, text).map_err(|e| InputError(format!("merge: {e}")))?);
    }
    let joined = join(parts).map_err(|e| InputError(format!("merge: {e}")))?;
    let written = joined.write(&mut sink).map(drop);
    written.map_err(|e| sink.describe(e.into()))?;
    sink.finish()
}
