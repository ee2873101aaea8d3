//! `--resume` for the commands that write part files (`sweep`, `plane`, `attractors`): a part that is
//! already there, complete and verified (checked as `merge` checks a part), of this run's
//! layout, tool, specification and shard, is left as it is and nothing is computed. A
//! missing file, or one that carries this run's provenance but was cut off or damaged,
//! is computed (stderr says why); any other regular file (not written by this tool,
//! another run's part, another format) is refused and left as it is: `--resume`
//! replaces only this run's own output. A path that is not a regular file (a directory,
//! a device) is left to the output's own rules.

use crate::config::files::{open_existing_output, read_again, LARGE_FILE};
use crate::config::run::Job;
use crate::config::InputError;
use crate::output::attractors_file::{
    opening, read_part as read_attractors_part, AttractorsHeader, ATTRACTORS_PART,
};
use crate::output::part_file::{
    differing_setting, opens_as, read_part, shard_name, spec_text, FileKind, Layout, TOOL,
};
use crate::output::to_stderr;
use bouncemap_engine::attractors::global::GlobalSpec;
use bouncemap_engine::jobs::grid::Shard;
use std::path::Path;

/// With `--resume` (in `job`): whether `--out` already holds this run's part (kind
/// `K`, settings `header`, shard `shard`, in the job's layout), so the run can end
/// at once. Says on stderr what it found. `--resume` needs `--out` and a format whose
/// files can be verified (csv or json).
pub fn already_written<K: FileKind>(
    job: &Job,
    header: &K::Header,
    shard: Shard,
) -> Result<bool, InputError> {
    if !job.resume {
        return Ok(false);
    }
    let layout = job.layout.ok_or_else(|| {
        InputError(
            "--resume with --format braille: valid with --format csv or json, whose files can be verified".into(),
        )
    })?;
    let out = job.out.as_deref().ok_or_else(|| {
        InputError(
            "--resume without --out: valid with --out FILE, the file to check and write".into(),
        )
    })?;
    let path = Path::new(out);
    match check::<K>(path, layout, header, shard) {
        Ok(done) => {
            to_stderr(&format!(
                "bouncemap: --resume: {done}: nothing to compute\n"
            ));
            Ok(true)
        }
        // Not there, or not a regular file (a directory, a device: the output's own
        // rules decide), or this run's own part damaged: computed.
        Err(why) if !regular(path) || own_output::<K>(path, layout, header, shard) => {
            // A path the output cannot be written to (a directory, a FIFO nobody reads)
            // is refused now, before saying it will be computed.
            if std::fs::symlink_metadata(path).is_ok() && !regular(path) {
                drop(
                    crate::output::sink::AtomicFile::create(path)
                        .map_err(|e| InputError(format!("--out: {e}")))?,
                );
            }
            to_stderr(&format!("bouncemap: --resume: {why}; computing it\n"));
            Ok(false)
        }
        Err(why) => Err(InputError(format!(
            "--resume: {why}, and it is not this run's output, so it is left as it is: valid an --out FILE that is missing or holds this part of this run"
        ))),
    }
}

/// Whether `path` is a regular file (through a symlink).
fn regular(path: &Path) -> bool {
    std::fs::metadata(path).is_ok_and(|m| m.is_file())
}

/// Whether the file at `path` opens with this run's provenance ([`opens_as`]): a part of
/// this run, maybe cut off or damaged, which the run may replace.
fn own_output<K: FileKind>(path: &Path, layout: Layout, header: &K::Header, shard: Shard) -> bool {
    open_existing_output(path, "the existing file", LARGE_FILE)
        .is_ok_and(|input| opens_as::<K>(input, layout, header, &shard_name(shard)))
}

