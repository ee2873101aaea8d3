//! Hostile case 10: `merge` streams. Parts of many MB (they may be up to 8 GiB each) are
//! joined holding a value per part and the buffers, not the parts: its peak memory (read
//! as it runs) stays a small fraction of their size (it was three times their size), and
//! what it writes is still the unsharded run's file but for the shard line.

use crate::scratch::s;
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Duration;

fn dir(name: &str) -> PathBuf {
    crate::scratch::dir("merge", name)
}

/// Run the binary to its end: its exit code, stderr and peak memory in bytes (its own
/// high-water mark, as the hostile tests read it).
fn run(args: &[&str]) -> (Option<i32>, String, u64) {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_bouncemap"));
    cmd.args(args);
    let r = crate::hostile::run_to(cmd, Duration::from_secs(300), Stdio::null());
    (r.code, r.err, r.max_rss)
}

/// A file around its shard (the value of its `# shard` line, or of its json
/// provenance's `shard`): the bytes before it, and where the bytes after it start.
fn around_shard(p: &Path) -> (Vec<u8>, u64) {
    let mut head = Vec::new();
    std::io::Read::read_to_end(
        &mut std::io::Read::take(std::fs::File::open(p).unwrap(), 4096),
        &mut head,
    )
    .unwrap();
    let find = |hay: &[u8], needle: &[u8]| hay.windows(needle.len()).position(|w| w == needle);
    for (open, close) in [(&b"\n# shard "[..], &b"\n"[..]), (b"\"shard\":\"", b"\"")] {
        if let Some(i) = find(&head, open) {
            let from = i + open.len();
            let to = from + find(&head[from..], close).unwrap();
            head.truncate(from);
            return (head, to as u64);
        }
    }
    panic!("{}: no shard in its head", p.display());
}

/// Whether two part files are the same but for their shards, read in pieces (they are
/// hundreds of MB).
fn same_but_shard(a: &Path, b: &Path) -> bool {
    let ((head_a, rest_a), (head_b, rest_b)) = (around_shard(a), around_shard(b));
    let open = |p: &Path, at: u64| {
        let mut f = std::fs::File::open(p).unwrap();
        std::io::Seek::seek(&mut f, std::io::SeekFrom::Start(at)).unwrap();
        BufReader::with_capacity(1 << 16, f)
    };
    let (mut ra, mut rb) = (open(a, rest_a), open(b, rest_b));
    if head_a != head_b {
        return false;
    }
    loop {
        let (x, y) = (ra.fill_buf().unwrap(), rb.fill_buf().unwrap());
        let n = x.len().min(y.len());
        if x[..n] != y[..n] {
            return false;
        }
        if n == 0 {
            return x.is_empty() && y.is_empty();
        }
        ra.consume(n);
        rb.consume(n);
    }
}

#[test]
fn merge_memory() {
    const MIB: u64 = 1 << 20;
    // 64 values of 20 000 points each, in two shards: 640 000 rows a part, about
    // 50 MiB (csv) and 40 MiB (json). A merge that held them peaked at three times that.
    let sweep = [
        "sweep",
        "--table",
        "fd:1",
        "--alpha",
        "0.57..0.58",
        "--steps",
        "64",
        "--transient",
        "3e4",
        "--keep",
        "2e4",
        "--no-early-stop",
    ];
    for format in ["csv", "json"] {
        let d = dir(format);
        let file = |name: &str| d.join(format!("{name}.{format}"));
        let mut parts = 0;
        for (name, shard) in [("a", Some("1/2")), ("b", Some("2/2")), ("whole", None)] {
            let out = file(name);
            let mut args = sweep.to_vec();
            args.extend(["--format", format, "--out", s(&out)]);
            if let Some(shard) = shard {
                args.extend(["--shard", shard]);
            }
            let (code, err, _) = run(&args);
            assert_eq!(code, Some(0), "{err}");
            if shard.is_some() {
                parts += std::fs::metadata(&out).unwrap().len();
            }
        }
        assert!(parts > 80 * MIB, "{format}: parts of {} MiB", parts / MIB);
        let merged = file("merged");
        let (code, err, rss) = run(&["merge", s(&file("a")), s(&file("b")), "--out", s(&merged)]);
        assert_eq!(code, Some(0), "{err}");
        assert!(
            rss < 24 * MIB,
            "{format}: merge of {} MiB of parts peaked at {} MiB",
            parts / MIB,
            rss / MIB
        );
        assert!(
            same_but_shard(&merged, &file("whole")),
            "{format}: the merge differs from the unsharded run"
        );
        std::fs::remove_dir_all(&d).unwrap();
    }
}
