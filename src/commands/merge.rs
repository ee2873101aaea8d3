//! `bouncemap merge`: join the part files of `sweep --shard I/N` into the file the
//! unsharded sweep writes (same format, values in index order, byte for byte).
//!
//! csv parts must share one header; json parts must agree on every setting but
//! `shard`. A value index found in two parts is refused, and so (for json, which
//! records `steps`) is a set of parts that misses values.

use crate::config::files::{read_text, LARGE_FILE};
use crate::config::flags::MergeArgs;
use crate::config::InputError;
use crate::output::records::SweepDoc;
use std::collections::BTreeMap;
use std::io::{self, BufWriter, Write};
use std::path::Path;

pub fn run(args: &MergeArgs) -> anyhow::Result<()> {
    let mut texts = Vec::new();
    for f in &args.files {
        let t = read_text(Path::new(f), "merge: part", LARGE_FILE)?;
        texts.push((f.as_str(), t));
    }
    let merged = merge_texts(&texts)?;
    match &args.out {
        Some(path) => std::fs::write(path, merged)
            .map_err(|e| InputError(format!("--out: cannot write {path}: {e}")))?,
        None => {
            let mut out = BufWriter::new(io::stdout().lock());
            out.write_all(merged.as_bytes())?;
            out.flush()?;
        }
    }
    Ok(())
}

/// Merge part files given as (name, text); csv or json decided by the first one.
pub fn merge_texts(parts: &[(&str, String)]) -> Result<String, InputError> {
    let first = parts
        .first()
        .ok_or_else(|| InputError("merge: no files given: valid one or more part files".into()))?;
    if first.1.trim_start().starts_with('{') {
        merge_json(parts)
    } else {
        merge_csv(parts)
    }
}

fn merge_csv(parts: &[(&str, String)]) -> Result<String, InputError> {
    let mut header: Option<&str> = None;
    // index -> (file, rows)
    let mut values: BTreeMap<usize, (&str, Vec<&str>)> = BTreeMap::new();
    for (name, text) in parts {
        let mut lines = text.lines();
        let h = lines
            .next()
            .ok_or_else(|| InputError(format!("merge: {name} is empty: valid a sweep csv file")))?;
        if !h.starts_with("index,") {
            return Err(InputError(format!(
                "merge: {name} is not a sweep csv file (its header is '{h}')"
            )));
        }
        match header {
            None => header = Some(h),
            Some(h0) if h0 != h => {
                return Err(InputError(format!(
                    "merge: {name} has header '{h}', other parts '{h0}': valid parts of one sweep"
                )))
            }
            _ => {}
        }
        let mut here: BTreeMap<usize, Vec<&str>> = BTreeMap::new();
        for (n, line) in lines.enumerate() {
            if line.is_empty() {
                continue;
            }
            let idx = line
                .split(',')
                .next()
                .and_then(|f| f.parse::<usize>().ok())
                .ok_or_else(|| {
                    InputError(format!(
                        "merge: {name} line {}: no value index in '{line}'",
                        n + 2
                    ))
                })?;
            here.entry(idx).or_default().push(line);
        }
        for (idx, rows) in here {
            if let Some((other, _)) = values.get(&idx) {
                return Err(InputError(format!(
                    "merge: value {idx} is in both {other} and {name}: valid disjoint shards"
                )));
            }
            values.insert(idx, (name, rows));
        }
    }
    let mut out = String::new();
    out.push_str(header.unwrap_or_default());
    out.push('\n');
    for (_, rows) in values.values() {
        for r in rows {
            out.push_str(r);
            out.push('\n');
        }
    }
    Ok(out)
}

fn merge_json(parts: &[(&str, String)]) -> Result<String, InputError> {
    let mut first: Option<(&str, SweepDoc)> = None;
    let mut values = BTreeMap::new();
    for (name, text) in parts {
        let mut doc: SweepDoc = serde_json::from_str(text)
            .map_err(|e| InputError(format!("merge: {name}: not sweep json: {e}")))?;
        doc.header.shard = None;
        for v in std::mem::take(&mut doc.values) {
            if let Some((other, _)) = values.get(&v.index) {
                return Err(InputError(format!(
                    "merge: value {} is in both {other} and {name}: valid disjoint shards",
                    v.index
                )));
            }
            values.insert(v.index, (*name, v));
        }
        match &first {
            None => first = Some((name, doc)),
            Some((_, d)) if d.header != doc.header => {
                return Err(InputError(format!(
                    "merge: {name} has other sweep settings than the first part: valid parts of one sweep"
                )))
            }
            _ => {}
        }
    }
    let (_, mut doc) = first.ok_or_else(|| InputError("merge: no files given".into()))?;
    if values.len() != doc.header.steps {
        return Err(InputError(format!(
            "merge: the parts hold {} of the sweep's {} values: valid every shard I/N of one sweep",
            values.len(),
            doc.header.steps
        )));
    }
    doc.values = values.into_values().map(|(_, v)| v).collect();
    let mut text = serde_json::to_string(&doc).map_err(|e| InputError(format!("merge: {e}")))?;
    text.push('\n');
    Ok(text)
}
