//! A part's values read again from its file, in order, one at a time (for `merge` to
//! write them), each checked against what was read the first time.

use super::read::row_of;
use super::stream::{Hashed, JsonItems};
use super::*;

impl<K: FileKind> Part<K> {
    /// Its values read again from `body` (its file from [`Body::offset`], [`Body::len`]
    /// bytes), in order, one at a time ([`Reread`]). Anything that differs from what was
    /// checked (the file changed since) is an error naming the file, and so is a
    /// checksum or a count at the end that differs.
    pub fn reread<R: BufRead>(&self, body: R) -> Reread<'_, K, R> {
        let b = &self.body;
        let source = match self.layout {
            Layout::Csv => Source::Csv(CsvSource {
                rows: csv::ReaderBuilder::new()
                    .has_headers(false)
                    .flexible(true)
                    .from_reader(Hashed::new(body, b.start, b.longest)),
                names: csv::StringRecord::from(K::field_names(&self.header)),
                record: csv::StringRecord::new(),
                ahead: None,
                index: None,
                read: 0,
            }),
            Layout::Json => Source::Json(JsonItems::new(body, b.start, b.longest)),
        };
        Reread {
            part: self,
            source,
            k: 0,
        }
    }
}

/// What a part read again hands out next: a json value whole, or the first csv row of a
/// value (the value's other rows follow from [`Reread::more`]).
pub enum Next<K: FileKind> {
    Value(K::Value),
    Row(K::Row),
}

/// A part's values read again ([`Part::reread`]): a json value at a time, or a csv row
/// at a time (a value of a sweep may have a million rows).
pub struct Reread<'a, K: FileKind, R: BufRead> {
    part: &'a Part<K>,
    source: Source<K, R>,
    /// Values begun.
    k: usize,
}

enum Source<K: FileKind, R: BufRead> {
    Csv(CsvSource<K, R>),
    Json(JsonItems<R>),
}

struct CsvSource<K: FileKind, R: BufRead> {
    rows: csv::Reader<Hashed<R>>,
    names: csv::StringRecord,
    record: csv::StringRecord,
    /// A row read past the end of a value: the next value's first.
    ahead: Option<K::Row>,
    /// The index the rows of the value being read state.
    index: Option<usize>,
    /// Rows read.
    read: usize,
}

impl<K: FileKind, R: BufRead> CsvSource<K, R> {
    /// The next row, or None at the end.
    fn row(&mut self) -> Result<Option<K::Row>, String> {
        if !self
            .rows
            .read_record(&mut self.record)
            .map_err(|e| one_line(&e.to_string()))?
        {
            return Ok(None);
        }
        self.read += 1;
        row_of(&self.record, &self.names).map(Some)
    }
}

/// A part that no longer reads as it did when checked.
fn changed(name: &str, why: &str) -> String {
    format!("{name}: changed since it was checked ({why}): valid parts left as they are until merge ends")
}

impl<K: FileKind, R: BufRead> Reread<'_, K, R> {
    /// The next value (json) or the first row of the next value (csv), with its place in
    /// the whole run; None after the last.
    pub fn next_value(&mut self) -> Result<Option<(usize, Next<K>)>, String> {
        let (part, k) = (self.part, self.k);
        let body = &part.body;
        let differs = |what: &str| Err(format!("its {what} differ from what was checked"));
        let next = match &mut self.source {
            Source::Csv(c) => {
                let row = match c.ahead.take() {
                    Some(row) => Ok(Some(row)),
                    None => c.row(),
                };
                match row {
                    Ok(Some(row)) => {
                        c.index = K::row_index(&row);
                        Ok(Some((c.index, Next::Row(row))))
                    }
                    Ok(None) if c.rows.get_ref().hash() != body.hash || c.read != body.rows => {
                        differs("rows")
                    }
                    Ok(None) if k != part.count => differs(K::UNIT),
                    other => other.map(|_| None),
                }
            }
            Source::Json(items) => match items.next_item() {
                Ok(Some((text, _))) => serde_json::from_slice::<K::Item>(text)
                    .map(|item| {
                        let v = K::from_item(item);
                        Some((K::stated_index(&v), Next::Value(v)))
                    })
                    .map_err(|e| one_line(&e.to_string())),
                Ok(None) => Ok(None),
                Err(e) => Err(one_line(&e.to_string())),
            }
            .and_then(|next| match next {
                None if items.hash() != body.hash || items.count() != part.count => {
                    differs(K::UNIT)
                }
                next => Ok(next),
            }),
        };
        match next.map_err(|e| changed(&part.name, &e))? {
            Some((stated, next)) => {
                self.k += 1;
                Ok(Some((K::place(part.shard, k, stated), next)))
            }
            None => Ok(None),
        }
    }

    /// The next csv row of the value begun last, or None when it has no more (a json
    /// value has none).
    pub fn more(&mut self) -> Result<Option<K::Row>, String> {
        let Source::Csv(c) = &mut self.source else {
            return Ok(None);
        };
        if c.ahead.is_some() {
            return Ok(None);
        }
        match c.row() {
            Ok(Some(row)) if c.index.is_some() && K::row_index(&row) == c.index => Ok(Some(row)),
            Ok(Some(row)) => {
                c.ahead = Some(row);
                Ok(None)
            }
            Ok(None) => Ok(None),
            Err(e) => Err(changed(&self.part.name, &e)),
        }
    }
}
