//! The layering of the three crates, checked from their sources. In the engine, the
//! figures crate and the binary, among the modules of every parent (the crate's top-level modules; the
//! children of each of those) the "uses" graph has no cycle; and the crate's top-level
//! modules use only modules of their own layer or the layers below it ([`ENGINE_LAYERS`],
//! [`FIGURES_LAYERS`], [`BINARY_LAYERS`]). A path `crate::a::b`, `super::x` or `self::y` in a file counts as
//! a use of the module it names.

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

/// The engine's top-level modules, bottom layer first: a module may use its own layer
/// and the layers below.
const ENGINE_LAYERS: &[&[&str]] = &[
    &[
        "error",
        "limits",
        "time",
        "linalg",
        "exact_sum",
        "poly",
        "test_rng",
        "real",
    ],
    &["table"],
    &["system"],
    &["impact", "chatter"],
    &["map", "tangent", "precise", "inverse"],
    &["jobs"],
    &["orbits"],
    &["run"],
    &["attractors"],
    &["sweep", "plane"],
];

/// The figures crate's top-level modules, bottom layer first (the engine lies below
/// them all): the data model and how numbers and text are set; what colours and names
/// an orbit or a parameter; drawing (SVG, PNG, the terminal's images); the builders of
/// each kind of figure.
const FIGURES_LAYERS: &[&[&str]] = &[
    &["model", "format", "text"],
    &["classes", "labels"],
    &["svg", "raster", "terminal"],
    &[
        "diagram", "basins", "curves", "global", "lyapunov", "manifold", "phase", "plane",
        "scaling", "shapes",
    ],
];

/// The binary's top-level modules, bottom layer first (the engine lies below them all).
const BINARY_LAYERS: &[&[&str]] = &[&["output"], &["config"], &["commands", "tui", "docs"]];

/// parent path → sibling → siblings it uses, for the crate whose sources are in `src`.
fn uses(src: &Path) -> BTreeMap<Vec<String>, BTreeMap<String, BTreeSet<String>>> {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    let mut graph: BTreeMap<Vec<String>, BTreeMap<String, BTreeSet<String>>> = BTreeMap::new();
    for f in &files {
        let module = module_of(src, f);
        let is_dir_module = f
            .file_name()
            .is_some_and(|n| n == "mod.rs" || n == "lib.rs" || n == "main.rs");
        let text = std::fs::read_to_string(f).unwrap();
        // A file's unit tests may use any layer (to compare with a closed form found
        // higher up): they are not part of the module graph.
        let text = text.split("#[cfg(test)]\nmod tests").next().unwrap_or("");
        for target in references(&module, is_dir_module, text) {
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
    graph
}

fn engine_src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("crates/engine/src")
}

fn figures_src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("crates/figures/src")
}

fn binary_src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// Every use between top-level modules goes to the same layer or one below.
fn assert_layered(src: &Path, layers: &[&[&str]]) {
    let graph = uses(src);
    let layer = |m: &str| layers.iter().position(|l| l.contains(&m));
    let top = graph
        .get(&Vec::new())
        .expect("no top-level uses found: the scan is broken");
    for (from, targets) in top {
        let Some(lf) = layer(from) else {
            assert!(
                matches!(from.as_str(), "lib" | "main"),
                "module {from} of {} is in no layer: add it to the layer list",
                src.display()
            );
            continue;
        };
        for to in targets {
            let lt = layer(to).unwrap_or_else(|| panic!("module {to} is in no layer"));
            assert!(
                lt <= lf,
                "{from} (layer {lf}) uses {to} (layer {lt}), a layer above it, in {}",
                src.display()
            );
        }
    }
}

#[test]
fn the_engine_uses_only_layers_below() {
    assert_layered(&engine_src(), ENGINE_LAYERS);
}

#[test]
fn the_figures_crate_uses_only_layers_below() {
    assert_layered(&figures_src(), FIGURES_LAYERS);
}

#[test]
fn no_figures_module_uses_a_sibling_that_uses_it_back() {
    assert_no_cycle(&figures_src());
}

#[test]
fn the_binary_uses_only_layers_below() {
    assert_layered(&binary_src(), BINARY_LAYERS);
}

#[test]
fn no_engine_module_uses_a_sibling_that_uses_it_back() {
    assert_no_cycle(&engine_src());
}

#[test]
fn no_module_uses_a_sibling_that_uses_it_back() {
    assert_no_cycle(&binary_src());
}

fn assert_no_cycle(src: &Path) {
    let graph = uses(src);
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

/// The engine's face is a handful of modules (the rest internal, their items
/// re-exported at the root), and neither library crate may use `unsafe`.
#[test]
fn the_engines_face_is_a_handful_of_modules_and_the_libraries_forbid_unsafe() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let lib = std::fs::read_to_string(root.join("crates/engine/src/lib.rs")).unwrap();
    let public: Vec<&str> = lib
        .lines()
        .filter_map(|l| l.strip_prefix("pub mod "))
        .collect();
    assert!(
        public.len() <= 8,
        "{} public modules: {public:?}",
        public.len()
    );
    for krate in ["crates/engine/src/lib.rs", "crates/figures/src/lib.rs"] {
        let text = std::fs::read_to_string(root.join(krate)).unwrap();
        assert!(text.contains("#![forbid(unsafe_code)]"), "{krate}");
    }
}
