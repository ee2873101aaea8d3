//! Parts of one continuation joined into the whole ([`Continuation::join`]), and a
//! part rebuilt from what was kept of it ([`Continuation::from_parts`]).
//!
//! The α values run one after another, each seeded from the one before, so a window
//! split into parts is not the sum of independent pieces: every part after the first
//! starts one α value early, at the last value of the part before it, computed there
//! afresh (unseeded). At that value both parts have a picture of the same grid of
//! starts, so their attractors are matched at distance ≈ 0 (the point sets of one
//! attractor at one α), and the later part's tracks are carried on by the earlier
//! part's. The joined continuation keeps the earlier part's (seeded) picture there.
//!
//! What a join cannot reproduce of one run over the whole window: an attractor that
//! only the seeds found at the joining value (basin fraction 0 there) is not carried
//! into the later part, and a track that only the later part's picture holds at the
//! joining value starts without a birth. [`Join`] counts both, and the largest
//! difference of basin fraction between the two pictures, so that the join says how
//! well it held.

use super::matching::match_point_sets;
use super::{Continuation, GlobalSpec, Member, Step, Track};
use crate::attractors::global::{Change, ChangeKind};

/// How two parts were joined, at the α value both computed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Join {
    /// The α value both computed (the last of the earlier part, the first of the later).
    pub alpha: f64,
    /// Its place in the joined continuation's steps.
    pub step: usize,
    /// Attractors of the two pictures matched to each other.
    pub matched: usize,
    /// Attractors only the earlier part's picture holds there (found by its seeds).
    pub only_before: usize,
    /// Attractors only the later part's picture holds there.
    pub only_after: usize,
    /// The largest difference of basin fraction between the two pictures: between
    /// matched attractors, the fraction of an unmatched one, and of the not-settled
    /// starts. 0 where the two pictures count the same starts on every attractor.
    pub fraction_difference: f64,
}

impl Continuation {
    /// A part of the continuation of `spec` over the α values `values`, rebuilt from
    /// its steps, changes and tracks (as a part file keeps them), every one checked
    /// against the others and against `spec`: refused with the reason when they do not
    /// make a whole part.
    pub fn from_parts(
        spec: GlobalSpec,
        values: std::ops::Range<usize>,
        steps: Vec<Step>,
        changes: Vec<Change>,
        tracks: Vec<Track>,
    ) -> Result<Continuation, String> {
        let mut cont = Continuation::part(spec, values.clone()).map_err(|e| e.to_string())?;
        if steps.len() != values.len() {
            return Err(format!(
                "{} α values, but its range {}..{} has {}",
                steps.len(),
                values.start,
                values.end,
                values.len()
            ));
        }
        let grid = cont.spec.starts();
        for (i, s) in steps.iter().enumerate() {
            let index = values.start + i;
            let at = format!("α value {} ({})", index + 1, s.alpha);
            if s.alpha.to_bits() != cont.spec.alpha(index).to_bits() {
                return Err(format!(
                    "{at}: not value {} of the window, {}",
                    index + 1,
                    cont.spec.alpha(index)
                ));
            }
            let counted: usize = s.members.iter().map(|m| m.starts).sum();
            if s.starts != grid || counted.checked_add(s.not_settled) != Some(grid) {
                return Err(format!(
                    "{at}: its starts ({counted} on attractors, {} not settled) are not the grid's {grid}",
                    s.not_settled
                ));
            }
            for (k, m) in s.members.iter().enumerate() {
                if m.track >= tracks.len() || (k > 0 && s.members[k - 1].track >= m.track) {
                    return Err(format!(
                        "{at}: attractor {} is not one of {} in order",
                        m.track + 1,
                        tracks.len()
                    ));
                }
                if m.fraction != m.starts as f64 / grid as f64 {
                    return Err(format!(
                        "{at}: attractor {}'s fraction {} is not its {} starts of {grid}",
                        m.track + 1,
                        m.fraction,
                        m.starts
                    ));
                }
            }
        }
        for (id, t) in tracks.iter().enumerate() {
            let seen = seen_at(&steps, id);
            if t.id != id || seen != Some((t.first, t.last)) {
                return Err(format!(
                    "attractor {}: its α values do not match where it is seen",
                    id + 1
                ));
            }
        }
        for (k, c) in changes.iter().enumerate() {
            let into = match c.what {
                ChangeKind::Death { into } => into,
                _ => None,
            };
            if c.step == 0
                || c.step >= steps.len()
                || c.track >= tracks.len()
                || into.is_some_and(|t| t >= tracks.len())
                || (k > 0 && changes[k - 1].step > c.step)
            {
                return Err(format!(
                    "change {} ({} of attractor {}) is not between two of its α values in order",
                    k + 1,
                    c.what.name(),
                    c.track + 1
                ));
            }
        }
        cont.steps = steps;
        cont.changes = changes;
        cont.tracks = tracks;
        Ok(cont)
    }

