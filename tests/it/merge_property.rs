//! `merge` either produces exactly the unsharded file (its provenance says `merged N/N`
//! where the unsharded one says `1/1`) or refuses with status 2, whatever happened to
//! the parts: truncated, dropped, duplicated, mixed with a part of another sweep, or a
//! byte flipped. Random small sweeps through the real binary;
//! `BOUNCEMAP_MERGE_CASES=N` for a longer search.

use proptest::prelude::*;
use std::path::{Path, PathBuf};
use std::process::Command;

fn bouncemap(args: &[String]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_bouncemap"))
        .args(args)
        .output()
        .unwrap()
}

#[derive(Clone, Debug)]
enum Damage {
    None,
    Truncate { part: usize, frac: f64 },
    Drop(usize),
    Duplicate(usize),
    Foreign(usize),
    Flip { part: usize, frac: f64 },
}

fn damage() -> impl Strategy<Value = Damage> {
    prop_oneof![
        Just(Damage::None),
        (0usize..8, 0.0..1.0).prop_map(|(part, frac)| Damage::Truncate { part, frac }),
        (0usize..8).prop_map(Damage::Drop),
        (0usize..8).prop_map(Damage::Duplicate),
        (0usize..8).prop_map(Damage::Foreign),
        (0usize..8, 0.0..1.0).prop_map(|(part, frac)| Damage::Flip { part, frac }),
    ]
}

/// Shards 1..=n (and the whole) of one sweep into `dir`; `transient` tells sweeps apart.
fn sweep(
    dir: &Path,
    tag: &str,
    steps: usize,
    n: usize,
    warm: bool,
    json: bool,
    transient: u64,
) -> (Vec<PathBuf>, PathBuf) {
    let ext = if json { "json" } else { "csv" };
    let base = |out: &Path, shard: Option<usize>| {
        let mut a: Vec<String> = [
            "sweep",
            "--alpha",
            "0.45..0.62",
            "--steps",
            &steps.to_string(),
            "--transient",
            &transient.to_string(),
            "--keep",
            "3",
            "--format",
            ext,
            "--out",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        a.push(out.to_str().unwrap().to_string());
        if warm {
            a.push("--warm".into());
        }
        if let Some(i) = shard {
            a.push("--shard".into());
            a.push(format!("{i}/{n}"));
        }
        a
    };
    let parts: Vec<PathBuf> = (1..=n)
        .map(|i| {
            let p = dir.join(format!("{tag}{i}.{ext}"));
            assert!(bouncemap(&base(&p, Some(i))).status.success());
            p
        })
        .collect();
    let whole = dir.join(format!("{tag}whole.{ext}"));
    assert!(bouncemap(&base(&whole, None)).status.success());
    (parts, whole)
}

/// The text with the provenance's shard taken out (the one thing a merge changes).
fn without_shard(t: &str) -> String {
    t.replace("# shard merged ", "# shard ")
        .lines()
        .filter(|l| !l.starts_with("# shard "))
        .map(|l| match l.find("\"shard\":\"") {
            Some(i) => {
                let end = l[i + 9..].find('"').unwrap() + i + 10;
                format!("{}{}", &l[..i], &l[end..])
            }
            None => l.to_string(),
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn cases() -> u32 {
    std::env::var("BOUNCEMAP_MERGE_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(24)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases()))]

    #[test]
    fn merge_gives_the_unsharded_file_or_refuses(
        steps in 1usize..40,
        n in 1usize..5,
        warm in any::<bool>(),
        json in any::<bool>(),
        damage in damage(),
    ) {
        let dir = std::env::temp_dir().join(format!("bouncemap-mp-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let (mut parts, whole) = sweep(&dir, "a", steps, n, warm, json, 1500);
        let k = |i: usize| i % n;
        match &damage {
            Damage::None => {}
            Damage::Truncate { part, frac } => {
                let p = &parts[k(*part)];
                let text = std::fs::read(p).unwrap();
                let cut = ((text.len() as f64) * frac) as usize;
                std::fs::write(p, &text[..cut.min(text.len() - 1)]).unwrap();
            }
            Damage::Drop(i) => {
                parts.remove(k(*i));
            }
            Damage::Duplicate(i) => {
                let p = parts[k(*i)].clone();
                parts.push(p);
            }
            // With one shard a part of another sweep is that sweep, whole: only mix parts.
            Damage::Foreign(i) if n > 1 => {
                let (other, _) = sweep(&dir, "b", steps, n, warm, json, 1700);
                parts[k(*i)] = other[k(*i)].clone();
            }
            Damage::Foreign(_) => {}
            Damage::Flip { part, frac } => {
                let p = &parts[k(*part)];
                let mut text = std::fs::read(p).unwrap();
                let at = ((text.len() as f64) * frac) as usize % text.len();
                text[at] = if text[at] == b'1' { b'2' } else { b'1' };
                std::fs::write(p, text).unwrap();
            }
        }
        let mut args = vec!["merge".to_string()];
        args.extend(parts.iter().map(|p| p.to_str().unwrap().to_string()));
        let out = bouncemap(&args);
        let err = String::from_utf8_lossy(&out.stderr).into_owned();
        match out.status.code() {
            Some(0) => {
                let merged = String::from_utf8(out.stdout).unwrap();
                let expected = std::fs::read_to_string(&whole).unwrap();
                prop_assert_eq!(without_shard(&merged), without_shard(&expected), "{:?}", damage);
            }
            Some(2) => {
                prop_assert_eq!(err.trim_end().lines().count(), 1, "{}", err);
                prop_assert!(!err.contains("panicked"), "{}", err);
            }
            other => prop_assert!(false, "status {:?}: {}", other, err),
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
