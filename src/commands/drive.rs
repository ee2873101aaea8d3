//! One engine job driven to its end on the calling thread, with progress on stderr:
//! the loop every headless computation runs (sweeps, basin pictures, planes, the
//! figures' sweeps), whatever its job and the batches it streams; and [`fill`], that
//! loop for a picture the job fills in chunk by chunk.

use super::progress::Progress;
use crate::output::sink::check_stdout;
use bouncemap_engine::jobs::picture::{Cells, Chunk, Filled};
use bouncemap_engine::jobs::{Batch, Handle, Progress as JobProgress, Summary};
use std::sync::mpsc::RecvTimeoutError;
use std::time::{Duration, Instant};

/// How long the loop waits for a batch before it redraws the progress anyway.
const TICK: Duration = Duration::from_millis(200);

/// Drive the job behind `handle` to its end: every batch of the current generation goes
/// to `each` as it arrives (with the handle, to acknowledge what was used), and
/// `progress` is brought up to date between batches, at least every [`TICK`]. An error
/// from `each` ends the drive at once (dropping the handle stops the job), and so does a
/// standard output whose reader has gone, when the results go there (a quiet end, see
/// [`check_stdout`]). Returns the job's summary; whether the results are complete is the
/// caller's to check.
pub fn drive_job<T>(
    handle: Handle<T>,
    mut progress: Progress,
    each: impl FnMut(&Handle<T>, Batch<T>) -> anyhow::Result<()>,
) -> anyhow::Result<Summary> {
    let summary = drive_reporting(handle, &mut |p| progress.update(p), each)?;
    progress.finish(&summary.progress);
    Ok(summary)
}

/// [`drive_job`]'s loop with the job's progress handed to `report` between batches,
/// for a caller whose progress spans several jobs (and who finishes it itself).
pub fn drive_reporting<T>(
    handle: Handle<T>,
    report: &mut dyn FnMut(&JobProgress),
    mut each: impl FnMut(&Handle<T>, Batch<T>) -> anyhow::Result<()>,
) -> anyhow::Result<Summary> {
    let mut checked = Instant::now();
    loop {
        match handle.receiver().recv_timeout(TICK) {
            Ok(b) if handle.is_current(&b) => each(&handle, b)?,
            Ok(_) | Err(RecvTimeoutError::Timeout) => {}
            Err(RecvTimeoutError::Disconnected) => break,
        }
        if checked.elapsed() >= TICK {
            checked = Instant::now();
            check_stdout()?;
        }
        report(&handle.progress());
    }
    Ok(handle.wait())
}

/// Drive the job behind `handle` to its end ([`drive_job`]), filling `picture` with its
/// chunks. A picture left incomplete is an error: "`what` stopped after N of M
/// (units)".
pub fn fill<P: Filled>(
    handle: Handle<Chunk<<P::Cells as Cells>::Cell>>,
    progress: Progress,
    mut picture: P,
    what: &str,
) -> anyhow::Result<P> {
    let unit = progress.unit();
    let summary = drive_job(handle, progress, |_, b| {
        picture.absorb(b.data);
        Ok(())
    })?;
    let total = summary.progress.total;
    if picture.covered() < total {
        anyhow::bail!(
            "{what} stopped after {} of {total} {unit}",
            picture.covered()
        );
    }
    Ok(picture)
}
