//! The documents made from the code are the ones checked in: the command reference,
//! the man pages, the keys, and the README's screenshot (made by running the
//! application's real jobs for a scripted sequence of keys, compared byte for byte).
//! `BOUNCEMAP_BLESS=1 cargo test generated` rewrites them (as `bouncemap generate-docs
//! docs` does).

use bouncemap::docs::{self, screenshot};
use std::path::PathBuf;

fn docs_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("docs")
}

fn bless() -> bool {
    std::env::var_os("BOUNCEMAP_BLESS").is_some_and(|v| v == "1")
}

/// Compare (or with BOUNCEMAP_BLESS=1 write) one document.
fn check(path: &str, bytes: &[u8]) -> Option<String> {
    let file = docs_dir().join(path);
    if bless() {
        std::fs::create_dir_all(file.parent().unwrap()).unwrap();
        std::fs::write(&file, bytes).unwrap();
        return None;
    }
    match std::fs::read(&file) {
        Ok(old) if old == bytes => None,
        Ok(_) => Some(format!("docs/{path} differs from what this build makes")),
        Err(e) => Some(format!("docs/{path}: {e}")),
    }
}

#[test]
fn the_reference_man_pages_and_keys_are_generated_from_this_build() {
    let texts = docs::texts();
    let mut stale: Vec<String> = texts
        .iter()
        .filter_map(|d| check(&d.path, &d.bytes))
        .collect();
    // No page left over from a command that is gone.
    let made: Vec<&str> = texts.iter().map(|d| d.path.as_str()).collect();
    for e in std::fs::read_dir(docs_dir().join("man")).unwrap() {
        let name = format!("man/{}", e.unwrap().file_name().to_string_lossy());
        if !made.contains(&name.as_str()) {
            stale.push(format!("docs/{name} is not made by this build"));
        }
    }
    assert!(
        stale.is_empty(),
        "{}; regenerate with BOUNCEMAP_BLESS=1 cargo test generated",
        stale.join("; ")
    );
}

#[test]
fn the_reference_lists_every_command_and_flag() {
    // Independent of the generator: every subcommand name `--help` prints, and every
    // long flag of `orbit --help`, appear in the reference.
    let reference = String::from_utf8(
        docs::texts()
            .into_iter()
            .find(|d| d.path == "reference.md")
            .unwrap()
            .bytes,
    )
    .unwrap();
    let help = super::cli::ok(&["--help"]);
    let commands: Vec<&str> = help
        .lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|c| *c != "help")
        .collect();
    assert!(commands.len() >= 14, "{commands:?}");
    for c in commands {
        assert!(reference.contains(&format!("`bouncemap {c}`")), "{c}");
    }
    for flag in super::cli::ok(&["orbit", "--help"])
        .split_whitespace()
        .filter(|w| w.starts_with("--"))
    {
        assert!(reference.contains(flag), "{flag}");
    }
}

#[test]
fn the_screenshot_is_of_this_build() {
    let png = screenshot::png(&screenshot::Script::readme()).unwrap();
    if let Some(problem) = check(screenshot::PATH, &png) {
        panic!("{problem}; regenerate with docs/make.sh or BOUNCEMAP_BLESS=1 cargo test generated");
    }
}

#[test]
fn completions_name_every_command() {
    for shell in ["bash", "zsh", "fish", "elvish", "powershell"] {
        let out = super::cli::ok(&["completions", shell]);
        for c in ["orbit", "cascade", "plane", "figure", "completions"] {
            assert!(out.contains(c), "{shell}: {c}");
        }
    }
    let (code, _, err) = super::cli::run(&["completions", "tcsh"]);
    assert_eq!(code, 2);
    assert_eq!(err.lines().count(), 1, "{err}");
}
