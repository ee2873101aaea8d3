//! Scratch directories for tests that write files: one per test and process, empty at
//! the start, and paths as the command-line arguments they become. The first one made
//! in a run also removes what earlier runs of the tests left in the system's temporary
//! directory (every `bouncemap-…-PID` whose process is gone), so the scratch space of
//! at most one run is kept.

use std::path::{Path, PathBuf};

/// An empty directory `bouncemap-{group}-{name}-{pid}` in the system's temporary
/// directory (whatever an earlier run left there removed); `group` keeps the test
/// modules' names apart.
pub(crate) fn dir(group: &str, name: &str) -> PathBuf {
    static SWEPT: std::sync::Once = std::sync::Once::new();
    SWEPT.call_once(sweep_earlier_runs);
    let d = std::env::temp_dir().join(format!("bouncemap-{group}-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Remove every `bouncemap-…-PID` entry of the temporary directory whose process no
/// longer runs (where that can be told: on Linux, by /proc). Entries of a live process,
/// this run's or another's, and every other name are left alone.
fn sweep_earlier_runs() {
    let proc = Path::new("/proc");
    if !proc.join("self").exists() {
        return;
    }
    let Ok(entries) = std::fs::read_dir(std::env::temp_dir()) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(pid) = name
            .to_str()
            .and_then(|n| n.strip_prefix("bouncemap-"))
            .and_then(|n| n.rsplit_once('-'))
            .and_then(|(_, pid)| pid.parse::<u32>().ok())
        else {
            continue;
        };
        if pid == std::process::id() || proc.join(pid.to_string()).exists() {
            continue;
        }
        let path = entry.path();
        let _ = if path.is_dir() {
            std::fs::remove_dir_all(&path)
        } else {
            std::fs::remove_file(&path)
        };
    }
}

/// A path as an argument (test paths are UTF-8).
pub(crate) fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}
