//! What a reading of either layout keeps of a part's values as they pass: their count
//! and the first failure of their checks, a value at a time.

use super::*;

/// A part as read, and the check of its values: how many its shard has, or the first
/// failure.
pub(super) type Reading<K> = (Part<K>, Result<usize, String>);

/// The values of a part as they are read: counted, and checked in order, the first
/// failure kept (a later malformed row or a bad end line is reported before it).
pub(super) struct Tally<K: FileKind> {
    pub(super) checker: Result<K::Checker, String>,
    pub(super) failure: Option<String>,
    pub(super) count: usize,
}

impl<K: FileKind> Tally<K> {
    pub(super) fn new(header: &K::Header, shard: Option<Shard>) -> Tally<K> {
        Tally {
            checker: K::checker(header, shard),
            failure: None,
            count: 0,
        }
    }

    pub(super) fn value(&mut self, v: &K::Value) {
        self.count += 1;
        if let (Ok(c), None) = (&mut self.checker, &self.failure) {
            self.failure = K::check(c, v).err();
        }
    }

    /// How many values the shard has, or the first failure.
    pub(super) fn result(self) -> Result<usize, String> {
        let c = self.checker?;
        match self.failure {
            Some(f) => Err(f),
            None => Ok(K::expected(&c)),
        }
    }
}