    /// Join `later`, the part that starts at this part's last α value, to this one:
    /// the continuation over both, and how the join held ([`Join`]). Refused (with the
    /// reason) unless both are complete parts of one specification and overlap in
    /// exactly that one value.
    pub fn join(mut self, later: Continuation) -> Result<(Continuation, Join), String> {
        if self.spec != later.spec {
            return Err("the parts are of different continuations".into());
        }
        if !self.complete() || !later.complete() {
            return Err("a part is not complete".into());
        }
        if later.from + 1 != self.to {
            return Err(format!(
                "the parts do not meet at one α value: one ends at value {}, the next starts at value {} (valid: at value {})",
                self.to,
                later.from + 1,
                self.to
            ));
        }
        let offset = self.steps.len() - 1;
        let before = &self.steps[offset];
        let after = &later.steps[0];
        let sets =
            |ms: &[Member]| -> Vec<_> { ms.iter().map(|m| (m.kind, m.points.clone())).collect() };
        let pairs = match_point_sets(&sets(&before.members), &sets(&after.members));
        let mut difference = (before.not_settled_fraction() - after.not_settled_fraction()).abs();
        for (b, m) in before.members.iter().enumerate() {
            match pairs.iter().find(|p| p.0 == b) {
                Some(&(_, a)) => {
                    difference = difference.max((m.fraction - after.members[a].fraction).abs())
                }
                None => difference = difference.max(m.fraction),
            }
        }
        for (a, m) in after.members.iter().enumerate() {
            if pairs.iter().all(|p| p.1 != a) {
                difference = difference.max(m.fraction);
            }
        }
        let join = Join {
            alpha: before.alpha,
            step: offset,
            matched: pairs.len(),
            only_before: before.members.len() - pairs.len(),
            only_after: after.members.len() - pairs.len(),
            fraction_difference: difference,
        };
        // The later part's tracks: carried on by the earlier part's where matched,
        // numbered after them otherwise (in the later part's order of appearance).
        let mut map: Vec<usize> = vec![usize::MAX; later.tracks.len()];
        for &(b, a) in &pairs {
            map[after.members[a].track] = before.members[b].track;
        }
        let mut next = self.tracks.len();
        for m in map.iter_mut().filter(|m| **m == usize::MAX) {
            *m = next;
            next += 1;
        }
        let Continuation {
            to,
            steps,
            changes,
            previous,
            ..
        } = later;
        for mut s in steps.into_iter().skip(1) {
            for m in &mut s.members {
                m.track = map[m.track];
            }
            s.members.sort_by_key(|m| m.track);
            self.steps.push(s);
        }
        for mut c in changes {
            c.step += offset;
            c.track = map[c.track];
            if let ChangeKind::Death { into: Some(t) } = &mut c.what {
                *t = map[*t];
            }
            self.changes.push(c);
        }
        self.previous = previous.map(|mut p| {
            for t in &mut p.tracks {
                *t = map[*t];
            }
            p
        });
        self.to = to;
        self.renumber(next);
        Ok((self, join))
    }

    /// Number the tracks (of provisional ids below `count`) in order of appearance,
    /// dropping any seen at no α value, and set where each is seen.
    fn renumber(&mut self, count: usize) {
        let mut order: Vec<(usize, usize)> = (0..count)
            .filter_map(|id| seen_at(&self.steps, id).map(|(first, _)| (first, id)))
            .collect();
        order.sort_unstable();
        let mut map = vec![usize::MAX; count];
        for (new, &(_, id)) in order.iter().enumerate() {
            map[id] = new;
        }
        for s in &mut self.steps {
            for m in &mut s.members {
                m.track = map[m.track];
            }
            s.members.sort_by_key(|m| m.track);
        }
        // A change of a track seen nowhere (the death, just after the joining value,
        // of an attractor only the later part's picture held there) goes with it.
        self.changes.retain(|c| map[c.track] != usize::MAX);
        for c in &mut self.changes {
            c.track = map[c.track];
            if let ChangeKind::Death { into: Some(t) } = &mut c.what {
                *t = map[*t];
            }
        }
        if let Some(p) = &mut self.previous {
            for t in &mut p.tracks {
                *t = map[*t];
            }
        }
        self.tracks = (0..order.len())
            .map(|id| {
                let (first, last) = seen_at(&self.steps, id).expect("seen");
                Track { id, first, last }
            })
            .collect();
    }
}

/// The first and last step where track `id` has a member.
fn seen_at(steps: &[Step], id: usize) -> Option<(usize, usize)> {
    let holds = |s: &Step| s.members.iter().any(|m| m.track == id);
    let first = steps.iter().position(holds)?;
    let last = steps.iter().rposition(holds)?;
    Some((first, last))
}
