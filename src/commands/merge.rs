//! `bouncemap merge`: join the part files of `sweep --shard I/N` (or of `plane --shard
//! I/N`) into the file the unsharded run writes (the same layout and values in index
//! order; its provenance says `merged N/N` where the unsharded file's says `1/1`).
//! Whether the parts are of a sweep or a plane is read from the first one; a part of
//! the other kind is then refused as not a file of that kind.
//!
//! Every part is checked first ([`read_part`]): its provenance, its specification
//! against its hash, every row (complete, well-formed, inside its shard, at the value its
//! index means), its end line and its count of values. Then the parts must be of one
//! sweep, written by the same tool, with every shard exactly once ([`join`]). Any
//! failure is one line naming the file (and line), status 2, and nothing is written.

use crate::config::files::{read_text, LARGE_FILE};
use crate::config::flags::MergeArgs;
use crate::config::InputError;
use crate::output::plane_file;
use crate::output::sink::Sink;
use crate::output::sweep_file::{join, read_part, PartValue, SweepWriter};
use std::path::Path;

pub fn run(args: &MergeArgs) -> anyhow::Result<()> {
    let mut sink = Sink::open(args.out.as_deref()).map_err(InputError)?;
    let mut texts = Vec::new();
    for f in &args.files {
        texts.push(read_text(Path::new(f), "merge: part", LARGE_FILE)?);
    }
    if texts.first().is_some_and(|t| plane_file::is_plane(t)) {
        return merge_planes(args, &texts, sink);
    }
    let mut parts = Vec::new();
    for (f, text) in args.files.iter().zip(&texts) {
        parts.push(read_part(f, text).map_err(|e| InputError(format!("merge: {e}")))?);
    }
    let count = parts.first().and_then(|p| p.shard).map_or(1, |s| s.count);
    let (layout, header, values) = join(parts).map_err(|e| InputError(format!("merge: {e}")))?;
    let shard = if count > 1 {
        format!("merged {count}/{count}")
    } else {
        "1/1".to_string()
    };
    let write = |sink: &mut Sink| -> anyhow::Result<()> {
        let mut w = SweepWriter::begin(sink, layout, &header, &shard, header.steps)?;
        for v in &values {
            match v {
                PartValue::Csv { rows, .. } => w.rows(rows)?,
                PartValue::Json(v) => w.json(v)?,
            }
        }
        w.end()?;
        Ok(())
    };
    write(&mut sink).map_err(|e| sink.describe(e))?;
    sink.finish()
}

/// Merge the parts of a plane.
fn merge_planes(args: &MergeArgs, texts: &[String], mut sink: Sink) -> anyhow::Result<()> {
    let mut parts = Vec::new();
    for (f, text) in args.files.iter().zip(texts) {
        parts.push(plane_file::read_part(f, text).map_err(|e| InputError(format!("merge: {e}")))?);
    }
    let count = parts.first().and_then(|p| p.shard).map_or(1, |s| s.count);
    let (layout, header, curves, rows) =
        plane_file::join(parts).map_err(|e| InputError(format!("merge: {e}")))?;
    let shard = if count > 1 {
        format!("merged {count}/{count}")
    } else {
        "1/1".to_string()
    };
    let written = plane_file::write(
        &mut sink,
        layout,
        &header,
        &shard,
        &curves,
        rows.len(),
        rows.into_iter(),
    )
    .map(drop);
    written.map_err(|e| sink.describe(e.into()))?;
    sink.finish()
}
