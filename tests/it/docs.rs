//! Every example in the README and in `docs/` runs, and prints what the page says.
//!
//! A fenced block marked `console` is a transcript: a line `$ COMMAND` is run by `sh -c`
//! with this build's `bouncemap` first on the PATH, in a scratch directory that sees the
//! repository's `assets/`; the lines after it, up to the next `$ ` line, are the output
//! it must print (stdout, then stderr). In the expected output a line `...` stands for
//! any number of lines and `[..]` for any text within a line; a last line `[exit N]`
//! says the command must end with status N (otherwise 0). A command followed by no
//! output lines is only required to succeed. Blocks marked `sh` (installing, the
//! terminal application, cluster jobs, long runs) are not run.
//!
//! So every number and finding the documents state about the dynamics is regenerated
//! here: a claim in the prose sits next to the transcript that shows it.

use std::path::{Path, PathBuf};
use std::process::Command;

/// One `$ ` command of a transcript and what it must print.
#[derive(Debug)]
struct Example {
    /// Line of the command in its file (1-based).
    line: usize,
    command: String,
    expected: Vec<String>,
    status: i32,
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The transcripts of one markdown file.
fn examples(text: &str) -> Vec<Example> {
    let mut out: Vec<Example> = Vec::new();
    let mut in_console = false;
    let mut in_other = false;
    for (i, line) in text.lines().enumerate() {
        let trimmed = line.trim_start();
        if let Some(info) = trimmed.strip_prefix("```") {
            if in_console || in_other {
                in_console = false;
                in_other = false;
            } else if info.trim() == "console" {
                in_console = true;
            } else {
                in_other = true;
            }
            continue;
        }
        if !in_console {
            continue;
        }
        if let Some(cmd) = line.strip_prefix("$ ") {
            out.push(Example {
                line: i + 1,
                command: cmd.to_string(),
                expected: Vec::new(),
                status: 0,
            });
        } else if let Some(ex) = out.last_mut() {
            if let Some(n) = line
                .strip_prefix("[exit ")
                .and_then(|s| s.strip_suffix(']'))
            {
                ex.status = n.parse().expect("[exit N] with an integer N");
            } else {
                ex.expected.push(line.to_string());
            }
        } else {
            panic!(
                "line {}: a console block must start with a `$ ` command",
                i + 1
            );
        }
    }
    out
}

/// Does `line` match `pattern`, where `[..]` matches any text?
fn line_matches(pattern: &str, line: &str) -> bool {
    let parts: Vec<&str> = pattern.split("[..]").collect();
    if parts.len() == 1 {
        return pattern == line;
    }
    let (first, last) = (parts[0], parts[parts.len() - 1]);
    if !line.starts_with(first) || line.len() < first.len() + last.len() {
        return false;
    }
    let mut rest = &line[first.len()..];
    for part in &parts[1..parts.len() - 1] {
        match rest.find(part) {
            Some(at) => rest = &rest[at + part.len()..],
            None => return false,
        }
    }
    rest.ends_with(last)
}

/// Do the printed `lines` match the expected ones, `...` matching any run of lines?
fn lines_match(expected: &[String], lines: &[&str]) -> bool {
    match expected.split_first() {
        None => lines.is_empty(),
        Some((e, rest)) if e == "..." => {
            (0..=lines.len()).any(|skip| lines_match(rest, &lines[skip..]))
        }
        Some((e, rest)) => {
            !lines.is_empty() && line_matches(e, lines[0]) && lines_match(rest, &lines[1..])
        }
    }
}

/// A scratch directory for one file's examples, with the repository's assets in it.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "bouncemap-docs-{}-{}",
        std::process::id(),
        name.replace('/', "-")
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(root().join("assets"), dir.join("assets")).unwrap();
    dir
}

/// Run every transcript of `file` (relative to the repository); all failures at once.
fn check(file: &str) {
    let text = std::fs::read_to_string(root().join(file)).unwrap();
    let examples = examples(&text);
    if examples.is_empty() {
        return;
    }
    let bin = Path::new(env!("CARGO_BIN_EXE_bouncemap"));
    let path = format!(
        "{}:{}",
        bin.parent().unwrap().display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let dir = scratch(file);
    let mut failures = Vec::new();
    for ex in &examples {
        let out = Command::new("sh")
            .arg("-c")
            .arg(&ex.command)
            .current_dir(&dir)
            .env("PATH", &path)
            .env("NO_COLOR", "1")
            .env_remove("BOUNCEMAP_CONFIG")
            .output()
            .unwrap();
        let status = out.status.code().unwrap_or(-1);
        let printed = format!(
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        let lines: Vec<&str> = printed.lines().collect();
        let output_ok = ex.expected.is_empty() || lines_match(&ex.expected, &lines);
        if status != ex.status || !output_ok {
            failures.push(format!(
                "{file}:{}: $ {}\n  exit status {status} (expected {})\n  printed:\n{}\n  expected:\n{}",
                ex.line,
                ex.command,
                ex.status,
                indent(&printed),
                indent(&ex.expected.join("\n")),
            ));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    assert!(failures.is_empty(), "\n{}", failures.join("\n\n"));
}

fn indent(s: &str) -> String {
    s.lines()
        .map(|l| format!("    {l}"))
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn the_matcher_takes_wildcards_and_rejects_differences() {
    let e = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    assert!(lines_match(&e(&["a [..] c", "..."]), &["a b c", "x", "y"]));
    assert!(lines_match(&e(&["...", "z"]), &["x", "y", "z"]));
    assert!(!lines_match(&e(&["a [..] c"]), &["a b d"]));
    assert!(!lines_match(&e(&["a"]), &["a", "b"]));
    assert!(!lines_match(&e(&["a", "b"]), &["a"]));
    assert!(line_matches("[..]", ""));
    assert!(!line_matches("ab[..]ba", "aba"));
    let ex = examples("```console\n$ true\nout\n[exit 3]\n```\n```sh\n$ no\n```\n");
    assert_eq!(ex.len(), 1);
    assert_eq!((ex[0].line, ex[0].status), (2, 3));
    assert_eq!(ex[0].expected, ["out"]);
}

/// The README and every page in `docs/`, each in its own thread.
fn documents() -> Vec<String> {
    let mut files = vec!["README.md".to_string()];
    let mut pages: Vec<String> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".md"))
        .map(|n| format!("docs/{n}"))
        .collect();
    pages.sort();
    files.extend(pages);
    files
}

#[test]
fn every_example_in_the_documents_runs_and_prints_what_they_say() {
    let results: Vec<(String, std::thread::Result<()>)> = std::thread::scope(|s| {
        let handles: Vec<_> = documents()
            .into_iter()
            .map(|f| {
                let name = f.clone();
                (name, s.spawn(move || check(&f)))
            })
            .collect();
        handles.into_iter().map(|(n, h)| (n, h.join())).collect()
    });
    let failed: Vec<&String> = results
        .iter()
        .filter(|(_, r)| r.is_err())
        .map(|(n, _)| n)
        .collect();
    assert!(
        failed.is_empty(),
        "examples failed in {failed:?} (details above)"
    );
}
