//! `bouncemap merge`: join the part files of `sweep --shard I/N` into the file the
//! unsharded sweep writes (same format, values in index order, byte for byte).
//!
//! csv parts must share one header; json parts must agree on every setting but
//! `shard`. A value index found in two parts is refused, and so (for json, which
//! records `steps`) is a set of parts that misses values.

use crate::input::InputError;
use clap::Args;
use std::collections::BTreeMap;
use std::io::{self, BufWriter, Write};

/// `bouncemap merge`.
#[derive(Args, Debug, Clone)]
pub struct MergeArgs {
    /// Part files written by `sweep --shard I/N --out FILE` (all csv or all json).
    #[arg(required = true, value_name = "FILE")]
    pub files: Vec<String>,
    /// Write to FILE instead of stdout.
    #[arg(long, value_name = "FILE")]
    pub out: Option<String>,
}

pub fn run(args: &MergeArgs) -> anyhow::Result<()> {
    let mut texts = Vec::new();
    for f in &args.files {
        let t = std::fs::read_to_string(f)
            .map_err(|e| InputError(format!("merge: cannot read {f}: {e}")))?;
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
    use serde_json::Value;
    let mut header: Option<serde_json::Map<String, Value>> = None;
    let mut values: BTreeMap<u64, (&str, Value)> = BTreeMap::new();
    for (name, text) in parts {
        let doc: Value = serde_json::from_str(text)
            .map_err(|e| InputError(format!("merge: {name}: not sweep json: {e}")))?;
        let Value::Object(mut m) = doc else {
            return Err(InputError(format!(
                "merge: {name}: not a sweep json object"
            )));
        };
        let vals = match m.remove("values") {
            Some(Value::Array(v)) => v,
            _ => {
                return Err(InputError(format!(
                    "merge: {name}: no \"values\" array: valid a sweep json file"
                )))
            }
        };
        m.insert("shard".into(), Value::Null);
        match &header {
            None => header = Some(m),
            Some(h) if *h != m => {
                return Err(InputError(format!(
                    "merge: {name} has other sweep settings than the first part: valid parts of one sweep"
                )))
            }
            _ => {}
        }
        for v in vals {
            let idx = v
                .get("index")
                .and_then(Value::as_u64)
                .ok_or_else(|| InputError(format!("merge: {name}: a value without an index")))?;
            if let Some((other, _)) = values.get(&idx) {
                return Err(InputError(format!(
                    "merge: value {idx} is in both {other} and {name}: valid disjoint shards"
                )));
            }
            values.insert(idx, (name, v));
        }
    }
    let header = header.unwrap_or_default();
    if let Some(steps) = header.get("steps").and_then(Value::as_u64) {
        if values.len() as u64 != steps {
            return Err(InputError(format!(
                "merge: the parts hold {} of the sweep's {steps} values: valid every shard I/N of one sweep",
                values.len()
            )));
        }
    }
    let mut buf = Vec::new();
    super::sweep::write_json_doc(
        &mut buf,
        header,
        values.into_values().map(|(_, v)| v).collect(),
    )
    .map_err(|e| InputError(format!("merge: {e}")))?;
    Ok(String::from_utf8(buf).expect("json is utf-8"))
}