/// Whether `path` already holds the part of kind `K` with settings `header` and shard
/// `shard` that this run would write, complete and verified: read and checked as `merge`
/// checks a part (provenance, specification against its hash, every value inside the
/// shard, end line, counts, checksum), then compared with this run (layout, tool,
/// specification, shard). `Ok` says what is there; `Err` says why it must be computed.
pub fn check<K: FileKind>(
    path: &Path,
    layout: Layout,
    header: &K::Header,
    shard: Shard,
) -> Result<String, String> {
    let shown = path.display().to_string();
    if std::fs::symlink_metadata(path).is_err_and(|e| e.kind() == std::io::ErrorKind::NotFound) {
        return Err(format!("no {shown} yet"));
    }
    let mut input = open_existing_output(path, "the existing file", LARGE_FILE).map_err(|e| e.0)?;
    let mut again =
        |offset, len| read_again(path, offset, len, 1 << 16).map(|r| Box::new(r) as Box<_>);
    let part = read_part::<K, _>(&shown, &mut input, &mut again);
    // What the reader found (not UTF-8 further on, grown) is said first.
    input.finish().map_err(|e| e.0)?;
    let part = part?;
    let kind = K::KIND;
    if part.layout != layout {
        return Err(format!(
            "{shown} is a {} {kind} file and this run writes {}",
            part.layout.name(),
            layout.name()
        ));
    }
    if part.provenance.tool != TOOL {
        return Err(format!(
            "{shown} was written by {}, not by this {TOOL}",
            part.provenance.tool
        ));
    }
    if spec_text(&part.header) != spec_text(header) {
        return Err(format!(
            "{shown} holds another {kind} ({} differs from this run's)",
            differing_setting(&part.header, header)
        ));
    }
    let shard = shard_name(shard);
    if part.provenance.shard != shard {
        return Err(format!(
            "{shown} holds shard {} of this {kind}, not shard {shard}",
            part.provenance.shard
        ));
    }
    Ok(format!(
        "{shown} already holds shard {shard} of this {kind}, complete and verified ({} {})",
        part.count,
        K::UNIT
    ))
}

/// [`already_written`] for a part of `attractors` (one json document, read whole): the
/// run `header`, shard `shard`, its header made a spec by `spec_of`.
pub fn attractors_written(
    job: &Job,
    header: &AttractorsHeader,
    shard: Shard,
    spec_of: &dyn Fn(&AttractorsHeader) -> Result<GlobalSpec, String>,
) -> Result<bool, InputError> {
    if !job.resume {
        return Ok(false);
    }
    let Some(out) = job.out.as_deref() else {
        return Ok(false);
    };
    let path = Path::new(out);
    let shown = path.display().to_string();
    if std::fs::symlink_metadata(path).is_err_and(|e| e.kind() == std::io::ErrorKind::NotFound) {
        to_stderr(&format!(
            "bouncemap: --resume: no {shown} yet; computing it\n"
        ));
        return Ok(false);
    }
    if !regular(path) {
        return Ok(false);
    }
    // Read as the sweep's parts are, not noted as an input (it is this run's output).
    let mut input = open_existing_output(path, "--resume: the existing file", ATTRACTORS_PART)?;
    let mut bytes = Vec::new();
    let read = std::io::Read::read_to_end(&mut input, &mut bytes);
    input.finish()?;
    read.map_err(|e| InputError(format!("--resume: {shown}: cannot read: {e}")))?;
    let text = String::from_utf8_lossy(&bytes);
    let ours = text.starts_with(&opening(header, shard));
    let why = match read_attractors_part(&text, spec_of) {
        Ok(p) if p.header == *header && p.shard == shard => {
            to_stderr(&format!(
                "bouncemap: --resume: {shown} already holds shard {} of this attractors run, complete and verified ({} α values): nothing to compute\n",
                shard_name(shard),
                p.cont.steps().len()
            ));
            return Ok(true);
        }
        Ok(p) if p.header == *header => format!(
            "{shown} holds shard {} of this attractors run, not shard {}",
            shard_name(p.shard),
            shard_name(shard)
        ),
        Ok(p) => format!(
            "{shown} holds shard {} of another attractors run",
            shard_name(p.shard)
        ),
        Err(e) => format!("{shown}: {e}"),
    };
    if ours {
        to_stderr(&format!("bouncemap: --resume: {why}; computing it\n"));
        Ok(false)
    } else {
        Err(InputError(format!(
            "--resume: {why}, and it is not this run's output, so it is left as it is: valid an --out FILE that is missing or holds this part of this run"
        )))
    }
}
