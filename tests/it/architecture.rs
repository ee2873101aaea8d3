//! The binary's layering, checked from its sources: among the modules of every parent
//! (the crate's `config`, `commands`, `output`, `tui`; the children of each of those)
//! the "uses" graph has no cycle. A path `crate::a::b`, `super::x` or `self::y` in a
//! file counts as a use of the module it names.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The module path of a source file (`src/tui/components/diagram.rs` → tui, components,
/// diagram; a `mod.rs` is its directory).
fn module_of(src: &Path, file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(src).unwrap();
    let mut parts: Vec<String> = rel
        .iter()
        .map(|c| c.to_string_lossy().trim_end_matches(".rs").to_string())
        .collect();
    if matches!(
        parts.last().map(String::as_str),
        Some("mod" | "lib" | "main")
    ) {
        parts.pop();
    }
    parts
}

/// Every absolute module path a file refers to.
fn references(module: &[String], is_dir_module: bool, text: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let code: String = text
        .lines()
        .filter(|l| !l.trim_start().starts_with("//"))
        .collect::<Vec<_>>()
        .join("\n");
    let bytes: Vec<char> = code.chars().collect();
    let mut i = 0;
    while i < bytes.len() {
        let rest: String = bytes[i..bytes.len().min(i + 7)].iter().collect();
        let start = ["crate::", "super::", "self::"].into_iter().find(|p| {
            rest.starts_with(p)
                && (i == 0 || !bytes[i - 1].is_alphanumeric() && bytes[i - 1] != '_')
        });
        let Some(prefix) = start else {
            i += 1;
            continue;
        };
        // The path's segments up to the first non-segment (or a brace list).
        let mut j = i;
        let mut segs: Vec<String> = Vec::new();
        loop {
            let mut w = String::new();
            while j < bytes.len() && (bytes[j].is_alphanumeric() || bytes[j] == '_') {
                w.push(bytes[j]);
                j += 1;
            }
            if !w.is_empty() {
                segs.push(w);
            }
            if j + 1 < bytes.len() && bytes[j] == ':' && bytes[j + 1] == ':' {
                j += 2;
                if j < bytes.len() && bytes[j] == '{' {
                    // A brace list: each entry's first segment.
                    let close = bytes[j..]
                        .iter()
                        .position(|&c| c == '}')
                        .map_or(bytes.len(), |k| j + k);
                    let inner: String = bytes[j + 1..close].iter().collect();
                    for entry in inner.split(',') {
                        let first = entry
                            .trim()
                            .split("::")
                            .next()
                            .unwrap_or("")
                            .trim()
                            .to_string();
                        if !first.is_empty() && first != "self" {
                            let mut s = segs.clone();
                            s.push(first);
                            out.push(resolve(module, is_dir_module, prefix, &s));
                        }
                    }
                    segs.clear();
                    break;
                }
            } else {
                break;
            }
        }
        if !segs.is_empty() {
            out.push(resolve(module, is_dir_module, prefix, &segs));
        }
        i = j.max(i + 1);
    }
    out
}

fn resolve(module: &[String], is_dir_module: bool, prefix: &str, segs: &[String]) -> Vec<String> {
    // segs starts with the prefix word itself (crate/super/self) and may chain supers.
    let mut base: Vec<String> = match prefix {
        "crate::" => Vec::new(),
        _ => {
            let mut b = module.to_vec();
            if !is_dir_module || prefix == "super::" {
                // A file module's `self` is itself; its `super` is its parent.
                if prefix == "super::" {
                    b.pop();
                }
            }
            b
        }
    };
    let mut rest = &segs[1..];
    while rest.first().map(String::as_str) == Some("super") {
        base.pop();
        rest = &rest[1..];
    }
    base.extend(rest.iter().cloned());
    base
}

#[test]
fn no_module_uses_a_sibling_that_uses_it_back() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    // parent path → sibling → siblings it uses
    let mut graph: BTreeMap<Vec<String>, BTreeMap<String, BTreeSet<String>>> = BTreeMap::new();
    for f in &files {
        let module = module_of(&src, f);
        let is_dir_module = f
            .file_name()
            .is_some_and(|n| n == "mod.rs" || n == "lib.rs" || n == "main.rs");
        let text = std::fs::read_to_string(f).unwrap();
        for target in references(&module, is_dir_module, &text) {
            let common = module
                .iter()
                .zip(&target)
                .take_while(|(a, b)| a == b)
                .count();
            if common < module.len() && common < target.len() {
                graph
                    .entry(module[..common].to_vec())
                    .or_default()
                    .entry(module[common].clone())
                    .or_default()
                    .insert(target[common].clone());
            }
        }
    }
    assert!(
        graph.contains_key(&Vec::new()),
        "no top-level uses found: the scan is broken"
    );
    for (parent, edges) in &graph {
        // Depth-first search for a cycle among the siblings under `parent`.
        fn visit(
            n: &str,
            edges: &BTreeMap<String, BTreeSet<String>>,
            state: &mut BTreeMap<String, u8>,
            path: &mut Vec<String>,
        ) -> Option<Vec<String>> {
            match state.get(n) {
                Some(1) => {
                    let at = path.iter().position(|p| p == n).unwrap();
                    let mut cycle = path[at..].to_vec();
                    cycle.push(n.to_string());
                    return Some(cycle);
                }
                Some(2) => return None,
                _ => {}
            }
            state.insert(n.to_string(), 1);
            path.push(n.to_string());
            for m in edges.get(n).into_iter().flatten() {
                if m != n {
                    if let Some(c) = visit(m, edges, state, path) {
                        return Some(c);
                    }
                }
            }
            path.pop();
            state.insert(n.to_string(), 2);
            None
        }
        let mut state = BTreeMap::new();
        for n in edges.keys() {
            if let Some(cycle) = visit(n, edges, &mut state, &mut Vec::new()) {
                panic!(
                    "modules under crate::{} use each other: {}",
                    parent.join("::"),
                    cycle.join(" → ")
                );
            }
        }
    }
}
