//! The documents made from the code, so they cannot disagree with it: the command
//! reference and the man pages from the command-line definitions, the keys of the
//! terminal application from its key table, and the README's screenshot from a scripted
//! run of the application. `bouncemap generate-docs DIR` writes them (docs/make.sh), and
//! a test compares the checked-in copies with what this build makes.

pub mod keys;
pub mod reference;
pub mod screenshot;

use std::path::Path;

/// One generated document: its path under `docs/` and its bytes.
pub struct Document {
    pub path: String,
    pub bytes: Vec<u8>,
}

/// Every generated document but the screenshot (which runs the application's jobs).
pub fn texts() -> Vec<Document> {
    let mut docs = vec![
        Document {
            path: "reference.md".into(),
            bytes: reference::markdown().into_bytes(),
        },
        Document {
            path: "keys.md".into(),
            bytes: keys::markdown().into_bytes(),
        },
    ];
    docs.extend(reference::man_pages());
    docs
}

/// Write every generated document (the screenshot too) under `dir`, each atomically.
pub fn write_all(dir: &Path) -> anyhow::Result<Vec<String>> {
    let mut docs = texts();
    docs.push(Document {
        path: screenshot::PATH.into(),
        bytes: screenshot::png(&screenshot::Script::readme())?,
    });
    let mut written = Vec::new();
    for d in docs {
        let path = dir.join(&d.path);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent)?;
        }
        let tmp = path.with_extension("tmp~");
        std::fs::write(&tmp, &d.bytes)?;
        std::fs::rename(&tmp, &path)?;
        written.push(d.path);
    }
    Ok(written)
}
