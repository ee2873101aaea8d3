//! Scratch directories for tests that write files: one per test and process, empty at
//! the start, and paths as the command-line arguments they become.

use std::path::{Path, PathBuf};

/// An empty directory `bouncemap-{group}-{name}-{pid}` in the system's temporary
/// directory (whatever an earlier run left there removed); `group` keeps the test
/// modules' names apart.
pub(crate) fn dir(group: &str, name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("bouncemap-{group}-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A path as an argument (test paths are UTF-8).
pub(crate) fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}
